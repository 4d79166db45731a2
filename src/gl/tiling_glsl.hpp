#pragma once
// A tiling model as GLSL data: its constants as GLSL source and its arrays (each pyramid level's
// texels, 3-D table and 1-D tables) as one float array, for the GL renderer (a storage buffer) and
// `stochtex export-shader` (a texture).

#include <string>
#include <vector>

#include "gl/glsl_text.hpp"
#include "methods/tiling/model.hpp"

namespace stochtex::gl {

struct TilingGlsl {
  std::string constants;    // GLSL const declarations, TILING_* (exact float literals)
  std::vector<float> data;  // read by tiling_data_at() of tiling evaluate.glsl
};

TilingGlsl tiling_glsl(const tiling::TilingModel& model);

// random.glsl, the constants, tiling_data_at() and tiling evaluate.glsl: all but `#version`. The
// data is the storage buffer at binding 0, or the texture `stochtex_tiling_data` of
// pack_rgba(data).
std::string tiling_library_source(const TilingGlsl& glsl,
                                  DataSource source = DataSource::storage_buffers);

}  // namespace stochtex::gl
