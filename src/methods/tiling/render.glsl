// The compute shader of `render --backend gl` for histogram-preserving tiling and blending: one
// invocation per output pixel. Requires random.glsl, the model's constants and tiling
// evaluate.glsl.

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform ivec2 first_pixel;    // grid.first_pixel + the dispatch's offset
uniform ivec2 dispatch_size;
uniform uvec2 origin_cell;    // low 32 bits of the skewed lattice cell of the grid origin
uniform vec2 origin_skewed;   // the origin's position in that cell, skewed lattice units
uniform vec2 origin_wrapped;  // the origin modulo the exemplar's period
uniform float scale;
uniform uint seed;
// The grid's footprint gives one level of detail for the render (level_of_detail in C++).
uniform int lod_level;
uniform float lod_blend;
uniform float footprint_width;  // TilingModel::footprint_width (zero for point samples)
// --gl-filter hardware: the footprint's side (zero for point samples).
uniform float filter_scale;
// A model whose channels go through T^-1 in groups of their own (gl_pass.cpp) renders its Gaussian
// in chunks of up to 4 channels, each chunk a model of the variance blend (no T^-1) writing its
// TILING_CHANNELS channels from channel TILING_RESULT_FIRST of pixels of TILING_RESULT_STRIDE; the
// first chunk (TILING_RESULT_LEVELS) also writes each pixel's level of detail for groups.glsl.
#ifdef TILING_RESULT_LEVELS
layout(std430, binding = 2) writeonly buffer ResultLevels { float result_levels[]; };
#endif
// With the patches kept apart (TILING_PATCH_OUTPUT: patches.glsl's tiling_patches), a chunk writes
// each patch's channels instead, at pixel * TILING_PATCH_STRIDE + patch * TILING_RESULT_STRIDE,
// and the first chunk the patches' weights, levels of detail and transforms (scale cos, scale
// sin, scale) after the 3 patches' channels.
#ifdef TILING_PATCH_OUTPUT
layout(std430, binding = 3) writeonly buffer ResultPatches { float result_patches[]; };
#endif

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  vec2 p = scale * (vec2(first_pixel + local_pixel) + 0.5);
  vec2 skewed = origin_skewed + vec2(p.x - p.y * TILING_INVERSE_SQRT3,
                                     2.0 * TILING_INVERSE_SQRT3 * p.y) / TILING_EDGE;
#ifdef TILING_TEXTURE_FILTER
  tiling_set_gradients(vec2(filter_scale, 0.0), vec2(0.0, filter_scale));
#endif
  int level = lod_level;
  float level_blend = lod_blend;
#ifdef TILING_PATCH_OUTPUT
  int pixel = local_pixel.y * dispatch_size.x + local_pixel.x;
  TilingPatches patches = tiling_patches(skewed, origin_cell, origin_wrapped + p, seed,
                                         footprint_width, level, level_blend);
  int base = pixel * TILING_PATCH_STRIDE;
  for (int v = 0; v < 3; ++v) {
    vec4 value = vec4(0.0);
    tiling_fetch_patch(patches, v, 1.0, value);
    for (int c = 0; c < TILING_CHANNELS; ++c)
      result_patches[base + v * TILING_RESULT_STRIDE + TILING_RESULT_FIRST + c] = value[c];
  }
#ifdef TILING_RESULT_LEVELS
  int extra = base + 3 * TILING_RESULT_STRIDE;
  for (int v = 0; v < 3; ++v) {
    result_patches[extra + v] = patches.weight[v];
    result_patches[extra + 3 + v] = float(patches.level[v]) + patches.level_blend[v];
    result_patches[extra + 6 + 3 * v] = patches.matrix[v][0][0];
    result_patches[extra + 7 + 3 * v] = patches.matrix[v][0][1];
    result_patches[extra + 8 + 3 * v] = patches.scale[v];
  }
  result_levels[2 * pixel] = float(level);
  result_levels[2 * pixel + 1] = level_blend;
#endif
#else
  vec4 g = tiling_blended_gaussian(skewed, origin_cell, origin_wrapped + p, seed, footprint_width,
                                   level, level_blend);
  vec4 value = tiling_inverse(g, level, level_blend);
#ifdef TILING_RESULT_STRIDE
  int pixel = local_pixel.y * dispatch_size.x + local_pixel.x;
  int index = pixel * TILING_RESULT_STRIDE + TILING_RESULT_FIRST;
  for (int c = 0; c < TILING_CHANNELS; ++c) result[index + c] = value[c];
#ifdef TILING_RESULT_LEVELS
  result_levels[2 * pixel] = float(level);
  result_levels[2 * pixel + 1] = level_blend;
#endif
#else
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * TILING_CHANNELS;
  for (int c = 0; c < TILING_CHANNELS; ++c) result[index + c] = value[c];
#endif
#endif
}
