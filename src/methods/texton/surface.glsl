// Texton surface noise (section 6 of the texton paper) in GLSL: the twin of
// TextonModel::evaluate_surface (model.cpp). Compiled after texton noise.glsl and
// src/gl/surface_process.glsl (SURFACE_CONTEXT = TextonFilter), with the constants of
// TextonModel::surface_constants at one MNI (surface_shader() in gl_data.cpp writes them):
// TEXTON_SURFACE_CELL_SIZE, TEXTON_SURFACE_POISSON_CDF, TEXTON_SURFACE_POISSON_CHUNKS,
// TEXTON_SURFACE_DEPTH, TEXTON_SURFACE_INVERSE_DEPTH, TEXTON_SURFACE_SCALE and
// TEXTON_SURFACE_CONSTANT.

uint surface_impulse_count(inout CounterRng rng, TextonFilter f) {
  return texton_count(rng, TEXTON_SURFACE_POISSON_CDF, TEXTON_SURFACE_POISSON_CHUNKS);
}

// An impulse within r/2 of the tangent plane, weighted by (1 - 2 |t| / r)+, carries the filtered
// texton at (z1, z2) in the frame (u1, u2).
void surface_impulse(inout CounterRng rng, float t, float z1, float z2, TextonFilter f,
                     inout vec4 acc) {
  float weight = 1.0 - abs(t) * TEXTON_SURFACE_INVERSE_DEPTH;
  if (weight > 0.0) texton_add(ivec2(0), f, z1, z2, weight, acc);
}

// The engine-facing surface entry point: a surface point in exemplar pixels (model space), its
// unit normal and unit tangent (the frame u1 = tangent, u2 = normal x tangent, u3 = normal), the
// screen derivatives of the position (dFdx(position), dFdy(position); zero = no filtering),
// projected on (u1, u2) and filtered as the planar noise filters a footprint, and a seed.
// Normalised by Proposition 3: the planar noise's mean and variance.
vec4 stochtex_texton_surface(vec3 position, vec3 normal, vec3 tangent, vec3 dpdx, vec3 dpdy,
                             uint seed) {
  vec3 bitangent = cross(normal, tangent);
  TextonFilter f = texton_filter(vec2(dot(dpdx, tangent), dot(dpdx, bitangent)),
                                 vec2(dot(dpdy, tangent), dot(dpdy, bitangent)));
  vec4 acc = surface_sum_impulses(position, tangent, bitangent, normal, texton_reach(f),
                                  TEXTON_SURFACE_DEPTH, TEXTON_SURFACE_CELL_SIZE, seed, f);
  return texton_output(acc, TEXTON_SURFACE_SCALE, TEXTON_SURFACE_CONSTANT, f);
}
