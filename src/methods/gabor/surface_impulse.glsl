// Surface Gabor noise's side of the impulse walk (src/gl/surface_process.glsl, compiled after
// this file with SURFACE_CONTEXT = GaborSurfacePoint): the twin of the lambda of
// GaborModel::evaluate_surface (model.cpp). Requires gabor evaluate.glsl and the constants of
// GaborModel::surface_grid (Twin::surface_shader in gl_data.cpp): GABOR_SURFACE_CDF (each grid's
// CDF texel in the data), GABOR_SURFACE_POISSON_CHUNKS, GABOR_SURFACE_CELL_SIZE and
// GABOR_SURFACE_AMPLITUDE_GAIN.

// One grid at one point: its index, its kernel filter and 1 / the tent's half-depth r_b 2^level.
struct GaborSurfacePoint {
  int grid;
  GaborGridFilter kernel;
  float inverse_depth;
};

uint surface_impulse_count(inout CounterRng rng, GaborSurfacePoint point) {
  return gabor_poisson(GABOR_SURFACE_CDF[point.grid], GABOR_SURFACE_POISSON_CHUNKS[point.grid],
                       rng);
}

// An impulse draws its kernel (frequency, then phase) whatever its place, then adds the filtered
// kernel at (z1, z2) in the frame (u1, u2) weighted by the tent (1 - |t| / depth)+.
void surface_impulse(inout CounterRng rng, float t, float z1, float z2, GaborSurfacePoint point,
                     inout vec4 acc) {
  vec4 gaussian = gabor_draw_alias(point.grid, rng);
  float phase = rng_uniform(rng);
  precise float weight = 1.0 - abs(t) * point.inverse_depth;
  float value;
  if (weight > 0.0 && gabor_kernel(point.kernel, gaussian, phase, z1, z2, value))
    acc.x += weight * value;
}
