#include "gl/lrp_glsl.hpp"

#include <algorithm>
#include <span>

#include "gl/glsl_text.hpp"
#include "gl/shaders.hpp"
#include "methods/lrp/window.hpp"

namespace stochtex::gl {

LrpGlsl lrp_glsl(const lrp::LrpModel& model) {
  const lrp::LrpData& d = model.data();
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

  // Section 5 (structure_model.cpp); glsl_array writes one zero for an empty table.
  const lrp::StructureData& st = d.structure;
  glsl.structure = st.cosine_table;
  glsl.turbulence_frequencies = st.turbulence_frequencies;
  for (std::size_t k = 0; k < st.turbulence_first.size(); ++k) {
    glsl.turbulence_substrata.push_back(st.turbulence_first[k]);
    glsl.turbulence_substrata.push_back(st.turbulence_count[k]);
  }
  std::vector<float> turbulence_spacing;
  std::vector<float> turbulence_amplitude;
  std::vector<int> turbulence_first;
  std::vector<int> turbulence_cosines;
  int next_turbulence = 0;
  for (const lrp::TurbulenceStratum& stratum : st.turbulence_strata) {
    turbulence_spacing.push_back(stratum.spacing);
    turbulence_amplitude.push_back(stratum.amplitude);
    turbulence_first.push_back(next_turbulence);
    turbulence_cosines.push_back(stratum.cosines);
    next_turbulence += stratum.cosines;
  }
  constant("bool", "LRP_HAS_STRUCTURE", st.empty() ? "false" : "true");
  constant("int", "LRP_STRUCTURE_BLOCKS", glsl_int(std::max(st.blocks, 1)));
  constant("int", "LRP_STRUCTURE_COSINES", glsl_int(st.cosines));
  constant("float", "LRP_STRUCTURE_PERIOD", glsl_float(static_cast<float>(st.period)));
  constant("float", "LRP_STRUCTURE_SIDE",
           glsl_float(st.empty() ? 1.0f
                                 : static_cast<float>(static_cast<double>(st.period) / st.blocks)));
  constant("bool", "LRP_PLACEMENT", st.placement ? "true" : "false");
  constant("float", "LRP_TURBULENCE", glsl_float(st.turbulence));
  constant("int", "LRP_TURBULENCE_STRATA", glsl_int(static_cast<int>(st.turbulence_strata.size())));
  // The size of the per-turbulence-stratum uniforms of lrp_render.glsl (never 0).
  constant("int", "LRP_TURBULENCE_ARRAY",
           glsl_int(std::max(1, static_cast<int>(turbulence_spacing.size()))));
  text += glsl_array("float", "LRP_TURBULENCE_SPACING", std::span<const float>(turbulence_spacing),
                     glsl_float);
  text += glsl_array("float", "LRP_TURBULENCE_AMPLITUDE",
                     std::span<const float>(turbulence_amplitude), glsl_float);
  text +=
      glsl_array("int", "LRP_TURBULENCE_FIRST", std::span<const int>(turbulence_first), glsl_int);
  text += glsl_array("int", "LRP_TURBULENCE_COSINES", std::span<const int>(turbulence_cosines),
                     glsl_int);
  return glsl;
}

std::string lrp_library_source(const LrpGlsl& glsl) {
  return std::string(kRandomGlsl) + glsl.constants + kLrpGlsl;
}

}  // namespace stochtex::gl
