// Bandwidth-quantised Gabor noise in GLSL, the twin of GaborModel::evaluate: the grids' sums into
// GABOR_COLOUR, mixed back to the exemplar's colours by gabor_colour. Compiled after evaluate.glsl
// and colour.glsl (a vec4, 1 to 4 channels) or colour_channels.glsl (an array, beyond).

#ifdef STOCHTEX_FLOAT
// Bandwidth-quantised Gabor noise (eq. 5) with footprint (dpdx, dpdy) (zero = point sample), mixed
// back to the exemplar's colours: the value of GaborModel::evaluate at the position that is, for
// every grid g, the corner of its level-0 cell cell[g] (64-bit indices as (x low, x high, y low,
// y high) words) plus offset[g] exemplar pixels. The caller splits its position so, as the CPU
// does (floor(p / GABOR_GRID_CELL_SIZE[g]) and p minus that cell's corner, in double or integers);
// any cell works, the nearest keeps the offsets small and precise.
GABOR_COLOUR gabor_noise(uvec4 cell[GABOR_GRID_ARRAY], vec2 offset[GABOR_GRID_ARRAY], vec2 dpdx,
                         vec2 dpdy, uint seed) {
#else
// Bandwidth-quantised Gabor noise (eq. 5) at p with footprint (dpdx, dpdy) (zero = point sample),
// mixed back to the exemplar's colours: the value of GaborModel::evaluate.
GABOR_COLOUR gabor_noise(dvec2 p, dvec2 dpdx, dvec2 dpdy, uint seed) {
#endif
  precise GABOR_COLOUR noise = gabor_zero();
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

// gabor_noise at p (exemplar pixels), its footprint and a seed: the entry points' body. Keep |p|
// below ~1e4 for full precision; further out, split the position per grid and call gabor_noise
// (gl_pass.cpp does it for `stochtex render`).
#ifdef STOCHTEX_FLOAT
GABOR_COLOUR gabor_noise_at(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  uvec4 cell[GABOR_GRID_ARRAY];
  vec2 offset[GABOR_GRID_ARRAY];
  for (int g = 0; g < GABOR_GRID_ARRAY; ++g) {
    cell[g] = uvec4(0u);
    offset[g] = p;
  }
  return gabor_noise(cell, offset, dpdx, dpdy, seed);
}
#else
GABOR_COLOUR gabor_noise_at(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return gabor_noise(dvec2(p), dvec2(dpdx), dvec2(dpdy), seed);
}
#endif

#ifdef GABOR_CHANNEL_ARRAY
// Every channel at p, with the arguments of stochtex_gabor: what `export-shader` calls for a
// material of more than 4 channels (export_material.cpp).
GABOR_COLOUR gabor_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return gabor_noise_at(p, dpdx, dpdy, seed);
}
#else
// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed.
vec4 stochtex_gabor(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return gabor_noise_at(p, dpdx, dpdy, seed);
}
#endif
