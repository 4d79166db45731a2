// The engine-facing entry point of the fast variant (texton hardware.glsl): p in exemplar pixels,
// its screen derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed.
vec4 stochtex_texton(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  texton_set_gradients(dpdx, dpdy);
  return texton_at_level_of_detail(p, dpdx, dpdy, seed);
}
