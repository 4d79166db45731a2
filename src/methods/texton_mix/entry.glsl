// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels (model space, where
// the mixing field lives), its screen derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no
// filtering) and a seed. Keep |p| below ~1e4 for full precision.
vec4 stochtex_texton_mix(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  return texton_mix_noise(p, uvec2(0u), seed, texton_filter(dpdx, dpdy));
}
