// Histogram-preserving tiling and blending in GLSL: the twin of TilingModel::evaluate (model.cpp,
// evaluate.hpp), same lattice, same hashed offsets, same tables. Requires random.glsl, then the
// constants shared with the C++ (TILING_GAUSSIAN_*, TILING_INVERSE_SQRT3, TILING_LOD_BIAS:
// Twin::kConstants in gl_twin.hpp), the model's constants (tiling_glsl() in gl_data.cpp) and `float tiling_data_at(int index)`,
// the model's one float array: each level's texels, 3-D table and 1-D tables at the
// TILING_LEVEL_* offsets (a storage buffer in the renderer, a texture in an exported shader).

#ifdef TILING_TEXTURE_FILTER
// hardware.glsl
vec4 tiling_texture_fetch(float x, float y, mat2 patch_matrix);
vec3 tiling_texture_lut(vec3 g, int level);
#endif

// erf to 1.5e-7 (Abramowitz & Stegun 7.1.26): GLSL has none; the C++ uses its own rational erf
// (erf_rational, evaluate.hpp).
float tiling_erf(float x) {
  float t = 1.0 / (1.0 + 0.3275911 * abs(x));
  float y = 1.0 - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t +
                   0.254829592) * t * exp(-x * x);
  return x < 0.0 ? -y : y;
}

// Eq. (22) and table_coordinate: the cell and fraction of U = Phi(g) in a table of `size` cells.
float tiling_table_coordinate(float g, int size, out int first) {
  float u = 0.5 + 0.5 * tiling_erf((g - TILING_GAUSSIAN_MEAN) * TILING_ERF_SCALE);
  float last = float(size - 1);
  float x = clamp(u * float(size) - 0.5, 0.0, last);
  first = min(int(x), size - 2);
  return x - float(first);
}

// A 1-D table of T^-1 at `offset` in the model's array at g (table_lookup): eq. (22), then linear
// interpolation.
float tiling_table(int offset, float g) {
  int cell;
  float t = tiling_table_coordinate(g, TILING_TABLE_SIZE, cell);
  float a = tiling_data_at(offset + cell);
  return a + t * (tiling_data_at(offset + cell + 1) - a);
}


// TilingModel::footprint_width: the footprint's longer axis (isotropic).
float tiling_footprint_width(vec2 dpdx, vec2 dpdy) {
  return max(length(dpdx), length(dpdy));
}

// TilingModel::level_of_detail of a footprint's width as one value: level int(lod) blended with
// the next by its fraction.
float tiling_lod_of_width(float width) {
  float lod = width > 1.0 ? log2(width) - TILING_LOD_BIAS : 0.0;
  return clamp(lod, 0.0, float(TILING_LEVELS - 1));
}
