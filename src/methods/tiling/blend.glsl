// Adds weight * patch v of `patches` (its level of detail blended with the next) to acc.
void tiling_fetch_patch(TilingPatches patches, int v, float weight, inout vec4 acc) {
  vec2 at = patches.position[v];
#ifdef TILING_TEXTURE_FILTER
  // `render --gl-filter hardware` (hardware.glsl): one mip-mapped, anisotropic texture fetch of
  // the patch instead of the exact trilinear reads of the pyramid.
  acc += weight * tiling_texture_fetch(at.x, at.y, patches.matrix[v]);
#else
  // The exact fetch (exact_fetch.glsl): bilinear and periodic at the patch's level, blended with
  // the next level's.
  int patch_level = patches.level[v];
  float patch_blend = patches.level_blend[v];
  TilingTaps fine = tiling_taps(patch_level, at.x, at.y);
  for (int c = 0; c < TILING_CHANNELS; ++c)
    tiling_add_tap_value(fine, weight * (1.0 - patch_blend), c, acc[c]);
  if (patch_blend > 0.0) {
    TilingTaps coarse = tiling_taps(min(patch_level + 1, TILING_LEVELS - 1), at.x, at.y);
    for (int c = 0; c < TILING_CHANNELS; ++c)
      tiling_add_tap_value(coarse, weight * patch_blend, c, acc[c]);
  }
#endif
}

// Step 2 (blended_gaussian): the patches blended by eq. (13) (eq. 3 for linear blending); with
// scale jitter, `level` and `level_blend` become T^-1's: the w^2-weighted mean of the patches'.
vec4 tiling_blended_gaussian(vec2 skewed, uvec2 origin_cell, vec2 wrapped, uint seed, float width,
                             inout int level, inout float level_blend) {
  TilingPatches patches = tiling_patches(skewed, origin_cell, wrapped, seed, width, level,
                                         level_blend);
  vec4 acc = vec4(0.0);
  float weight_squares = 0.0;
  float weighted_lod = 0.0;
  for (int v = 0; v < 3; ++v) {
    float w = patches.weight[v];
    weight_squares += w * w;
    if (TILING_SCALE_JITTER > 0.0)
      weighted_lod += w * w * (float(patches.level[v]) + patches.level_blend[v]);
    tiling_fetch_patch(patches, v, w, acc);
  }
  if (TILING_SCALE_JITTER > 0.0) {
    // TilingModel::split_level of the mean, clamped at the top level.
    float lod = weighted_lod / weight_squares;
    level = lod >= float(TILING_LEVELS - 1) ? TILING_LEVELS - 1 : int(lod);
    level_blend = lod >= float(TILING_LEVELS - 1) ? 0.0 : lod - float(level);
  }
  float inverse_norm = TILING_BLEND == 2 ? 1.0 : 1.0 / sqrt(weight_squares);
  return (acc - TILING_BLEND_MEAN) * inverse_norm + TILING_BLEND_MEAN;
}

// Step 3 at one pyramid level (inverse_at_level).
vec4 tiling_inverse_at_level(vec4 g, int level) {
  vec4 result = vec4(0.0);
  if (TILING_COLOUR_LUT) {
#ifdef TILING_TEXTURE_FILTER
    result.rgb = tiling_texture_lut(g.rgb, level);
#else
    int n = TILING_LUT_SIZE;
    ivec3 cell;
    vec3 t;
    for (int c = 0; c < 3; ++c) {
      int first;
      t[c] = tiling_table_coordinate(g[c], n, first);
      cell[c] = first;
    }
    int step_y = n * 3;
    int step_z = step_y * n;
    int base = TILING_LEVEL_LUT[level] + cell.z * step_z + cell.y * step_y + cell.x * 3;
    for (int c = 0; c < 3; ++c) {
      int p = base + c;
      float x00 = tiling_data_at(p) + t.x * (tiling_data_at(p + 3) - tiling_data_at(p));
      float x10 = tiling_data_at(p + step_y) +
                  t.x * (tiling_data_at(p + step_y + 3) - tiling_data_at(p + step_y));
      float x01 = tiling_data_at(p + step_z) +
                  t.x * (tiling_data_at(p + step_z + 3) - tiling_data_at(p + step_z));
      float x11 = tiling_data_at(p + step_z + step_y) +
                  t.x * (tiling_data_at(p + step_z + step_y + 3) - tiling_data_at(p + step_z + step_y));
      float y0 = x00 + t.y * (x10 - x00);
      float y1 = x01 + t.y * (x11 - x01);
      result[c] = y0 + t.z * (y1 - y0);
    }
#endif
  } else {
    vec3 decorrelated = vec3(0.0);
    for (int c = 0; c < TILING_COLOUR_CHANNELS; ++c)
      decorrelated[c] = tiling_table(TILING_LEVEL_TABLES[level] + c * TILING_TABLE_SIZE, g[c]);
    for (int c = 0; c < TILING_COLOUR_CHANNELS; ++c) {
      float value = TILING_COLOUR_MEAN[c];
      for (int k = 0; k < TILING_COLOUR_CHANNELS; ++k)
        value += TILING_COLOUR_BASIS[c * TILING_COLOUR_CHANNELS + k] * decorrelated[k];
      result[c] = value;
    }
  }
  if (TILING_HAS_ALPHA)
    result[TILING_CHANNELS - 1] = tiling_table(
        TILING_LEVEL_TABLES[level] + TILING_FIRST_ALPHA_TABLE * TILING_TABLE_SIZE,
        g[TILING_CHANNELS - 1]);
  return result;
}

// Step 3 (inverse_transform): the identity for the variance and linear blends.
vec4 tiling_inverse(vec4 g, int level, float level_blend) {
  if (TILING_BLEND != 0) return g;
  vec4 result = tiling_inverse_at_level(g, level);
  if (level_blend > 0.0) result += level_blend * (tiling_inverse_at_level(g, level + 1) - result);
  return result;
}

