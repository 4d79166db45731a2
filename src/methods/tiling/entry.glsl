// TilingModel::level_of_detail as one value: level int(lod) blended with the next by its fraction.
float tiling_level_of_detail(vec2 dpdx, vec2 dpdy) {
  return tiling_lod_of_width(tiling_footprint_width(dpdx, dpdy));
}

// Steps 1-2 of Algorithm 1 at p (exemplar pixels, |p| below ~1e4) with the patches of `seed`, for
// a footprint of width `width` at `level`, `level_blend` (which become T^-1's, tiling blend.glsl).
vec4 tiling_blended_at(vec2 p, uint seed, float width, inout int level, inout float level_blend) {
  vec2 skewed;
  vec2 wrapped;
  tiling_lattice_at(p, skewed, wrapped);
  return tiling_blended_gaussian(skewed, uvec2(0u), wrapped, seed, width, level, level_blend);
}

// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. The level
// of detail is TilingModel::level_of_detail's; keep |p| below ~1e4 for full precision.
vec4 stochtex_tiling(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  float width = tiling_footprint_width(dpdx, dpdy);
  float lod = tiling_lod_of_width(width);
  int level = int(lod);
  float level_blend = lod - float(level);
  vec4 g = tiling_blended_at(p, seed, width, level, level_blend);
  return tiling_inverse(g, level, level_blend);
}
