// The engine-facing entry point (`stochtex export-shader`): p in exemplar pixels, its screen
// derivatives (dFdx(p), dFdy(p) in a fragment shader; zero = no filtering) and a seed. The
// strata's lattice nodes come from p in float: keep |p| below ~1e4 for full precision.
vec4 stochtex_lrp(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  vec4 noise = vec4(0.0);
  for (int s = 0; s < LRP_STRATA_TOTAL; ++s) {
    if (LRP_STRATUM_AMPLITUDE[s] == 0.0) continue;
    uint stratum_seed = cell_key(uint(s / LRP_STRATA), uint(s % LRP_STRATA), seed, STREAM_PHASES);
    noise[LRP_STRATUM_CHANNEL[s]] += lrp_stratum_noise(s, p / LRP_STRATUM_SPACING[s], uvec2(0u),
                                                       stratum_seed, true, dpdx, dpdy);
  }
  if (LRP_HAS_STRUCTURE) {
    // The origin is 0: the structure origin and placement block are 0, the placement grid is
    // offset by half a block (add_structure), turbulence nodes come from p itself.
    uvec2 nodes[LRP_TURBULENCE_ARRAY];
    vec2 offsets[LRP_TURBULENCE_ARRAY];
    uint seeds[2 * LRP_TURBULENCE_ARRAY];
    for (int t = 0; t < LRP_TURBULENCE_ARRAY; ++t) {
      nodes[t] = uvec2(0u);
      offsets[t] = vec2(0.0);
      for (int axis = 0; axis < 2; ++axis)
        seeds[axis * LRP_TURBULENCE_ARRAY + t] =
            cell_key(uint(LRP_TURBULENCE_STREAM_BASE + axis), uint(t), seed, STREAM_PHASES);
    }
    lrp_add_structure(p, vec2(0.0), uvec2(0u), vec2(-0.5), nodes, offsets, seeds, seed, true, dpdx,
                      dpdy, noise);
  }
  return lrp_colour(noise);
}
