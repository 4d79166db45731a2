#pragma once
// A texton model as GLSL data: its constants as GLSL source and its texel pyramid as one RGBA
// atlas image. Used by the GL renderer and by `stochtex export-shader`, so both run the same code.

#include <string>

#include "methods/texton/model.hpp"
#include "stochtex/image.hpp"

namespace stochtex::gl {

struct TextonGlsl {
  std::string constants;  // GLSL const declarations (exact: every float reads back unchanged)
  ImageF atlas;           // 4 channels; level l's padded texels start at row level_rows[l]
};

TextonGlsl texton_glsl(const texton::TextonModel& model);

// random.glsl, the constants, the atlas sampler and evaluate.glsl: all but `#version`.
std::string texton_library_source(const TextonGlsl& glsl);

}  // namespace stochtex::gl
