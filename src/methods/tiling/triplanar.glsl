// Triplanar histogram-preserving blending (figure 16 of the tiling paper): the twin of
// TilingModel::evaluate_triplanar (model.cpp). Compiled after tiling entry.glsl (and, in the fast
// variant, hardware.glsl and fast_entry.glsl, TILING_TEXTURE_FILTER defined); requires
// random.glsl's cell_key and src/gl/triplanar.glsl.

// The engine-facing triplanar entry point: a surface point in exemplar pixels (model space), its
// unit normal, the screen derivatives of the position (dFdx(position), dFdy(position); zero = no
// filtering), the sharpness of the weights |n_k|^sharpness (1 to 64, 4 by default) and a seed.
// Plane k reads its patches at the level of detail of the footprint projected on it, with the
// seed cell_key(k, 0, seed, STREAM_OFFSETS); the planes are blended in Gaussian space (eq. 13)
// and T^-1 is looked up once, at the w^2-weighted mean of the planes' levels.
vec4 stochtex_tiling_triplanar(vec3 position, vec3 normal, vec3 dpdx, vec3 dpdy, float sharpness,
                               uint seed) {
  vec3 weights = stochtex_triplanar_weights(normal, sharpness);
  vec4 acc = vec4(0.0);
  float weight_squares = 0.0;
  float lod = 0.0;
  for (int k = 0; k < 3; ++k) {
    float w = weights[k];
    if (w == 0.0) continue;
    vec2 plane_dpdx = stochtex_on_plane(dpdx, k);
    vec2 plane_dpdy = stochtex_on_plane(dpdy, k);
    float width = tiling_footprint_width(plane_dpdx, plane_dpdy);
    float plane_lod = tiling_lod_of_width(width);
    int level = int(plane_lod);
    float level_blend = plane_lod - float(level);
#ifdef TILING_TEXTURE_FILTER
    tiling_set_gradients(plane_dpdx, plane_dpdy);
#endif
    vec4 g = tiling_blended_at(stochtex_on_plane(position, k),
                               cell_key(uint(k), 0u, seed, STREAM_OFFSETS), width, level,
                               level_blend);
    acc += w * (g - TILING_BLEND_MEAN);
    weight_squares += w * w;
    lod += w * w * (float(level) + level_blend);
  }
  float inverse_norm = TILING_BLEND == 2 ? 1.0 : 1.0 / sqrt(weight_squares);
  vec4 g = acc * inverse_norm + TILING_BLEND_MEAN;
  // The mean may round past the top level: clamped there with no blend (model.cpp).
  lod /= weight_squares;
  if (lod >= float(TILING_LEVELS - 1)) return tiling_inverse(g, TILING_LEVELS - 1, 0.0);
  int level = int(lod);
  return tiling_inverse(g, level, lod - float(level));
}
