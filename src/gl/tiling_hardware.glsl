// `render --backend gl --gl-filter hardware` for tiling: the patches are read from the
// Gaussianised exemplar as a mip-mapped GL texture (GL_REPEAT, trilinear, anisotropic where the
// driver has it) with textureGrad, as the paper's shader does (section 5.4: derivatives taken
// before the random offset, so the three patches share them). Compiled after tiling
// evaluate.glsl, both with TILING_TEXTURE_FILTER defined. The look-up of T^-1 stays the exact one, at
// the level of detail the CPU chooses for the footprint.

uniform sampler2D stochtex_tiling_exemplar;
// The footprint in texture coordinates, divided by sqrt(3): the hardware's level of detail is
// then log2(w) - log2(3) / 2, the CPU pyramid's (TilingModel::level_of_detail).
vec2 tiling_duv_dx;
vec2 tiling_duv_dy;

vec4 tiling_texture_fetch(float x, float y) {
  return textureGrad(stochtex_tiling_exemplar, vec2(x, y) / vec2(TILING_WIDTH, TILING_HEIGHT),
                     tiling_duv_dx, tiling_duv_dy);
}
