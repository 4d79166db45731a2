// The fast variant of tiling (`render --backend gl --gl-filter hardware`, `export-shader
// --variant fast`): the patches are read from the Gaussianised exemplar as a mip-mapped texture
// (GL_REPEAT, trilinear, anisotropic where the driver has it) with textureGrad, as the paper's
// shader does (section 5.4: derivatives taken before the random offset, so the three patches share
// them: 3 fetches), and T^-1's 3-D table of the footprint's pyramid level (the per-level
// prefiltering of Deliot & Heitz 2019) from a 3-D texture with hardware trilinear interpolation
// (+ 1 fetch); the 1-D tables of the per-channel transport stay exact reads of
// `tiling_data_at`. Compiled after tiling evaluate.glsl and blend.glsl, before entry.glsl (whose
// stochtex_tiling the library renames tiling_at_level_of_detail) and fast_entry.glsl, all with
// TILING_TEXTURE_FILTER defined.

uniform sampler2D stochtex_tiling_exemplar;
// The footprint in texture coordinates, divided by sqrt(3): the hardware's level of detail is
// then log2(w) - log2(3) / 2, the CPU pyramid's (TilingModel::level_of_detail).
vec2 tiling_duv_dx;
vec2 tiling_duv_dy;

// The footprint of p (its screen derivatives, exemplar pixels) for the texture fetches.
void tiling_set_gradients(vec2 dpdx, vec2 dpdy) {
  vec2 texel = TILING_INVERSE_SQRT3 / vec2(TILING_WIDTH, TILING_HEIGHT);
  tiling_duv_dx = dpdx * texel;
  tiling_duv_dy = dpdy * texel;
}

// The texture holds (value - 1/2) / TILING_TEXTURE_SCALE + 1/2, which fits [0, 1] (gl_data.cpp):
// an affine map, so it commutes with the hardware's filtering. `patch_matrix` is the patch's
// rotation and scale (the artist controls; the identity without them): the footprint turns with it.
vec4 tiling_texture_fetch(float x, float y, mat2 patch_matrix) {
  vec2 period = vec2(TILING_WIDTH, TILING_HEIGHT);
  vec2 duv_dx = tiling_duv_dx;
  vec2 duv_dy = tiling_duv_dy;
  if (TILING_TRANSFORMED) {
    duv_dx = patch_matrix * (duv_dx * period) / period;
    duv_dy = patch_matrix * (duv_dy * period) / period;
  }
  vec4 stored = textureGrad(stochtex_tiling_exemplar, vec2(x, y) / period, duv_dx, duv_dy);
  return (stored - 0.5) * TILING_TEXTURE_SCALE + 0.5;
}

#ifdef TILING_LUT_TEXTURE
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
#else
// This model has no 3-D table (TILING_COLOUR_LUT is false): never called.
vec3 tiling_texture_lut(vec3 g, int level) {
  return vec3(0.0);
}
#endif
