// Step 3 of Algorithm 1 (T^-1) for a model whose channels go through groups of their own (a
// material's maps, issue 18, or an image of more than 4 channels): the second pass of `render
// --backend gl` (gl_pass.cpp), the twin of TilingModel::inverse_transform. The first pass (tiling
// render.glsl, in chunks of up to 4 channels) wrote each pixel's blended Gaussian, all
// TILING_CHANNELS channels, to `result` and its level of detail (level, blend) to `result_levels`;
// this pass replaces the Gaussian by T^-1 in place. Requires the constants shared with the C++
// (Twin::kConstants), the groups' constants (tiling_groups_glsl() in gl_data.cpp), `float
// tiling_data_at(int index)` (each level's 1-D tables at TILING_LEVEL_TABLES) and tiling
// evaluate.glsl.

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) buffer Result { float result[]; };
layout(std430, binding = 2) readonly buffer ResultLevels { float result_levels[]; };

uniform ivec2 dispatch_size;

// A 1-D table of T^-1 at g (table_lookup): eq. (22), then linear interpolation.
float tiling_table(int offset, float g) {
  int cell;
  float t = tiling_table_coordinate(g, TILING_TABLE_SIZE, cell);
  float a = tiling_data_at(offset + cell);
  return a + t * (tiling_data_at(offset + cell + 1) - a);
}

// T^-1 at one pyramid level (inverse_at_level), group by group: one case per GroupTransform that
// the GPU twin has (the C++ refuses a model with any other).
void tiling_groups_at_level(float g[TILING_CHANNELS], int level, out float value[TILING_CHANNELS]) {
  for (int k = 0; k < TILING_GROUPS; ++k) {
    int first = TILING_GROUP_FIRST[k];
    int count = TILING_GROUP_CHANNELS[k];
    int tables = TILING_LEVEL_TABLES[level] + TILING_GROUP_TABLE[k] * TILING_TABLE_SIZE;
    switch (TILING_GROUP_TRANSFORM[k]) {
      case TILING_GROUP_DECORRELATED: {
        // 1-D tables on the group's principal axes, then back to its basis and mean (Deliot &
        // Heitz 2019).
        float decorrelated[TILING_CHANNELS];
        for (int c = 0; c < count; ++c)
          decorrelated[c] = tiling_table(tables + c * TILING_TABLE_SIZE, g[first + c]);
        int basis = TILING_GROUP_BASIS[k];
        for (int c = 0; c < count; ++c) {
          float v = TILING_COLOUR_MEAN[TILING_GROUP_MEAN[k] + c];
          for (int j = 0; j < count; ++j)
            v += TILING_COLOUR_BASIS[basis + c * count + j] * decorrelated[j];
          value[first + c] = v;
        }
        break;
      }
      case TILING_GROUP_DIRECT:
        // One channel, one table.
        value[first] = tiling_table(tables, g[first]);
        break;
    }
  }
}

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  int pixel = local_pixel.y * dispatch_size.x + local_pixel.x;
  int index = pixel * TILING_CHANNELS;
  float g[TILING_CHANNELS];
  for (int c = 0; c < TILING_CHANNELS; ++c) g[c] = result[index + c];
  // inverse_transform: the level's T^-1 blended with the next level's by the level blend.
  int level = int(result_levels[2 * pixel]);
  float level_blend = result_levels[2 * pixel + 1];
  float value[TILING_CHANNELS];
  tiling_groups_at_level(g, level, value);
  if (level_blend > 0.0) {
    float coarse[TILING_CHANNELS];
    tiling_groups_at_level(g, level + 1, coarse);
    for (int c = 0; c < TILING_CHANNELS; ++c) value[c] += level_blend * (coarse[c] - value[c]);
  }
  for (int c = 0; c < TILING_CHANNELS; ++c) result[index + c] = value[c];
}
