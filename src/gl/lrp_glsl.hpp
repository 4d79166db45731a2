#pragma once
// An LRP model as GLSL data: its constants as GLSL source, its frequency and sub-stratum tables as
// storage-buffer contents, for the GL renderer.

#include <cstdint>
#include <string>
#include <vector>

#include "methods/lrp/model.hpp"

namespace stochtex::gl {

struct LrpGlsl {
  std::string constants;                 // GLSL const declarations, LRP_* (exact float literals)
  std::vector<float> frequencies;        // `lrp_frequencies`: (f_x, f_y, weight) triples
  std::vector<std::uint32_t> substrata;  // `lrp_substrata`: (first, count) pairs
};

LrpGlsl lrp_glsl(const lrp::LrpModel& model);

// random.glsl, the constants and lrp evaluate.glsl: all but `#version`.
std::string lrp_library_source(const LrpGlsl& glsl);

}  // namespace stochtex::gl
