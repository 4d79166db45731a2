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
  std::vector<float> frequencies;        // `lrp_frequencies`: (f_x, f_y) pairs
  std::vector<std::uint32_t> substrata;  // `lrp_substrata`: (first, count) pairs
  // Section 5 (empty without structure): `lrp_structure` (f_x, f_y, amplitude, phase) per
  // cosine, `lrp_turbulence_frequencies` and `lrp_turbulence_substrata` as above.
  std::vector<float> structure;
  std::vector<float> turbulence_frequencies;
  std::vector<std::uint32_t> turbulence_substrata;
};

LrpGlsl lrp_glsl(const lrp::LrpModel& model);

// random.glsl, the constants and lrp evaluate.glsl: all but `#version`.
std::string lrp_library_source(const LrpGlsl& glsl);

}  // namespace stochtex::gl
