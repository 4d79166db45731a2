// Step 1 of Algorithm 1: the three patches around a point, each with its blend weight (sharpened,
// sharpen_weights), where it is read (exemplar pixels), its transform M (patch_transform, the
// rotation and scale jitter) and its level of detail. `skewed` is the position in skewed lattice
// units relative to the lattice cell `origin_cell` (low 32 bits), `wrapped` the position modulo
// the exemplar's period; both formed on the CPU in double for the far part. `width` is the
// footprint's (0: a point sample), `level`, `level_blend` its level of detail; with scale jitter
// each patch reads its own level. The artist controls (TILING_ROTATION, TILING_SCALE_JITTER,
// TILING_SHARPNESS) are the model's constants: with their defaults the compiler removes their
// code.
struct TilingPatches {
  float weight[3];
  vec2 position[3];
  mat2 matrix[3];
  float scale[3];
  int level[3];
  float level_blend[3];
};

TilingPatches tiling_patches(vec2 skewed, uvec2 origin_cell, vec2 wrapped, uint seed, float width,
                             int level, float level_blend) {
  TilingPatches patches;
  vec2 cell = floor(skewed);
  vec2 f = skewed - cell;
  bool lower = f.x + f.y < 1.0;
  ivec2 d[3] = ivec2[3](lower ? ivec2(0, 0) : ivec2(1, 1), lower ? ivec2(1, 0) : ivec2(0, 1),
                        lower ? ivec2(0, 1) : ivec2(1, 0));
  patches.weight = lower ? float[3](1.0 - f.x - f.y, f.x, f.y)
                         : float[3](f.x + f.y - 1.0, 1.0 - f.x, 1.0 - f.y);
  if (TILING_SHARPNESS != 1.0) {
    // sharpen_weights (evaluate.hpp): Burley 2019's exponent, renormalised.
    float sum = 0.0;
    for (int v = 0; v < 3; ++v) {
      patches.weight[v] = pow(patches.weight[v], TILING_SHARPNESS);
      sum += patches.weight[v];
    }
    for (int v = 0; v < 3; ++v) patches.weight[v] /= sum;
  }
  for (int v = 0; v < 3; ++v) {
    uvec2 vertex = origin_cell + uvec2(ivec2(cell) + d[v]);
    CounterRng rng = CounterRng(cell_key(vertex.x, vertex.y, seed, STREAM_OFFSETS), 0u);
    uint draw_u = rng_next(rng);
    uint draw_v = rng_next(rng);
    uint high;
    uint low;
    umulExtended(draw_u, uint(TILING_WIDTH), high, low);
    float offset_x = float(high);
    umulExtended(draw_v, uint(TILING_HEIGHT), high, low);
    float offset_y = float(high);
    float x = wrapped.x + offset_x;
    float y = wrapped.y + offset_y;
    patches.matrix[v] = mat2(1.0);
    patches.scale[v] = 1.0;
    patches.level[v] = level;
    patches.level_blend[v] = level_blend;
    if (TILING_TRANSFORMED) {
      // patch_transform and patch_shift (evaluate.hpp): rotation and scale about the vertex.
      CounterRng draws =
          CounterRng(cell_key(vertex.x, vertex.y, seed, TILING_STREAM_TRANSFORMS), 0u);
      float angle_draw = rng_uniform(draws);
      float scale_draw = rng_uniform(draws);
      float angle = TILING_ROTATION * (2.0 * angle_draw - 1.0);
      float patch_scale = exp2(TILING_SCALE_JITTER * (2.0 * scale_draw - 1.0));
      float c = patch_scale * cos(angle);
      float s = patch_scale * sin(angle);
      patches.matrix[v] = mat2(c, s, -s, c);
      patches.scale[v] = patch_scale;
      vec2 from_vertex = f - vec2(d[v]);
      float local_x = TILING_EDGE * (from_vertex.x + 0.5 * from_vertex.y);
      float local_y = TILING_EDGE * from_vertex.y * (1.5 * TILING_INVERSE_SQRT3);
      x += (c - 1.0) * local_x - s * local_y;
      y += s * local_x + (c - 1.0) * local_y;
      if (TILING_SCALE_JITTER > 0.0) {
        float lod = tiling_lod_of_width(width * patch_scale);
        patches.level[v] = int(lod);
        patches.level_blend[v] = lod - float(patches.level[v]);
      }
    }
    patches.position[v] = vec2(x, y);
  }
  return patches;
}

// Adds weight * patch v of `patches` (its level of detail blended with the next) to acc.
void tiling_fetch_patch(TilingPatches patches, int v, float weight, inout vec4 acc) {
  vec2 at = patches.position[v];
#ifdef TILING_TEXTURE_FILTER
  // `render --gl-filter hardware` (hardware.glsl): one mip-mapped, anisotropic texture fetch of
  // the patch instead of the exact trilinear reads of the pyramid.
  acc += weight * tiling_texture_fetch(at.x, at.y, patches.matrix[v]);
#else
  int patch_level = patches.level[v];
  float patch_blend = patches.level_blend[v];
  tiling_fetch(patch_level, at.x, at.y, weight * (1.0 - patch_blend), acc);
  if (patch_blend > 0.0)
    tiling_fetch(min(patch_level + 1, TILING_LEVELS - 1), at.x, at.y, weight * patch_blend, acc);
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

