// `render --backend gl --gl-filter hardware` for texton noise: each impact reads the texton from
// a mip-mapped GL texture (trilinear, anisotropic where the driver has it) with textureGrad, the
// prefiltered-texton filtering of the paper (section 5) done by the texture units. The texture is
// level 0 of the pyramid (padded texels, bilinear = the order-1 B-spline) with GL's mip chain,
// its finest levels capped at the model's coarsest (beyond it texton_noise fades the fluctuation
// as the exact path does). Compiled after texton evaluate.glsl, both with TEXTON_TEXTURE_FILTER.

uniform sampler2D stochtex_texton_texture;
// The footprint in texture coordinates, divided by sqrt(3): the hardware's level of detail is
// then log2(w) - log2(3) / 2, the CPU's (filter_setup).
vec2 texton_duv_dx;
vec2 texton_duv_dy;

vec4 texton_texture_fetch(float dx, float dy) {
  vec2 texel = (vec2(dx, dy) - TEXTON_LEVEL_FIRST_TEXEL[0]) / TEXTON_LEVEL_SPACING[0] +
               float(TEXTON_PADDING) + 0.5;
  return textureGrad(stochtex_texton_texture, texel / vec2(textureSize(stochtex_texton_texture, 0)),
                     texton_duv_dx, texton_duv_dy);
}
