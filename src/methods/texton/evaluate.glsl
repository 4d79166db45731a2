// Texton noise in GLSL: the twin of TextonModel::evaluate_typed and filter_setup (evaluate.hpp,
// model.cpp), same hash, same draws, same constants, so the CPU and GPU agree to float rounding.
// Requires random.glsl, then the constants shared with the C++ (TEXTON_PADDING, TEXTON_MAX_PROBES,
// TEXTON_LOD_BIAS, TEXTON_LATTICE_STEP_U/V: Twin::kConstants in gl_twin.hpp), the model's
// constants (texton_glsl() in gl_data.cpp writes them: TEXTON_CHANNELS, TEXTON_ORDER,
// TEXTON_CELL_SIZE, TEXTON_COUNT_CDF, TEXTON_COUNT_CHUNKS, TEXTON_BALANCED,
// TEXTON_INVERSE_SQRT_INTENSITY, TEXTON_CONSTANT_TERM, TEXTON_MEAN, TEXTON_LEVELS and the
// TEXTON_LEVEL_* arrays) and `vec4 texton_atlas_texel(ivec2 texel)`, the atlas of every pyramid
// level's padded texels (RGBA = up to 4 channels), level l in rows TEXTON_LEVEL_ROW[l] onwards
// (texton_atlas_source() in gl_data.cpp: a sampler, or the surface evaluator's storage buffer).

#ifdef TEXTON_TEXTURE_FILTER
vec4 texton_texture_fetch(float dx, float dy);  // hardware.glsl
#endif

// One impulse of the shot noise (Impulse in evaluate.hpp): the atlas texel where its texton's
// pyramid starts (texton noise: the atlas corner) and its weight (texton noise: 1; mixing, texton
// paper section 7: a random sign); the balanced points multiply it by their own sign.
struct TextonImpulse {
  ivec2 atlas;
  float weight;
};

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

// A cell's point count by inversion of a tabulated CDF in `chunks` draws (CellCount in
// core/cell_count.hpp): the planar grid's (Poisson or balanced), or surface noise's 3-D cells'
// (Poisson).
uint texton_count(inout CounterRng rng, float cdf[TEXTON_COUNT_CDF.length()], uint chunks) {
  uint total = 0u;
  for (uint c = 0u; c < chunks; ++c) {
    float u = rng_uniform(rng);
    uint k = 0u;
    while (u >= cdf[k]) ++k;
    total += k;
  }
  return total;
}

uint texton_cell_count(inout CounterRng rng) {
  return texton_count(rng, TEXTON_COUNT_CDF, TEXTON_COUNT_CHUNKS);
}

