// colour = mean + mixing * noise (section 7; mix_to_colour in model.cpp): the planar noise's and
// surface noise's (surface.glsl).
vec4 gabor_colour(vec4 noise) {
  precise vec4 colour = GABOR_MEAN;
  for (int c = 0; c < GABOR_CHANNELS; ++c)
    for (int k = 0; k < GABOR_CHANNELS; ++k)
      colour[c] += GABOR_MIXING[c * GABOR_CHANNELS + k] * noise[k];
  return colour;
}

#ifdef STOCHTEX_FLOAT
// Bandwidth-quantised Gabor noise (eq. 5) with footprint (dpdx, dpdy) (zero = point sample), mixed
// back to the exemplar's colours: the value of GaborModel::evaluate at the position that is, for
// every grid g, the corner of its level-0 cell cell[g] (64-bit indices as (x low, x high, y low,
// y high) words) plus offset[g] exemplar pixels. The caller splits its position so, as the CPU
// does (floor(p / GABOR_GRID_CELL_SIZE[g]) and p minus that cell's corner, in double or integers);
// any cell works, the nearest keeps the offsets small and precise.
vec4 gabor_noise(uvec4 cell[GABOR_GRID_ARRAY], vec2 offset[GABOR_GRID_ARRAY], vec2 dpdx, vec2 dpdy,
                 uint seed) {
#else
// Bandwidth-quantised Gabor noise (eq. 5) at p with footprint (dpdx, dpdy) (zero = point sample),
// mixed back to the exemplar's colours: the value of GaborModel::evaluate.
vec4 gabor_noise(dvec2 p, dvec2 dpdx, dvec2 dpdy, uint seed) {
#endif
  precise vec4 noise = vec4(0.0);
  for (int g = 0; g < GABOR_GRIDS; ++g) {
    GaborGridFilter f = gabor_grid_filter(g, dpdx, dpdy);
    if (f.skip) continue;
    uint level_seed = cell_key(uint(g), uint(f.level), seed, STREAM_KERNELS);
#ifdef STOCHTEX_FLOAT
    uvec2 origin;
    vec2 p = offset[g];
    p.x += gabor_level_origin(cell[g].x, cell[g].y, f.level, GABOR_GRID_CELL_SIZE[g], origin.x);
    p.y += gabor_level_origin(cell[g].z, cell[g].w, f.level, GABOR_GRID_CELL_SIZE[g], origin.y);
    precise float grid_noise = f.amplitude * gabor_grid_sum(g, p, origin, f, level_seed);
#else
    precise float grid_noise = f.amplitude * gabor_grid_sum(g, p, f, level_seed);
#endif
    noise[GABOR_GRID_CHANNEL[g]] += grid_noise;
  }
  return gabor_colour(noise);
}

#ifdef STOCHTEX_FLOAT
// The engine-facing entry point: p in exemplar pixels, its screen derivatives (dFdx(p), dFdy(p)
// in a fragment shader; zero = no filtering) and a seed. Keep |p| below ~1e4 for full precision;
// further out, split the position per grid and call gabor_noise (gl_pass.cpp does it for
// `stochtex render`).
vec4 stochtex_gabor(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  uvec4 cell[GABOR_GRID_ARRAY];
  vec2 offset[GABOR_GRID_ARRAY];
  for (int g = 0; g < GABOR_GRID_ARRAY; ++g) {
    cell[g] = uvec4(0u);
    offset[g] = p;
  }
  return gabor_noise(cell, offset, dpdx, dpdy, seed);
}
#else
// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed.
vec4 stochtex_gabor(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return gabor_noise(dvec2(p), dvec2(dpdx), dvec2(dpdy), seed);
}
#endif
