// TilingModel::level_of_detail as one value: level int(lod) blended with the next by its fraction.
float tiling_level_of_detail(vec2 dpdx, vec2 dpdy) {
  float width = max(length(dpdx), length(dpdy));
  float lod = width > 1.0 ? log2(width) - TILING_LOD_BIAS : 0.0;
  return clamp(lod, 0.0, float(TILING_LEVELS - 1));
}

// Steps 1-2 of Algorithm 1 at p (exemplar pixels, |p| below ~1e4) with the patches of `seed`.
vec4 tiling_blended_at(vec2 p, uint seed, int level, float level_blend) {
  vec2 skewed = vec2(p.x - p.y * TILING_INVERSE_SQRT3, 2.0 * TILING_INVERSE_SQRT3 * p.y) /
                TILING_EDGE;
  vec2 period = vec2(TILING_WIDTH, TILING_HEIGHT);
  vec2 wrapped = p - period * floor(p / period);
  return tiling_blended_gaussian(skewed, uvec2(0u), wrapped, seed, level, level_blend);
}

// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. The level
// of detail is TilingModel::level_of_detail's; keep |p| below ~1e4 for full precision.
vec4 stochtex_tiling(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  float lod = tiling_level_of_detail(dpdx, dpdy);
  int level = int(lod);
  float level_blend = lod - float(level);
  return tiling_inverse(tiling_blended_at(p, seed, level, level_blend), level, level_blend);
}
