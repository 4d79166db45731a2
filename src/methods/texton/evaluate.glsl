// Texton noise in GLSL: the twin of TextonModel::evaluate_typed and filter_setup (evaluate.hpp,
// model.cpp), same hash, same draws, same constants, so the CPU and GPU agree to float rounding.
// Requires random.glsl, then the constants shared with the C++ (TEXTON_PADDING, TEXTON_MAX_PROBES,
// TEXTON_LOD_BIAS: Twin::kConstants in gl_twin.hpp), the model's constants (texton_glsl() in
// gl_data.cpp writes them: TEXTON_CHANNELS, TEXTON_ORDER, TEXTON_CELL_SIZE, TEXTON_POISSON_CDF, TEXTON_POISSON_CHUNKS,
// TEXTON_INVERSE_SQRT_INTENSITY, TEXTON_CONSTANT_TERM, TEXTON_MEAN, TEXTON_LEVELS and the
// TEXTON_LEVEL_* arrays) and `uniform sampler2D stochtex_texton_atlas`: every pyramid level's
// padded texels (RGBA = up to 4 channels), level l in rows TEXTON_LEVEL_ROW[l] onwards.

#ifdef TEXTON_TEXTURE_FILTER
vec4 texton_texture_fetch(float dx, float dy);  // hardware.glsl
#endif

struct TextonFilter {
  int level;
  float level_blend;
  int probes;
  vec2 probe_step;
  float fade;
};

// filter_setup of evaluate.hpp: the pyramid level(s) and probes for a footprint.
TextonFilter texton_filter(vec2 dpdx, vec2 dpdy) {
  TextonFilter f = TextonFilter(0, 0.0, 1, vec2(0.0), 1.0);
  float length_x = length(dpdx);
  float length_y = length(dpdy);
  float major = max(length_x, length_y);
  float minor = min(length_x, length_y);
  if (!(major > 1.0)) return f;
  int top_level = TEXTON_LEVELS - 1;
  f.probes = int(min(float(TEXTON_MAX_PROBES), ceil(major / max(minor, 1.0))));
  float width = max(max(major / float(f.probes), minor), 1.0);
  float lod = max(0.0, log2(width) - TEXTON_LOD_BIAS);
  if (lod >= float(top_level)) {
    f.fade = exp2(float(top_level) - lod);
    lod = float(top_level);
  }
  f.level = min(int(lod), top_level);
  f.level_blend = f.level == top_level ? 0.0 : lod - float(f.level);
  f.probe_step = (length_x >= length_y ? dpdx : dpdy) / float(f.probes);
  return f;
}

uint texton_poisson_count(inout CounterRng rng) {
  uint total = 0u;
  for (uint c = 0u; c < TEXTON_POISSON_CHUNKS; ++c) {
    float u = rng_uniform(rng);
    uint k = 0u;
    while (u >= TEXTON_POISSON_CDF[k]) ++k;
    total += k;
  }
  return total;
}

// B-spline interpolation weights of order TEXTON_ORDER at texel coordinate u (BsplineKernel).
int texton_weights(float u, out float w[6]) {
  for (int i = 0; i < 6; ++i) w[i] = 0.0;
  if (TEXTON_ORDER == 0) {
    w[0] = 1.0;
    return int(floor(u + 0.5));
  }
  float cell = floor(u);
  float t = u - cell;
  int first = int(cell) - (TEXTON_ORDER - 1) / 2;
  if (TEXTON_ORDER == 1) {
    w[0] = 1.0 - t;
    w[1] = t;
  } else if (TEXTON_ORDER == 3) {
    float s = 1.0 - t;
    float t2 = t * t;
    float t3 = t2 * t;
    w[0] = s * s * s * (1.0 / 6.0);
    w[1] = (4.0 - 6.0 * t2 + 3.0 * t3) * (1.0 / 6.0);
    w[2] = (1.0 + 3.0 * t + 3.0 * t2 - 3.0 * t3) * (1.0 / 6.0);
    w[3] = t3 * (1.0 / 6.0);
  } else {
    float s = 1.0 - t;
    float t2 = t * t;
    float t3 = t2 * t;
    float t4 = t3 * t;
    float t5 = t4 * t;
    w[0] = s * s * s * s * s * (1.0 / 120.0);
    w[1] = (26.0 - 50.0 * t + 20.0 * t2 + 20.0 * t3 - 20.0 * t4 + 5.0 * t5) * (1.0 / 120.0);
    w[2] = (66.0 - 60.0 * t2 + 30.0 * t4 - 10.0 * t5) * (1.0 / 120.0);
    w[3] = (26.0 + 50.0 * t + 20.0 * t2 - 20.0 * t3 - 20.0 * t4 + 10.0 * t5) * (1.0 / 120.0);
    w[4] = (1.0 + 5.0 * t + 10.0 * t2 + 10.0 * t3 + 5.0 * t4 - 5.0 * t5) * (1.0 / 120.0);
    w[5] = t5 * (1.0 / 120.0);
  }
  return first;
}

void texton_accumulate(int level, float dx, float dy, float weight, inout vec4 acc) {
  float half_width = TEXTON_LEVEL_HALF_WIDTH[level];
  if (abs(dx) >= half_width || abs(dy) >= half_width) return;
  float wx[6];
  float wy[6];
  float inverse_spacing = 1.0 / TEXTON_LEVEL_SPACING[level];
  int x0 = texton_weights((dx - TEXTON_LEVEL_FIRST_TEXEL[level]) * inverse_spacing, wx);
  int y0 = texton_weights((dy - TEXTON_LEVEL_FIRST_TEXEL[level]) * inverse_spacing, wy);
  ivec2 base = ivec2(x0 + TEXTON_PADDING, TEXTON_LEVEL_ROW[level] + y0 + TEXTON_PADDING);
  for (int j = 0; j <= TEXTON_ORDER; ++j)
    for (int i = 0; i <= TEXTON_ORDER; ++i)
      acc += (weight * wy[j] * wx[i]) * texelFetch(stochtex_texton_atlas, base + ivec2(i, j), 0);
}

// Texton noise at p, in exemplar pixels relative to the corner of cell `origin_cell` (whose
// index enters the hash as its low 32 bits, so callers may keep p small and the cell far).
vec4 texton_noise(vec2 p, uvec2 origin_cell, uint seed, TextonFilter f) {
  int top_level = TEXTON_LEVELS - 1;
  int coarse = min(f.level + 1, top_level);
  float probe_extent = 0.5 * float(f.probes - 1) * max(abs(f.probe_step.x), abs(f.probe_step.y));
  float kernel_reach = f.level_blend > 0.0 ? max(TEXTON_LEVEL_HALF_WIDTH[f.level],
                                                 TEXTON_LEVEL_HALF_WIDTH[coarse])
                                           : TEXTON_LEVEL_HALF_WIDTH[f.level];
  float reach = kernel_reach + probe_extent;
  float probe_weight = 1.0 / float(f.probes);
  vec4 acc = vec4(0.0);
  int first_x = int(floor((p.x - reach) / TEXTON_CELL_SIZE));
  int last_x = int(floor((p.x + reach) / TEXTON_CELL_SIZE));
  int first_y = int(floor((p.y - reach) / TEXTON_CELL_SIZE));
  int last_y = int(floor((p.y + reach) / TEXTON_CELL_SIZE));
  for (int cell_y = first_y; cell_y <= last_y; ++cell_y) {
    float offset_y = p.y - float(cell_y) * TEXTON_CELL_SIZE;
    for (int cell_x = first_x; cell_x <= last_x; ++cell_x) {
      float offset_x = p.x - float(cell_x) * TEXTON_CELL_SIZE;
      CounterRng rng = CounterRng(cell_key(origin_cell.x + uint(cell_x),
                                           origin_cell.y + uint(cell_y), seed, STREAM_POINTS),
                                  0u);
      uint impacts = texton_poisson_count(rng);
      for (uint n = 0u; n < impacts; ++n) {
        float u = rng_uniform(rng);
        float v = rng_uniform(rng);
        float dx = offset_x - u * TEXTON_CELL_SIZE;
        float dy = offset_y - v * TEXTON_CELL_SIZE;
#ifdef TEXTON_TEXTURE_FILTER
        // `render --gl-filter hardware` (hardware.glsl): one mip-mapped,
        // anisotropic texture fetch of the texton instead of the exact levels and probes.
        acc += texton_texture_fetch(dx, dy);
#else
        if (f.probes == 1 && f.level_blend == 0.0) {
          texton_accumulate(f.level, dx, dy, 1.0, acc);
          continue;
        }
        for (int k = 0; k < f.probes; ++k) {
          float shift = float(k) + 0.5 - 0.5 * float(f.probes);
          float px = dx + shift * f.probe_step.x;
          float py = dy + shift * f.probe_step.y;
          texton_accumulate(f.level, px, py, probe_weight * (1.0 - f.level_blend), acc);
          if (f.level_blend > 0.0)
            texton_accumulate(coarse, px, py, probe_weight * f.level_blend, acc);
        }
#endif
      }
    }
  }
  // (f - lambda sum alpha) / sqrt(lambda) + mean, eq. (2); `fade` scales the fluctuation only.
  vec4 noise = acc * TEXTON_INVERSE_SQRT_INTENSITY + TEXTON_CONSTANT_TERM - TEXTON_MEAN;
  return TEXTON_MEAN + f.fade * noise;
}

// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. Keep |p|
// below ~1e4 for full precision; move far regions with texton_noise's origin_cell instead.
vec4 stochtex_texton(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return texton_noise(p, uvec2(0u), seed, texton_filter(dpdx, dpdy));
}
