// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. The level
// of detail is TilingModel::level_of_detail's; keep |p| below ~1e4 for full precision.
vec4 stochtex_tiling(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  int level = 0;
  float level_blend = 0.0;
  float width = max(length(dpdx), length(dpdy));
  float lod = width > 1.0 ? log2(width) - TILING_LOD_BIAS : 0.0;
  if (lod >= float(TILING_LEVELS - 1)) {
    level = TILING_LEVELS - 1;
  } else if (lod > 0.0) {
    level = int(lod);
    level_blend = lod - float(level);
  }
  vec2 skewed = vec2(p.x - p.y * TILING_INVERSE_SQRT3, 2.0 * TILING_INVERSE_SQRT3 * p.y) /
                TILING_EDGE;
  vec2 period = vec2(TILING_WIDTH, TILING_HEIGHT);
  vec2 wrapped = p - period * floor(p / period);
  vec4 g = tiling_blended_gaussian(skewed, uvec2(0u), wrapped, seed, level, level_blend);
  return tiling_inverse(g, level, level_blend);
}
