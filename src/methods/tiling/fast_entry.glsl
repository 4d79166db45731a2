// The engine-facing entry point of the fast variant (tiling hardware.glsl): p in exemplar pixels,
// its screen derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed.
vec4 stochtex_tiling(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  tiling_set_gradients(dpdx, dpdy);
  return tiling_at_level_of_detail(p, dpdx, dpdy, seed);
}
