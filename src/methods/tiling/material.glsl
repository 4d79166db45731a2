// A tiling material in an exported shader (`export-shader` of a material, docs/shaders.md
// "Materials"): every channel of the model at p, the twin of TilingModel::evaluate for N channels.
// The three patches (patches.glsl) are read apart, all N channels each (exact_fetch.glsl), then
// turned, weighed and blended (tiling_blend_patch_values) and put through each group's T^-1
// (tiling_groups_inverse, inverse_groups.glsl). Requires those files and the constants of
// tiling_material_glsl() (gl_data.cpp).

// The material's channels at p (exemplar pixels, |p| below ~1e4), with the arguments of
// stochtex_tiling: its screen derivatives (zero: no filtering) and a seed.
float[TILING_CHANNELS] tiling_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  float width = tiling_footprint_width(dpdx, dpdy);
  float lod = tiling_lod_of_width(width);
  int level = int(lod);
  float level_blend = lod - float(level);
  vec2 skewed;
  vec2 wrapped;
  tiling_lattice_at(p, skewed, wrapped);
  TilingPatches patches = tiling_patches(skewed, uvec2(0u), wrapped, seed, width, level,
                                         level_blend);
  float patch_values[3 * TILING_CHANNELS];
  float w[3];
  float lods[3];
  vec3 turns[3];
  for (int v = 0; v < 3; ++v) {
    int patch_level = patches.level[v];
    float patch_blend = patches.level_blend[v];
    TilingTaps fine = tiling_taps(patch_level, patches.position[v].x, patches.position[v].y);
    TilingTaps coarse = tiling_taps(min(patch_level + 1, TILING_LEVELS - 1),
                                    patches.position[v].x, patches.position[v].y);
    for (int c = 0; c < TILING_CHANNELS; ++c) {
      float value = 0.0;
      tiling_add_tap_value(fine, 1.0 - patch_blend, c, value);
      if (patch_blend > 0.0) tiling_add_tap_value(coarse, patch_blend, c, value);
      patch_values[v * TILING_CHANNELS + c] = value;
    }
    w[v] = patches.weight[v];
    lods[v] = float(patch_level) + patch_blend;
    turns[v] = vec3(patches.matrix[v][0][0], patches.matrix[v][0][1], patches.scale[v]);
  }
  float g[TILING_CHANNELS];
  tiling_blend_patch_values(patch_values, w, lods, turns, g, level, level_blend);
  return tiling_groups_inverse(g, level, level_blend);
}
