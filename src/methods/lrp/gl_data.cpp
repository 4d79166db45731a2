// Local random-phase noise as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "methods/lrp/gl_twin.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {

namespace {

// The first texel of each table in the exported tables texture, one entry per texel: frequencies
// (f_x, f_y, weight), sub-strata (first, count), structure cosines (f_x, f_y, amplitude, phase),
// turbulence frequencies (f_x, f_y), turbulence sub-strata (first, count).
struct TableLayout {
  std::size_t substrata, structure, turbulence_frequencies, turbulence_substrata, end;
};

TableLayout table_layout(const LrpGlsl& glsl) {
  TableLayout layout{};
  layout.substrata = glsl.frequencies.size() / 3;
  layout.structure = layout.substrata + glsl.substrata.size() / 2;
  layout.turbulence_frequencies = layout.structure + glsl.structure.size() / 4;
  layout.turbulence_substrata =
      layout.turbulence_frequencies + glsl.turbulence_frequencies.size() / 2;
  layout.end = layout.turbulence_substrata + glsl.turbulence_substrata.size() / 2;
  return layout;
}

// The GLSL arrays <prefix>_SPACING, _AMPLITUDE, _FIRST (a stratum's first cosine: the running
// sum of the cosines before it) and _COSINES of a table of strata, the random strata
// (lrp::Stratum) and the turbulence strata (lrp::TurbulenceStratum) alike.
template <typename StratumType>
std::string stratum_arrays(const std::string& prefix, const std::vector<StratumType>& strata) {
  std::vector<float> spacing;
  std::vector<float> amplitude;
  std::vector<int> first;
  std::vector<int> cosines;
  int next = 0;
  for (const StratumType& stratum : strata) {
    spacing.push_back(stratum.spacing);
    amplitude.push_back(stratum.amplitude);
    first.push_back(next);
    cosines.push_back(stratum.cosines);
    next += stratum.cosines;
  }
  return glsl_array("float", (prefix + "_SPACING").c_str(), std::span<const float>(spacing),
                    glsl_float) +
         glsl_array("float", (prefix + "_AMPLITUDE").c_str(), std::span<const float>(amplitude),
                    glsl_float) +
         glsl_array("int", (prefix + "_FIRST").c_str(), std::span<const int>(first), glsl_int) +
         glsl_array("int", (prefix + "_COSINES").c_str(), std::span<const int>(cosines), glsl_int);
}

}  // namespace

LrpGlsl lrp_glsl(const lrp::LrpModel& model) {
  const lrp::LrpData& d = model.data();
  LrpGlsl glsl;
  for (std::size_t f = 0; f < d.weights.size(); ++f) {
    glsl.frequencies.push_back(d.frequencies[2 * f]);
    glsl.frequencies.push_back(d.frequencies[2 * f + 1]);
    glsl.frequencies.push_back(d.weights[f]);
  }
  for (std::size_t k = 0; k < d.substratum_first.size(); ++k) {
    glsl.substrata.push_back(d.substratum_first[k]);
    glsl.substrata.push_back(d.substratum_count[k]);
  }
  // The strata in the evaluator's order (channel-major), as LrpModel's runtime table.
  std::vector<int> channel;
  for (std::size_t s = 0; s < d.strata_table.size(); ++s)
    channel.push_back(static_cast<int>(s) / d.strata);
  const std::array<float, lrp::kWindowTerms> window = lrp::window_coefficients();
  std::string& text = glsl.constants;
  const auto constant = [&](const char* type, const char* name, const std::string& value) {
    text += "const " + std::string(type) + " " + name + " = " + value + ";\n";
  };
  constant("int", "LRP_CHANNELS", glsl_int(d.channels));
  constant("int", "LRP_STRATA", glsl_int(d.strata));
  constant("int", "LRP_STRATA_TOTAL", glsl_int(static_cast<int>(d.strata_table.size())));
  constant("bool", "LRP_NORMALISE_ENVELOPE", d.normalise_envelope ? "true" : "false");
  constant("float", "LRP_MEAN_ENVELOPE", glsl_float(static_cast<float>(model.mean_envelope())));
  constant("vec4", "LRP_MEAN", glsl_vec4(d.mean));
  text += glsl_array("float", "LRP_BASIS", std::span<const float>(d.colour_basis), glsl_float);
  text += glsl_array("float", "LRP_WINDOW", std::span<const float>(window), glsl_float);
  text += stratum_arrays("LRP_STRATUM", d.strata_table);
  text += glsl_array("int", "LRP_STRATUM_CHANNEL", std::span<const int>(channel), glsl_int);

  // Section 5 (structure_model.cpp); glsl_array writes one zero for an empty table.
  const lrp::StructureData& st = d.structure;
  glsl.structure = st.cosine_table;
  glsl.turbulence_frequencies = st.turbulence_frequencies;
  for (std::size_t k = 0; k < st.turbulence_first.size(); ++k) {
    glsl.turbulence_substrata.push_back(st.turbulence_first[k]);
    glsl.turbulence_substrata.push_back(st.turbulence_count[k]);
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
  // The size of the per-turbulence-stratum arrays of lrp_add_structure (never 0).
  constant("int", "LRP_TURBULENCE_ARRAY",
           glsl_int(std::max(1, static_cast<int>(st.turbulence_strata.size()))));
  text += stratum_arrays("LRP_TURBULENCE", st.turbulence_strata);
  return glsl;
}

std::string lrp_library_source(const LrpGlsl& glsl, DataSource source) {
  std::string readers;
  if (source == DataSource::storage_buffers) {
    readers = R"glsl(
layout(std430, binding = 0) readonly buffer LrpFrequencies { float lrp_frequencies[]; };
layout(std430, binding = 2) readonly buffer LrpSubstrata { uint lrp_substrata[]; };
vec3 lrp_frequency(uint index) {
  return vec3(lrp_frequencies[3u * index], lrp_frequencies[3u * index + 1u],
              lrp_frequencies[3u * index + 2u]);
}
uvec2 lrp_substratum(int index) {
  return uvec2(lrp_substrata[2 * index], lrp_substrata[2 * index + 1]);
}
layout(std430, binding = 3) readonly buffer LrpStructure { vec4 lrp_structure[]; };
layout(std430, binding = 4) readonly buffer LrpTurbulenceFrequencies {
  vec2 lrp_turbulence_frequencies[];
};
layout(std430, binding = 5) readonly buffer LrpTurbulenceSubstrata {
  uvec2 lrp_turbulence_substrata[];
};
vec4 lrp_structure_cosine(int index) { return lrp_structure[index]; }
vec2 lrp_turbulence_frequency(uint index) { return lrp_turbulence_frequencies[index]; }
uvec2 lrp_turbulence_substratum(int index) { return lrp_turbulence_substrata[index]; }
)glsl";
  } else {
    const TableLayout layout = table_layout(glsl);
    readers = "uniform sampler2D stochtex_lrp_tables;\nconst int LRP_TABLES_WIDTH = " +
              std::to_string(kDataTextureWidth) +
              ";\nconst int LRP_SUBSTRATA_TEXEL = " + std::to_string(layout.substrata) +
              ";\nconst int LRP_STRUCTURE_TEXEL = " + std::to_string(layout.structure) +
              ";\nconst int LRP_TURBULENCE_FREQUENCY_TEXEL = " +
              std::to_string(layout.turbulence_frequencies) +
              ";\nconst int LRP_TURBULENCE_SUBSTRATUM_TEXEL = " +
              std::to_string(layout.turbulence_substrata) + ";\n" + R"glsl(
vec4 lrp_table_texel(int index) {
  return texelFetch(stochtex_lrp_tables,
                    ivec2(index % LRP_TABLES_WIDTH, index / LRP_TABLES_WIDTH), 0);
}
vec3 lrp_frequency(uint index) { return lrp_table_texel(int(index)).xyz; }
uvec2 lrp_substratum(int index) { return uvec2(lrp_table_texel(LRP_SUBSTRATA_TEXEL + index).xy); }
vec4 lrp_structure_cosine(int index) { return lrp_table_texel(LRP_STRUCTURE_TEXEL + index); }
vec2 lrp_turbulence_frequency(uint index) {
  return lrp_table_texel(LRP_TURBULENCE_FREQUENCY_TEXEL + int(index)).xy;
}
uvec2 lrp_turbulence_substratum(int index) {
  return uvec2(lrp_table_texel(LRP_TURBULENCE_SUBSTRATUM_TEXEL + index).xy);
}
)glsl";
  }
  return random_source() + float_math_source() + glsl_constants(Twin<lrp::LrpModel>::kConstants) +
         glsl.constants + readers + shader_source("methods/lrp/evaluate.glsl");
}

ImageF lrp_tables_image(const LrpGlsl& glsl) {
  const TableLayout layout = table_layout(glsl);
  ImageF image(kDataTextureWidth,
               static_cast<int>((std::max<std::size_t>(layout.end, 1) + kDataTextureWidth - 1) /
                                kDataTextureWidth),
               4);
  const auto texel = [&](std::size_t index, int c) -> float& {
    return image.at(static_cast<int>(index % kDataTextureWidth),
                    static_cast<int>(index / kDataTextureWidth), c);
  };
  // Integers as floats are exact below 2^24 (export_shader checks).
  for (std::size_t i = 0; i < layout.substrata; ++i)
    for (int c = 0; c < 3; ++c) texel(i, c) = glsl.frequencies[3 * i + static_cast<std::size_t>(c)];
  for (std::size_t i = 0; i < glsl.substrata.size(); ++i)
    texel(layout.substrata + i / 2, static_cast<int>(i % 2)) =
        static_cast<float>(glsl.substrata[i]);
  for (std::size_t i = 0; i < glsl.structure.size(); ++i)
    texel(layout.structure + i / 4, static_cast<int>(i % 4)) = glsl.structure[i];
  for (std::size_t i = 0; i < glsl.turbulence_frequencies.size(); ++i)
    texel(layout.turbulence_frequencies + i / 2, static_cast<int>(i % 2)) =
        glsl.turbulence_frequencies[i];
  for (std::size_t i = 0; i < glsl.turbulence_substrata.size(); ++i)
    texel(layout.turbulence_substrata + i / 2, static_cast<int>(i % 2)) =
        static_cast<float>(glsl.turbulence_substrata[i]);
  return image;
}

ExportParts Twin<lrp::LrpModel>::shader(const lrp::LrpModel& model,
                                        ShaderVariant /*variant: fast is exact*/) {
  LrpGlsl glsl = lrp_glsl(model);
  constexpr std::uint32_t kExactFloatIntegers = 1u << 24;
  const auto too_large = [](std::uint32_t value) { return value >= kExactFloatIntegers; };
  if (std::any_of(glsl.substrata.begin(), glsl.substrata.end(), too_large) ||
      std::any_of(glsl.turbulence_substrata.begin(), glsl.turbulence_substrata.end(), too_large))
    throw Error(ErrorCode::invalid_input,
                "export-shader: this lrp model has more than 2^24 frequencies, which a float "
                "texture cannot index exactly");
  // Beyond 4 channels (a material), lrp_channels (channels.glsl) instead of the vec4 entry point.
  const bool material = model.channels() > 4;
  std::string entry = shader_source("methods/lrp/entry.glsl");
  if (material) {
    const lrp::LrpData& d = model.data();
    if (!d.structure.empty())
      throw Error(ErrorCode::invalid_input,
                  "export-shader: the lrp shader keeps section 5's structure (ratio > 0) for at "
                  "most 4 channels and this material has " +
                      std::to_string(d.channels) +
                      "; analyse it with ratio 0, or render its maps with `stochtex render`");
    glsl.constants +=
        "const int LRP_MATERIAL_CHANNELS = " + glsl_int(d.channels) +
        ";\nconst int LRP_TURBULENCE_AXES = " + glsl_int(static_cast<int>(lrp::kTurbulenceAxes)) +
        ";\n" +
        glsl_array("float", "LRP_MATERIAL_MEAN", std::span<const float>(d.mean), glsl_float);
    entry = shader_source("methods/lrp/channels.glsl");
  }
  std::vector<ShaderTexture> images;
  images.push_back({"lrp_tables", lrp_tables_image(glsl)});
  ExportParts parts{
      lrp::LrpModel::kMethodName,
      "local random-phase noise",
      "Local random-phase noise (" + std::to_string(model.channels()) + " channels)",
      lrp_library_source(glsl, DataSource::textures) + (material ? "" : "\n") + entry,
      std::move(images),
      "`lrp_tables.exr` holds one table entry per texel, the tables one after the other from\n"
      "the texels LRP_SUBSTRATA_TEXEL, LRP_STRUCTURE_TEXEL, ... of the shader: frequencies\n"
      "(R, G: cycles per pixel; B: weight), sub-strata (R, G: first frequency and count), and\n"
      "for a model that keeps structure (ratio > 0) its cosines and turbulence tables. Keep |p|\n"
      "below ~1e4 for full float precision."};
  if (material) parts.channels_function = "lrp_channels";
  return parts;
}

}  // namespace stochtex::gl
