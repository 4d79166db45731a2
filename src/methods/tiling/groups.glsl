// The second pass of `render --backend gl` for a model whose channels go through T^-1 in groups of
// their own (gl_pass.cpp). The first pass (tiling render.glsl, in chunks of up to 4 channels)
// wrote each pixel's blended Gaussian, all TILING_CHANNELS channels, to `result` (or its three
// patches apart to `result_patches`, TILING_PATCH_INPUT) and its level of detail (level, blend) to
// `result_levels`; this pass replaces the Gaussian by T^-1 in place. Requires
// inverse_groups.glsl.

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) buffer Result { float result[]; };
layout(std430, binding = 2) readonly buffer ResultLevels { float result_levels[]; };
#ifdef TILING_PATCH_INPUT
// The patches kept apart by the first pass (render.glsl, TILING_PATCH_OUTPUT): this pass turns
// the normal maps' slopes, weighs the patches by their heights and blends them (the per-patch path
// of TilingModel::blended_gaussian) before T^-1.
layout(std430, binding = 3) readonly buffer ResultPatches { float result_patches[]; };
#endif

uniform ivec2 dispatch_size;

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  int pixel = local_pixel.y * dispatch_size.x + local_pixel.x;
  int index = pixel * TILING_CHANNELS;
  int level = int(result_levels[2 * pixel]);
  float level_blend = result_levels[2 * pixel + 1];
  float g[TILING_CHANNELS];
#ifdef TILING_PATCH_INPUT
  int base = pixel * TILING_PATCH_STRIDE;
  int extra = base + 3 * TILING_CHANNELS;
  float patch_values[3 * TILING_CHANNELS];
  float w[3];
  float lods[3];
  vec3 turns[3];
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < TILING_CHANNELS; ++c)
      patch_values[v * TILING_CHANNELS + c] = result_patches[base + v * TILING_CHANNELS + c];
    w[v] = result_patches[extra + v];
    lods[v] = result_patches[extra + 3 + v];
    turns[v] = vec3(result_patches[extra + 6 + 3 * v], result_patches[extra + 7 + 3 * v],
                    result_patches[extra + 8 + 3 * v]);
  }
  tiling_blend_patch_values(patch_values, w, lods, turns, g, level, level_blend);
#else
  for (int c = 0; c < TILING_CHANNELS; ++c) g[c] = result[index + c];
#endif
  float value[TILING_CHANNELS] = tiling_groups_inverse(g, level, level_blend);
  for (int c = 0; c < TILING_CHANNELS; ++c) result[index + c] = value[c];
}
