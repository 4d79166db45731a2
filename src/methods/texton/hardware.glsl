// The fast variant of texton noise (`render --backend gl --gl-filter hardware`, `export-shader
// --variant fast`): each impact reads the texton from a mip-mapped texture (trilinear,
// anisotropic where the driver has it) with textureGrad, the prefiltered-texton filtering of the
// paper (section 5) done by the texture units. The texture is level 0 of the pyramid (padded
// texels, bilinear = the order-1 B-spline) with generated mip-maps, capped at the model's coarsest
// level (beyond it texton_noise fades the fluctuation as the exact path does). Compiled after
// texton evaluate.glsl, before impulses.glsl, noise.glsl, entry.glsl (whose stochtex_texton the
// library renames texton_at_level_of_detail) and fast_entry.glsl, all with TEXTON_TEXTURE_FILTER
// defined.

uniform sampler2D stochtex_texton_texture;
// The footprint in texture coordinates, divided by sqrt(3): the hardware's level of detail is
// then log2(w) - log2(3) / 2, the CPU's (filter_setup).
vec2 texton_duv_dx;
vec2 texton_duv_dy;

// The footprint of p (its screen derivatives, exemplar pixels) for the texture fetches.
void texton_set_gradients(vec2 dpdx, vec2 dpdy) {
  vec2 texel = exp2(-TEXTON_LOD_BIAS) / (TEXTON_LEVEL_SPACING[0] *
                                         vec2(textureSize(stochtex_texton_texture, 0)));
  texton_duv_dx = dpdx * texel;
  texton_duv_dy = dpdy * texel;
}

vec4 texton_texture_fetch(float dx, float dy) {
  vec2 texel = (vec2(dx, dy) - TEXTON_LEVEL_FIRST_TEXEL[0]) / TEXTON_LEVEL_SPACING[0] +
               float(TEXTON_PADDING) + 0.5;
  return textureGrad(stochtex_texton_texture, texel / vec2(textureSize(stochtex_texton_texture, 0)),
                     texton_duv_dx, texton_duv_dy);
}
