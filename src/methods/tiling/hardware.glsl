// `render --backend gl --gl-filter hardware` for tiling: the patches are read from the
// Gaussianised exemplar as a mip-mapped GL texture (GL_REPEAT, trilinear, anisotropic where the
// driver has it) with textureGrad, as the paper's shader does (section 5.4: derivatives taken
// before the random offset, so the three patches share them), and the 3-D table of T^-1 as a 3-D
// texture read with hardware trilinear interpolation, at the pyramid level the CPU chooses for the
// footprint (the 1-D tables of the per-channel transport stay the exact reads). Compiled after
// tiling evaluate.glsl, both with TILING_TEXTURE_FILTER defined.

uniform sampler2D stochtex_tiling_exemplar;
// The footprint in texture coordinates, divided by sqrt(3): the hardware's level of detail is
// then log2(w) - log2(3) / 2, the CPU pyramid's (TilingModel::level_of_detail).
vec2 tiling_duv_dx;
vec2 tiling_duv_dy;

vec4 tiling_texture_fetch(float x, float y) {
  return textureGrad(stochtex_tiling_exemplar, vec2(x, y) / vec2(TILING_WIDTH, TILING_HEIGHT),
                     tiling_duv_dx, tiling_duv_dy);
}

// The 3-D tables of all levels, stacked along z (level l in slices l n .. l n + n - 1): the
// coordinates of table_coordinate, between texel centres of one level, so the hardware's
// trilinear interpolation never mixes two levels.
uniform sampler3D stochtex_tiling_lut;

vec3 tiling_texture_lut(vec3 g, int level) {
  vec3 cell;
  for (int c = 0; c < 3; ++c) {
    int first;
    float t = tiling_table_coordinate(g[c], TILING_LUT_SIZE, first);
    cell[c] = float(first) + t;
  }
  float n = float(TILING_LUT_SIZE);
  float depth = n * float(TILING_LEVELS);
  vec3 uvw = vec3((cell.xy + 0.5) / n, (float(level) * n + cell.z + 0.5) / depth);
  return textureLod(stochtex_tiling_lut, uvw, 0.0).rgb;
}
