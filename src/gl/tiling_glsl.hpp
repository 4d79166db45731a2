#pragma once
// A tiling model as GLSL data: its constants as GLSL source and its arrays (each pyramid level's
// texels, 3-D table and 1-D tables) as one float buffer, for the GL renderer.

#include <string>
#include <vector>

#include "methods/tiling/model.hpp"

namespace stochtex::gl {

struct TilingGlsl {
  std::string constants;    // GLSL const declarations, TILING_* (exact float literals)
  std::vector<float> data;  // the storage buffer `tiling_data` of tiling evaluate.glsl
};

TilingGlsl tiling_glsl(const tiling::TilingModel& model);

// random.glsl, the constants and tiling evaluate.glsl: all but `#version`.
std::string tiling_library_source(const TilingGlsl& glsl);

}  // namespace stochtex::gl
