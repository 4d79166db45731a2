// Local random-phase noise in GLSL: the twin of LrpModel::evaluate_typed (model.cpp,
// evaluate.hpp, window.hpp), same lattices, same draws, same polynomial cosine (cos_turns of
// float_math.glsl) and window. Requires random.glsl and float_math.glsl, then the constants shared
// with the C++ (LRP_WINDOW_*, LRP_TURBULENCE_STREAM_BASE: Twin::kConstants in gl_twin.hpp), the
// model's constants (lrp_glsl() in gl_data.cpp writes them) and the table readers
// `vec3 lrp_frequency(uint index)` (f_x, f_y, weight) and `uvec2 lrp_substratum(int index)`
// (first, count): storage buffers in the renderer, a texture in an exported shader
// (lrp_library_source in gl_data.cpp).

// Frequency clamping, section 6.4 (clamp_weight).
float lrp_clamp_weight(float cycles) {
  return clamp((LRP_CLAMP_END - cycles) * (1.0 / (LRP_CLAMP_END - LRP_CLAMP_START)), 0.0, 1.0);
}

// The Kaiser-Bessel window at squared distance r2 in lattice units (window_from_square).
float lrp_window(float r2) {
  float t = 1.0 - r2 * (1.0 / LRP_WINDOW_RADIUS_SQUARED);
  if (t <= 0.0) return 0.0;
  float sum = LRP_WINDOW[LRP_WINDOW_TERMS - 1];
  for (int m = LRP_WINDOW_TERMS - 2; m >= 0; --m) sum = sum * t + LRP_WINDOW[m];
  return sum * t * sqrt(t);
}

// stratum_sum (evaluate.hpp): (sum_i w_i sum_j a_j cos(...), sum_i w_i^2) of random stratum s, or
// of turbulence stratum s when `turbulence`, at `u`, the position in lattice units relative to the
// lattice node `origin_node` (low 32 bits; formed on the CPU in double for the far part).
// `axis_a`, `axis_b`: the footprint's axes in exemplar pixels, used when `filtered`.
vec2 lrp_stratum_sum(bool turbulence, int s, vec2 u, uvec2 origin_node, uint stratum_seed,
                     bool filtered, vec2 axis_a, vec2 axis_b) {
  vec2 node = floor(u + 0.5);
  vec2 offset = u - node;
  float spacing = turbulence ? LRP_TURBULENCE_SPACING[s] : LRP_STRATUM_SPACING[s];
  int cosines = turbulence ? LRP_TURBULENCE_COSINES[s] : LRP_STRATUM_COSINES[s];
  int first = turbulence ? LRP_TURBULENCE_FIRST[s] : LRP_STRATUM_FIRST[s];
  float sum = 0.0;
  float window_square = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      float rx = offset.x - float(dx);
      float ry = offset.y - float(dy);
      float w = lrp_window(rx * rx + ry * ry);
      if (w <= 0.0) continue;
      float px = rx * spacing;
      float py = ry * spacing;
      uvec2 cell = origin_node + uvec2(ivec2(node) + ivec2(dx, dy));
      CounterRng rng = CounterRng(cell_key(cell.x, cell.y, stratum_seed, STREAM_PHASES), 0u);
      float local = 0.0;
      for (int j = 0; j < cosines; ++j) {
        uint draw = rng_next(rng);
        int k = first + j;
        uint high;
        uint low;
        uvec2 substratum = turbulence ? lrp_turbulence_substratum(k) : lrp_substratum(k);
        umulExtended(draw & LRP_PICK_MASK, substratum.y, high, low);
        uint pick = substratum.x + ((high << (32u - LRP_PICK_BITS)) | (low >> LRP_PICK_BITS));
        vec3 frequency =
            turbulence ? vec3(lrp_turbulence_frequency(pick), 1.0) : lrp_frequency(pick);
        float fx = frequency.x;
        float fy = frequency.y;
        float phase = float(draw >> LRP_PICK_BITS) * LRP_PHASE_STEP;
        float c = cos_turns(fx * px + fy * py + phase);
        if (filtered) {
          float along_a = abs(fx * axis_a.x + fy * axis_a.y);
          float along_b = abs(fx * axis_b.x + fy * axis_b.y);
          c *= lrp_clamp_weight(along_a > along_b ? along_a : along_b);
        }
        local += frequency.z * c;
      }
      sum += w * local;
      window_square += w * w;
    }
  }
  return vec2(sum, window_square);
}

// One random stratum's noise (equation 1 times A_S, envelope normalised when asked).
float lrp_stratum_noise(int s, vec2 u, uvec2 origin_node, uint stratum_seed, bool filtered,
                        vec2 axis_a, vec2 axis_b) {
  vec2 result = lrp_stratum_sum(false, s, u, origin_node, stratum_seed, filtered, axis_a, axis_b);
  float scale = LRP_STRATUM_AMPLITUDE[s];
  if (LRP_NORMALISE_ENVELOPE) scale *= sqrt(LRP_MEAN_ENVELOPE / result.y);
  return scale * result.x;
}

// mean + basis * noise (equation 2 in the decorrelated colour space).
vec4 lrp_colour(vec4 noise) {
  vec4 value = vec4(0.0);
  for (int c = 0; c < LRP_CHANNELS; ++c) {
    value[c] = LRP_MEAN[c];
    for (int k = 0; k < LRP_CHANNELS; ++k) value[c] += LRP_BASIS[c * LRP_CHANNELS + k] * noise[k];
  }
  return value;
}

// Section 5, the twin of structure_model.cpp: table readers `vec4 lrp_structure_cosine(int)`
// (f_x, f_y, amplitude, phase; channel-major, then block, then cosine),
// `vec2 lrp_turbulence_frequency(uint)` and `uvec2 lrp_turbulence_substratum(int)` (first, count).

// add_fixed_phase: n_R at q (exemplar pixels; the caller reduces q modulo the period, so the node
// index differs from the CPU's by a multiple of B, the same block), times `weight`, into noise.
void lrp_add_fixed_phase(vec2 q, bool filtered, vec2 axis_a, vec2 axis_b, float weight,
                         inout vec4 noise) {
  float side = LRP_STRUCTURE_SIDE;
  vec2 u = q / side - 0.5;
  vec2 node = floor(u + 0.5);
  vec2 offset = u - node;
  ivec2 cell = ivec2(node);
  vec4 sum = vec4(0.0);
  float window_sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      float rx = offset.x - float(dx);
      float ry = offset.y - float(dy);
      float w = lrp_window((rx * rx + ry * ry) * LRP_WINDOW_RADIUS_SQUARED);
      if (w <= 0.0) continue;
      float px = rx * side;
      float py = ry * side;
      // B is a power of two: & (B - 1) is the non-negative remainder, as wrap() on the CPU.
      int block = ((cell.y + dy) & (LRP_STRUCTURE_BLOCKS - 1)) * LRP_STRUCTURE_BLOCKS +
                  ((cell.x + dx) & (LRP_STRUCTURE_BLOCKS - 1));
      for (int c = 0; c < LRP_CHANNELS; ++c) {
        int base =
            (c * LRP_STRUCTURE_BLOCKS * LRP_STRUCTURE_BLOCKS + block) * LRP_STRUCTURE_COSINES;
        float local = 0.0;
        for (int j = 0; j < LRP_STRUCTURE_COSINES; ++j) {
          vec4 cosine = lrp_structure_cosine(base + j);
          float fx = cosine.x;
          float fy = cosine.y;
          float value = cosine.z * cos_turns(fx * px + fy * py + cosine.w);
          if (filtered) {
            float along_a = abs(fx * axis_a.x + fy * axis_a.y);
            float along_b = abs(fx * axis_b.x + fy * axis_b.y);
            value *= lrp_clamp_weight(along_a > along_b ? along_a : along_b);
          }
          local += value;
        }
        sum[c] += w * local;
      }
      window_sum += w;
    }
  }
  float scale = weight / window_sum;
  for (int c = 0; c < LRP_CHANNELS; ++c) noise[c] += scale * sum[c];
}

// turbulence_noise: sum_S |n_S| of turbulence stratum t's noise at `u` (lattice units relative to
// `origin_node`), on the stream `stratum_seed`.
float lrp_turbulence_stratum(int t, vec2 u, uvec2 origin_node, uint stratum_seed) {
  vec2 result = lrp_stratum_sum(true, t, u, origin_node, stratum_seed, false, vec2(0.0), vec2(0.0));
  return abs(LRP_TURBULENCE_AMPLITUDE[t] * sqrt(LRP_MEAN_ENVELOPE / result.y) * result.x);
}

// blend_weight: weight of block i + 1 against block i, a smoothstep over 1/8 of a block each side.
float lrp_blend_weight(float t) {
  float a = clamp((t - 0.5) * (0.5 / LRP_PLACEMENT_BLEND) + 0.5, 0.0, 1.0);
  return a * a * (3.0 - 2.0 * a);
}

// add_structure (structure_model.cpp) at p, a position relative to an origin whose values the
// caller forms: `structure_origin`, the origin modulo the structure period; `placement_block`
// (low 32 bits) and `placement_offset`, the placement block holding the origin and the origin's
// position from it in half periods; per turbulence stratum the node nearest the origin (low 32
// bits) and the origin's offset from it in lattice units; per axis and turbulence stratum the
// stream. Section 5.2: turbulence x + sigma n_T(x) with n_T at the undisplaced, unshifted x, then
// random placement of half-period blocks blended at their borders.
void lrp_add_structure(vec2 p, vec2 structure_origin, uvec2 placement_block, vec2 placement_offset,
                       uvec2 turbulence_node[LRP_TURBULENCE_ARRAY],
                       vec2 turbulence_offset[LRP_TURBULENCE_ARRAY],
                       uint turbulence_seed[2 * LRP_TURBULENCE_ARRAY], uint seed, bool filtered,
                       vec2 axis_a, vec2 axis_b, inout vec4 noise) {
  vec2 q = structure_origin + p;
  if (LRP_TURBULENCE > 0.0) {
    float n[2] = float[2](0.0, 0.0);
    for (int axis = 0; axis < 2; ++axis)
      for (int t = 0; t < LRP_TURBULENCE_STRATA; ++t)
        n[axis] += lrp_turbulence_stratum(t, turbulence_offset[t] + p / LRP_TURBULENCE_SPACING[t],
                                          turbulence_node[t],
                                          turbulence_seed[axis * LRP_TURBULENCE_ARRAY + t]);
    q += vec2(LRP_TURBULENCE * n[0], LRP_TURBULENCE * n[1]);
  }
  if (!LRP_PLACEMENT) {
    lrp_add_fixed_phase(q, filtered, axis_a, axis_b, 1.0, noise);
    return;
  }
  vec2 g = placement_offset + p / (0.5 * LRP_STRUCTURE_PERIOD);
  vec2 base = floor(g);
  float weight_x = lrp_blend_weight(g.x - base.x);
  float weight_y = lrp_blend_weight(g.y - base.y);
  uvec2 block = placement_block + uvec2(ivec2(base));
  float weights[4] = float[4]((1.0 - weight_x) * (1.0 - weight_y), weight_x * (1.0 - weight_y),
                              (1.0 - weight_x) * weight_y, weight_x * weight_y);
  float square_sum = 0.0;
  for (int i = 0; i < 4; ++i) square_sum += weights[i] * weights[i];
  float normalisation = 1.0 / sqrt(square_sum);
  for (int i = 0; i < 4; ++i) {
    float w = weights[i];
    if (w <= 0.0) continue;
    CounterRng rng = CounterRng(
        cell_key(block.x + uint(i & 1), block.y + uint(i >> 1), seed, STREAM_OFFSETS), 0u);
    float shift_x = rng_uniform(rng);
    float shift_y = rng_uniform(rng);
    lrp_add_fixed_phase(q + vec2(shift_x, shift_y) * LRP_STRUCTURE_PERIOD, filtered, axis_a,
                        axis_b, w * normalisation, noise);
  }
}
