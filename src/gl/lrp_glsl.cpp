#include "gl/lrp_glsl.hpp"

#include <span>

#include "gl/glsl_text.hpp"
#include "gl/shaders.hpp"
#include "methods/lrp/window.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {

LrpGlsl lrp_glsl(const lrp::LrpModel& model) {
  const lrp::LrpData& d = model.data();
  // evaluate.glsl has no twin of structure_model.cpp yet (section 5 of the paper).
  if (!d.structure.empty())
    throw Error(ErrorCode::invalid_input,
                "the gl backend does not evaluate lrp structure preservation (ratio > 0) yet; use "
                "--backend cpu");
  LrpGlsl glsl;
  glsl.frequencies = d.frequencies;
  for (std::size_t k = 0; k < d.substratum_first.size(); ++k) {
    glsl.substrata.push_back(d.substratum_first[k]);
    glsl.substrata.push_back(d.substratum_count[k]);
  }
  // The strata in the evaluator's order (channel-major), as LrpModel's runtime table.
  std::vector<float> spacing;
  std::vector<float> amplitude;
  std::vector<int> first;
  std::vector<int> cosines;
  std::vector<int> channel;
  int next = 0;
  for (std::size_t s = 0; s < d.strata_table.size(); ++s) {
    spacing.push_back(d.strata_table[s].spacing);
    amplitude.push_back(d.strata_table[s].amplitude);
    first.push_back(next);
    cosines.push_back(d.strata_table[s].cosines);
    channel.push_back(static_cast<int>(s) / d.strata);
    next += d.strata_table[s].cosines;
  }
  const std::array<float, lrp::kWindowTerms> window = lrp::window_coefficients();
  std::string& text = glsl.constants;
  const auto constant = [&](const char* type, const char* name, const std::string& value) {
    text += "const " + std::string(type) + " " + name + " = " + value + ";\n";
  };
  constant("int", "LRP_CHANNELS", glsl_int(d.channels));
  constant("int", "LRP_STRATA_TOTAL", glsl_int(static_cast<int>(d.strata_table.size())));
  constant("bool", "LRP_NORMALISE_ENVELOPE", d.normalise_envelope ? "true" : "false");
  constant("float", "LRP_MEAN_ENVELOPE", glsl_float(static_cast<float>(model.mean_envelope())));
  constant("vec4", "LRP_MEAN", glsl_vec4(d.mean));
  text += glsl_array("float", "LRP_BASIS", std::span<const float>(d.colour_basis), glsl_float);
  text += glsl_array("float", "LRP_WINDOW", std::span<const float>(window), glsl_float);
  text += glsl_array("float", "LRP_STRATUM_SPACING", std::span<const float>(spacing), glsl_float);
  text +=
      glsl_array("float", "LRP_STRATUM_AMPLITUDE", std::span<const float>(amplitude), glsl_float);
  text += glsl_array("int", "LRP_STRATUM_FIRST", std::span<const int>(first), glsl_int);
  text += glsl_array("int", "LRP_STRATUM_COSINES", std::span<const int>(cosines), glsl_int);
  text += glsl_array("int", "LRP_STRATUM_CHANNEL", std::span<const int>(channel), glsl_int);
  return glsl;
}

std::string lrp_library_source(const LrpGlsl& glsl) {
  return std::string(kRandomGlsl) + glsl.constants + kLrpGlsl;
}

}  // namespace stochtex::gl
