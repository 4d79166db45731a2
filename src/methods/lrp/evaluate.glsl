// Local random-phase noise in GLSL: the twin of LrpModel::evaluate_typed (model.cpp,
// evaluate.hpp, window.hpp), same lattices, same draws, same polynomial cosine and window.
// Requires random.glsl, then the model's constants (lrp_glsl() in src/gl writes them) and the
// table readers `vec3 lrp_frequency(uint index)` (f_x, f_y, weight) and
// `uvec2 lrp_substratum(int index)` (first, count): storage buffers in the renderer, a texture in an exported shader (src/gl/lrp_glsl.cpp).

const uint STREAM_PHASES = 0x7f4a7c15u;

// cos(2 pi t), t in turns (cos_turns).
float lrp_cos_turns(float t) {
  t -= float(int(t));
  t = abs(t);
  t = t > 0.5 ? 1.0 - t : t;
  float sign = t > 0.25 ? -1.0 : 1.0;
  t = t > 0.25 ? 0.5 - t : t;
  float x = 6.283185307179586 * t;
  float x2 = x * x;
  float p = 1.0 + x2 * (-1.0 / 2.0 +
                        x2 * (1.0 / 24.0 +
                              x2 * (-1.0 / 720.0 +
                                    x2 * (1.0 / 40320.0 +
                                          x2 * (-1.0 / 3628800.0 + x2 * (1.0 / 479001600.0))))));
  return sign * p;
}

// Frequency clamping, section 6.4 (clamp_weight).
float lrp_clamp_weight(float cycles) { return clamp((1.0 - cycles) * 2.0, 0.0, 1.0); }

// The Kaiser-Bessel window at squared distance r2 in lattice units (window_from_square).
float lrp_window(float r2) {
  float t = 1.0 - r2 * (1.0 / 2.25);
  if (t <= 0.0) return 0.0;
  float sum = LRP_WINDOW[19];
  for (int m = 18; m >= 0; --m) sum = sum * t + LRP_WINDOW[m];
  return sum * t * sqrt(t);
}

// One stratum's noise at `u`, the position in lattice units relative to the lattice node
// `origin_node` (low 32 bits; formed on the CPU in double for the far part). `axis_a`, `axis_b`:
// the footprint's axes in exemplar pixels, zero for point samples.
float lrp_stratum_noise(int s, vec2 u, uvec2 origin_node, uint stratum_seed, bool filtered,
                        vec2 axis_a, vec2 axis_b) {
  vec2 node = floor(u + 0.5);
  vec2 offset = u - node;
  float spacing = LRP_STRATUM_SPACING[s];
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
      for (int j = 0; j < LRP_STRATUM_COSINES[s]; ++j) {
        uint draw = rng_next(rng);
        int k = LRP_STRATUM_FIRST[s] + j;
        uint high;
        uint low;
        uvec2 substratum = lrp_substratum(k);
        umulExtended(draw & 0xfffffu, substratum.y, high, low);
        vec3 frequency = lrp_frequency(substratum.x + ((high << 12u) | (low >> 20u)));
        float fx = frequency.x;
        float fy = frequency.y;
        float phase = float(draw >> 20u) * (1.0 / 4096.0);
        float c = lrp_cos_turns(fx * px + fy * py + phase);
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
  float scale = LRP_STRATUM_AMPLITUDE[s];
  if (LRP_NORMALISE_ENVELOPE) scale *= sqrt(LRP_MEAN_ENVELOPE / window_square);
  return scale * sum;
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

// Section 5, the twin of structure_model.cpp: storage buffers `lrp_structure` (f_x, f_y,
// amplitude, phase per cosine; channel-major, then block, then cosine),
// `lrp_turbulence_frequencies` and `lrp_turbulence_substrata`.
layout(std430, binding = 3) readonly buffer LrpStructure { float lrp_structure[]; };
layout(std430, binding = 4) readonly buffer LrpTurbulenceFrequencies {
  float lrp_turbulence_frequencies[];
};
layout(std430, binding = 5) readonly buffer LrpTurbulenceSubstrata {
  uint lrp_turbulence_substrata[];
};

const uint STREAM_OFFSETS = 0x85ebca6bu;

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
      float w = lrp_window((rx * rx + ry * ry) * 2.25);
      if (w <= 0.0) continue;
      float px = rx * side;
      float py = ry * side;
      // B is a power of two: & (B - 1) is the non-negative remainder, as wrap() on the CPU.
      int block = ((cell.y + dy) & (LRP_STRUCTURE_BLOCKS - 1)) * LRP_STRUCTURE_BLOCKS +
                  ((cell.x + dx) & (LRP_STRUCTURE_BLOCKS - 1));
      for (int c = 0; c < LRP_CHANNELS; ++c) {
        int base = 4 * ((c * LRP_STRUCTURE_BLOCKS * LRP_STRUCTURE_BLOCKS + block) *
                        LRP_STRUCTURE_COSINES);
        float local = 0.0;
        for (int j = 0; j < LRP_STRUCTURE_COSINES; ++j) {
          int k = base + 4 * j;
          float fx = lrp_structure[k];
          float fy = lrp_structure[k + 1];
          float value =
              lrp_structure[k + 2] * lrp_cos_turns(fx * px + fy * py + lrp_structure[k + 3]);
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
  vec2 node = floor(u + 0.5);
  vec2 offset = u - node;
  float spacing = LRP_TURBULENCE_SPACING[t];
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
      for (int j = 0; j < LRP_TURBULENCE_COSINES[t]; ++j) {
        uint draw = rng_next(rng);
        int k = LRP_TURBULENCE_FIRST[t] + j;
        uint high;
        uint low;
        umulExtended(draw & 0xfffffu, lrp_turbulence_substrata[2 * k + 1], high, low);
        uint pick = lrp_turbulence_substrata[2 * k] + ((high << 12u) | (low >> 20u));
        float phase = float(draw >> 20u) * (1.0 / 4096.0);
        local += lrp_cos_turns(lrp_turbulence_frequencies[2 * pick] * px +
                               lrp_turbulence_frequencies[2 * pick + 1] * py + phase);
      }
      sum += w * local;
      window_square += w * w;
    }
  }
  return abs(LRP_TURBULENCE_AMPLITUDE[t] * sqrt(LRP_MEAN_ENVELOPE / window_square) * sum);
}

// blend_weight: weight of block i + 1 against block i, a smoothstep over 1/8 of a block each side.
float lrp_blend_weight(float t) {
  float a = clamp((t - 0.5) * 4.0 + 0.5, 0.0, 1.0);
  return a * a * (3.0 - 2.0 * a);
}

// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. The
// strata's lattice nodes come from p in float: keep |p| below ~1e4 for full precision.
vec4 stochtex_lrp(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  vec4 noise = vec4(0.0);
  for (int s = 0; s < LRP_STRATA_TOTAL; ++s) {
    if (LRP_STRATUM_AMPLITUDE[s] == 0.0) continue;
    uint stratum_seed = cell_key(uint(s / LRP_STRATA), uint(s % LRP_STRATA), seed, STREAM_PHASES);
    noise[LRP_STRATUM_CHANNEL[s]] += lrp_stratum_noise(s, p / LRP_STRATUM_SPACING[s], uvec2(0u),
                                                       stratum_seed, true, dpdx, dpdy);
  }
  return lrp_colour(noise);
}
