// The compute shader of `render --backend gl` for Gabor noise: one invocation per output pixel.
// Requires random.glsl, the model's constants and gabor evaluate.glsl, in the same precision
// (glsl_precision_variant: doubles for --gl-filter exact, floats for --gl-filter hardware).

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform ivec2 first_pixel;  // grid.first_pixel + the dispatch's offset
uniform ivec2 dispatch_size;
#ifdef STOCHTEX_FLOAT
// Per grid, the grid origin split on the CPU in double as GaborModel::evaluate splits positions:
// its level-0 cell (x low, x high, y low, y high words of 64-bit indices) and the offset from it.
uniform uvec4 origin_cell[GABOR_GRID_ARRAY];
uniform vec2 origin_offset[GABOR_GRID_ARRAY];
uniform float scale;
#else
uniform dvec2 origin;       // the grid's, in double as the CPU forms its positions
uniform double scale;
#endif
uniform uint seed;
uniform bool filtered;
// gabor_noise's colour type, GABOR_COLOUR: colour.glsl's vec4 or colour_channels.glsl's array.

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
#ifdef STOCHTEX_FLOAT
  // p = origin + scale (i + 1/2): the far part stays in the cells, the float part is the
  // origin's offset plus the pixel's, as precise at origin 1e7 as at 0.
  precise vec2 pixel = scale * (vec2(first_pixel + local_pixel) + 0.5);
  vec2 offset[GABOR_GRID_ARRAY];
  for (int g = 0; g < GABOR_GRID_ARRAY; ++g) offset[g] = origin_offset[g] + pixel;
  vec2 dpdx = filtered ? vec2(scale, 0.0) : vec2(0.0);
  vec2 dpdy = filtered ? vec2(0.0, scale) : vec2(0.0);
  GABOR_COLOUR value = gabor_noise(origin_cell, offset, dpdx, dpdy, seed);
#else
  // p = origin + scale (i + 1/2), the CPU renderer's position to the last bit.
  precise dvec2 p = origin + scale * (dvec2(first_pixel + local_pixel) + 0.5lf);
  dvec2 dpdx = filtered ? dvec2(scale, 0.0lf) : dvec2(0.0lf);
  dvec2 dpdy = filtered ? dvec2(0.0lf, scale) : dvec2(0.0lf);
  GABOR_COLOUR value = gabor_noise(p, dpdx, dpdy, seed);
#endif
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * GABOR_CHANNELS;
  for (int c = 0; c < GABOR_CHANNELS; ++c) result[index + c] = value[c];
}
