// Texton noise mixing in GLSL (texton paper section 7): the twin of MixField::rho and
// TextonMixModel::evaluate_typed (model.cpp), same draws, so the CPU and GPU agree to float
// rounding. Requires random.glsl (STREAM_SIGNS among its constants), texton's shared constants
// (Twin::kConstants: TEXTON_PADDING, ...), the shot noise's constants (texton_shot_noise_glsl), this
// model's (texton_mix_glsl in gl_data.cpp: TEXTON_MIX_STEPS, TEXTON_MIX_ATLAS_COLUMNS,
// TEXTON_MIX_ATLAS_TILE, TEXTON_MIX_MEAN_A/B, TEXTON_MIX_FIELD_AT_ORIGIN and the ramp's
// TEXTON_MIX_RAMP_* or, with TEXTON_MIX_MASK defined, the mask's TEXTON_MIX_MASK_* and
// texton_mix_mask(index)), the atlas sampler and texton evaluate.glsl, exact_fetch.glsl and
// impulses.glsl.
//
// TEXTON_MIX_FIELD is the field's value at the corner of the origin cell (texton_mix_field_at):
// the exported library's origin cell is 0; the renderer defines it as a uniform before the library.
#ifndef TEXTON_MIX_FIELD
#define TEXTON_MIX_FIELD TEXTON_MIX_FIELD_AT_ORIGIN
#endif

// rho at x, in exemplar pixels from the origin cell's corner (MixField::rho).
float texton_mix_rho(vec2 x) {
#ifdef TEXTON_MIX_MASK
  // Bilinear between pixel centres, clamped to the edge pixels.
  vec2 m = clamp(TEXTON_MIX_FIELD + x * TEXTON_MIX_MASK_INVERSE_SCALE, vec2(0.0),
                 vec2(TEXTON_MIX_MASK_SIZE - 1));
  ivec2 i = min(ivec2(m), TEXTON_MIX_MASK_SIZE - 1);
  ivec2 i1 = min(i + 1, TEXTON_MIX_MASK_SIZE - 1);
  float s = m.x - float(i.x);
  float t = m.y - float(i.y);
  int w = TEXTON_MIX_MASK_SIZE.x;
  return (1.0 - t) * ((1.0 - s) * texton_mix_mask(i.y * w + i.x) +
                      s * texton_mix_mask(i.y * w + i1.x)) +
         t * ((1.0 - s) * texton_mix_mask(i1.y * w + i.x) + s * texton_mix_mask(i1.y * w + i1.x));
#else
  return clamp(TEXTON_MIX_FIELD.x + dot(x, TEXTON_MIX_RAMP_UNIT) * TEXTON_MIX_RAMP_INVERSE_LENGTH,
               0.0, 1.0);
#endif
}

// The impulses of the mixing (impulses.glsl): point x_j uses the texton of the region its centre
// falls in (rho(x_j) rounded to the nearest of the R steps) with a random sign drawn from the
// cell's own stream.
TextonImpulse texton_impulse(uvec2 origin_cell, ivec2 cell, uint index, vec2 uv, uint seed) {
  int step = int(floor(texton_mix_rho((vec2(cell) + uv) * TEXTON_CELL_SIZE) *
                           float(TEXTON_MIX_STEPS - 1) +
                       0.5));
  ivec2 tile = ivec2(step % TEXTON_MIX_ATLAS_COLUMNS, step / TEXTON_MIX_ATLAS_COLUMNS);
  return TextonImpulse(tile * TEXTON_MIX_ATLAS_TILE, texton_sign(origin_cell, cell, index, seed));
}

// The mixed texton noise f / sqrt(lambda) + (1 - rho) mean_A + rho mean_B at p, in exemplar pixels
// from the corner of cell `origin_cell`; `fade` scales the fluctuation only.
vec4 texton_mix_noise(vec2 p, uvec2 origin_cell, uint seed, TextonFilter f) {
  vec4 acc = texton_sum_impulses(p, origin_cell, seed, f);
  float rho = texton_mix_rho(p);
  return (1.0 - rho) * TEXTON_MIX_MEAN_A + rho * TEXTON_MIX_MEAN_B +
         f.fade * acc * TEXTON_INVERSE_SQRT_INTENSITY;
}
