// Step 3 of Algorithm 1 (T^-1) for a model whose channels go through groups of their own (a
// material's maps, issue 18, or an image of more than 4 channels), and the per-patch blend of the
// controls that need every channel (the height-aware blend, turned slopes): the twins of
// TilingModel::inverse_transform and of blended_gaussian's per-patch path, shared by the render's
// second pass (groups.glsl) and an exported material (material.glsl). Requires the constants
// shared with the C++ (Twin::kConstants), the groups' constants (append_groups in gl_data.cpp),
// `float tiling_data_at(int index)` (each level's 1-D tables at TILING_LEVEL_TABLES) and tiling
// evaluate.glsl.

// radial_lookup (evaluate.hpp): |s| of the radial table at `offset` at the Gaussian radius rho,
// linear in the Rayleigh CDF U = 1 - exp(-rho^2 / (2 sigma^2)), clamped at the ends.
float tiling_radial_lookup(int offset, float rho) {
  float u = 1.0 - exp(-0.5 * rho * rho / (TILING_GAUSSIAN_DEVIATION * TILING_GAUSSIAN_DEVIATION));
  float x = clamp(u * float(TILING_TABLE_SIZE) - 0.5, 0.0, float(TILING_TABLE_SIZE - 1));
  int first = min(int(x), TILING_TABLE_SIZE - 2);
  float a = tiling_data_at(offset + first);
  return a + (x - float(first)) * (tiling_data_at(offset + first + 1) - a);
}

// radial_inverse: the Gaussian radius of the slope magnitude r, by bisection on the table.
float tiling_radial_inverse(int offset, float r) {
  int size = TILING_TABLE_SIZE;
  if (!(r > tiling_data_at(offset)))
    return TILING_GAUSSIAN_DEVIATION * sqrt(-2.0 * log(1.0 - 0.5 / float(size)));
  if (!(r < tiling_data_at(offset + size - 1)))
    return TILING_GAUSSIAN_DEVIATION * sqrt(-2.0 * log(0.5 / float(size)));
  int low = 0;
  int high = size - 1;
  while (high - low > 1) {
    int middle = (low + high) / 2;
    if (tiling_data_at(offset + middle) < r)
      low = middle;
    else
      high = middle;
  }
  float a = tiling_data_at(offset + low);
  float t = (r - a) / (tiling_data_at(offset + high) - a);
  return TILING_GAUSSIAN_DEVIATION * sqrt(-2.0 * log(1.0 - (float(low) + 0.5 + t) / float(size)));
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
      case TILING_GROUP_RADIAL: {
        // A normal map's slopes: the magnitude from the radial table along g's direction.
        vec2 d = vec2(g[first], g[first + 1]) - TILING_GAUSSIAN_MEAN;
        float rho = length(d);
        float magnitude = rho > 0.0 ? tiling_radial_lookup(tables, rho) / rho : 0.0;
        value[first] = magnitude * d.x;
        value[first + 1] = magnitude * d.y;
        break;
      }
    }
  }
}

// turn_slopes (evaluate.hpp): a patch's slopes at `first` of `values` (the three patches' channels
// one after another) turned by its transform (scale cos, scale sin, scale), their magnitude scaled
// through the level-0 radial table at `table`.
void tiling_turn_slopes(vec3 turn, int table, int first, inout float values[3 * TILING_CHANNELS]) {
  float dx = values[first] - TILING_GAUSSIAN_MEAN;
  float dy = values[first + 1] - TILING_GAUSSIAN_MEAN;
  float factor = 1.0 / turn.z;
  if (turn.z != 1.0) {
    float rho = sqrt(dx * dx + dy * dy);
    if (rho > 0.0)
      factor *= tiling_radial_inverse(table, turn.z * tiling_radial_lookup(table, rho)) / rho;
  }
  values[first] = TILING_GAUSSIAN_MEAN + factor * (turn.x * dx - turn.y * dy);
  values[first + 1] = TILING_GAUSSIAN_MEAN + factor * (turn.y * dx + turn.x * dy);
}

// The per-patch path of blended_gaussian: the patches' values (their channels one patch after
// another, blend weights,
// levels of detail and transforms: scale cos, scale sin, scale) turned, weighed by their heights
// (height_blend_weights) and blended by eq. (13); the level of detail of the scale jitter from
// the final weights.
void tiling_blend_patch_values(float patch_values[3 * TILING_CHANNELS], float w[3], float lods[3],
                               vec3 turns[3], out float g[TILING_CHANNELS], inout int level,
                               inout float level_blend) {
  if (TILING_TURNED)
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < TILING_GROUPS; ++k)
        if (TILING_GROUP_TRANSFORM[k] == TILING_GROUP_RADIAL)
          tiling_turn_slopes(turns[v],
                             TILING_LEVEL_TABLES[0] + TILING_GROUP_TABLE[k] * TILING_TABLE_SIZE,
                             v * TILING_CHANNELS + TILING_GROUP_FIRST[k], patch_values);
  if (TILING_HEIGHT_DEPTH > 0.0) {
    float top = -1e30;  // below every height + weight
    for (int v = 0; v < 3; ++v)
      if (w[v] > 0.0)
        top = max(top, patch_values[v * TILING_CHANNELS + TILING_HEIGHT_CHANNEL] + w[v]);
    float sum = 0.0;
    for (int v = 0; v < 3; ++v) {
      float below = patch_values[v * TILING_CHANNELS + TILING_HEIGHT_CHANNEL] + w[v] - top;
      w[v] = w[v] > 0.0 ? w[v] * (below < 0.0 ? exp(below / TILING_HEIGHT_DEPTH) : 1.0) : 0.0;
      sum += w[v];
    }
    for (int v = 0; v < 3; ++v) w[v] /= sum;
  }
  float weight_squares = 0.0;
  float weighted_lod = 0.0;
  for (int c = 0; c < TILING_CHANNELS; ++c) g[c] = 0.0;
  for (int v = 0; v < 3; ++v) {
    weight_squares += w[v] * w[v];
    weighted_lod += w[v] * w[v] * lods[v];
    for (int c = 0; c < TILING_CHANNELS; ++c)
      g[c] += w[v] * patch_values[v * TILING_CHANNELS + c];
  }
  float inverse_norm = 1.0 / sqrt(weight_squares);
  for (int c = 0; c < TILING_CHANNELS; ++c)
    g[c] = (g[c] - TILING_BLEND_MEANS[c]) * inverse_norm + TILING_BLEND_MEANS[c];
  if (TILING_SCALE_JITTER_ON) {
    // TilingModel::split_level of the mean, clamped at the top level.
    float lod = weighted_lod / weight_squares;
    level = lod >= float(TILING_LEVELS - 1) ? TILING_LEVELS - 1 : int(lod);
    level_blend = lod >= float(TILING_LEVELS - 1) ? 0.0 : lod - float(level);
  }
}

// inverse_transform: T^-1 of g at `level`, blended with the next level's by `level_blend`.
float[TILING_CHANNELS] tiling_groups_inverse(float g[TILING_CHANNELS], int level,
                                             float level_blend) {
  float value[TILING_CHANNELS];
  tiling_groups_at_level(g, level, value);
  if (level_blend > 0.0) {
    float coarse[TILING_CHANNELS];
    tiling_groups_at_level(g, level + 1, coarse);
    for (int c = 0; c < TILING_CHANNELS; ++c) value[c] += level_blend * (coarse[c] - value[c]);
  }
  return value;
}
