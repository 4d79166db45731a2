// Surface Gabor noise (section 9.1 of Gabor noise by example) in GLSL: the twin of
// GaborModel::evaluate_surface (model.cpp). Compiled after surface_impulse.glsl and
// src/gl/surface_process.glsl, in the double variant of gabor evaluate.glsl.

// The engine-facing surface entry point: a surface point in exemplar pixels (model space), its
// unit normal and unit tangent (the frame u1 = tangent, u2 = normal x tangent, u3 = normal), the
// screen derivatives of the position (dFdx(position), dFdy(position); zero = no filtering),
// projected on (u1, u2) and filtered as the planar noise filters a footprint, and a seed. Each
// grid's kernels lie in the tangent plane, the process thinned by the footprint as in the plane.
vec4 stochtex_gabor_surface(vec3 position, vec3 normal, vec3 tangent, vec3 dpdx, vec3 dpdy,
                            uint seed) {
  vec3 bitangent = cross(normal, tangent);
  dvec2 footprint_x = dvec2(dot(dpdx, tangent), dot(dpdx, bitangent));
  dvec2 footprint_y = dvec2(dot(dpdy, tangent), dot(dpdy, bitangent));
  precise vec4 noise = vec4(0.0);
  for (int g = 0; g < GABOR_GRIDS; ++g) {
    GaborGridFilter f = gabor_grid_filter(g, footprint_x, footprint_y);
    if (f.skip) continue;
    // 2^level, exactly: f.cell_size is the grid's cell size times it.
    double level_scale = f.cell_size / GABOR_GRID_CELL_SIZE[g];
    double depth = GABOR_GRID_RADIUS[g] * level_scale;
    GaborSurfacePoint point = GaborSurfacePoint(g, f, float(1.0lf / depth));
    uint level_seed = cell_key(uint(g), uint(f.level), seed, STREAM_KERNELS);
    float sum = surface_sum_impulses(position, tangent, bitangent, normal, float(f.reach),
                                     float(depth), float(GABOR_SURFACE_CELL_SIZE[g] * level_scale),
                                     level_seed, point).x;
    precise float grid_noise = float(double(f.amplitude) * GABOR_SURFACE_AMPLITUDE_GAIN) * sum;
    noise[GABOR_GRID_CHANNEL[g]] += grid_noise;
  }
  return gabor_colour(noise);
}
