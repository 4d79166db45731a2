// Gabor noise of more than 4 channels (a material's maps, up to kMaxChannels): noise.glsl with the
// colour as an array of GABOR_CHANNELS floats (GABOR_COLOUR) instead of a vec4, GABOR_MEAN an
// array of GABOR_CHANNELS and GABOR_MIXING of GABOR_CHANNELS^2 floats (gl_data.cpp). Compiled
// after evaluate.glsl in its place; the models of 1 to 4 channels keep noise.glsl, so their GLSL
// is unchanged. Same sums, in the same order, as GaborModel::evaluate and mix_to_colour.
#define GABOR_COLOUR float[GABOR_CHANNELS]

// colour = mean + mixing * noise (section 7; mix_to_colour in model.cpp).
GABOR_COLOUR gabor_colour(GABOR_COLOUR noise) {
  precise GABOR_COLOUR colour;
  for (int c = 0; c < GABOR_CHANNELS; ++c) {
    colour[c] = GABOR_MEAN[c];
    for (int k = 0; k < GABOR_CHANNELS; ++k)
      colour[c] += GABOR_MIXING[c * GABOR_CHANNELS + k] * noise[k];
  }
  return colour;
}

#ifdef STOCHTEX_FLOAT
// Bandwidth-quantised Gabor noise (eq. 5), every channel: gabor_noise of noise.glsl, positions
// split per grid.
GABOR_COLOUR gabor_noise(uvec4 cell[GABOR_GRID_ARRAY], vec2 offset[GABOR_GRID_ARRAY], vec2 dpdx,
                         vec2 dpdy, uint seed) {
#else
// Bandwidth-quantised Gabor noise (eq. 5), every channel: gabor_noise of noise.glsl.
GABOR_COLOUR gabor_noise(dvec2 p, dvec2 dpdx, dvec2 dpdy, uint seed) {
#endif
  precise GABOR_COLOUR noise;
  for (int c = 0; c < GABOR_CHANNELS; ++c) noise[c] = 0.0;
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

// Every channel at p, with the arguments of stochtex_gabor (noise.glsl): what `export-shader` calls
// for a material (export_material.cpp). Keep |p| below ~1e4 for full precision.
#ifdef STOCHTEX_FLOAT
GABOR_COLOUR gabor_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  uvec4 cell[GABOR_GRID_ARRAY];
  vec2 offset[GABOR_GRID_ARRAY];
  for (int g = 0; g < GABOR_GRID_ARRAY; ++g) {
    cell[g] = uvec4(0u);
    offset[g] = p;
  }
  return gabor_noise(cell, offset, dpdx, dpdy, seed);
}
#else
GABOR_COLOUR gabor_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return gabor_noise(dvec2(p), dvec2(dpdx), dvec2(dpdy), seed);
}
#endif
