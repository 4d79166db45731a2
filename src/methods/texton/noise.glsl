// Texton noise at p (TextonModel::evaluate_typed), p in exemplar pixels relative to the corner of
// cell `origin_cell`: the shot noise of impulses.glsl, whose impulses are all the one texton (at
// the atlas corner) with weight 1 (times the balanced points' signs), normalised as eq. (2).
TextonImpulse texton_impulse(uvec2 origin_cell, ivec2 cell, uint index, vec2 uv, uint seed) {
  return TextonImpulse(ivec2(0), 1.0);
}

// The noise's value from the sum (FilteredTexton::output), texton noise's and surface noise's
// (surface.glsl): (acc - offset) * scale + mean, with constant = mean - offset * scale, `fade`
// (texton_filter) scaling the fluctuation only.
vec4 texton_output(vec4 acc, float scale, vec4 constant, TextonFilter f) {
  vec4 noise = acc * scale + constant - TEXTON_MEAN;
  return TEXTON_MEAN + f.fade * noise;
}

vec4 texton_noise(vec2 p, uvec2 origin_cell, uint seed, TextonFilter f) {
  vec4 acc = texton_sum_impulses(p, origin_cell, seed, f);
  // (f - E f) / sqrt(lambda) + mean, eq. (2).
  return texton_output(acc, TEXTON_INVERSE_SQRT_INTENSITY, TEXTON_CONSTANT_TERM, f);
}
