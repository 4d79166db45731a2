#include "gl/colour.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/glsl_text.hpp"
#include "gl/readme.hpp"
#include "gl/shaders.hpp"

namespace stochtex::gl {
namespace {

// The table of D, four consecutive means per RGBA texel (colour.glsl), zeros past the last.
ShaderTexture decoded_texture() {
  constexpr int kMeans = kExpectationMeanCells + 1;
  constexpr int kRows = kExpectationDeviationCells + 1;
  constexpr int kTexels = (kMeans + 3) / 4;
  const std::vector<float>& table = expectation_table();
  ImageF image(kTexels, kRows, 4);
  for (int s = 0; s < kRows; ++s)
    for (int m = 0; m < kMeans; ++m)
      image.at(m / 4, s, m % 4) = table[static_cast<std::size_t>(s) * kMeans + m];
  return ShaderTexture{"decoded", std::move(image)};
}

// r(w) of every channel, one RGBA texel per width step, channel c in row c / 4, component c % 4
// (zeros past the model's channels): one row for a model of one image.
ShaderTexture removed_texture(const ModelColour& colour, int channels) {
  ImageF image(kRemovedSteps, (channels + 3) / 4, 4);
  for (int k = 0; k < kRemovedSteps; ++k)
    for (int c = 0; c < channels; ++c)
      image.at(k, c / 4, c % 4) = colour.removed_deviation[static_cast<std::size_t>(k) * channels +
                                                           static_cast<std::size_t>(c)];
  return ShaderTexture{"removed", std::move(image)};
}

std::string colour_library(const ModelColour& colour, int channels) {
  const std::array<GlslConstant, 7> constants = {{
      {"STOCHTEX_MEAN_LOW", kExpectationMeanLow},
      {"STOCHTEX_MEAN_HIGH", kExpectationMeanHigh},
      {"STOCHTEX_MEAN_CELLS", kExpectationMeanCells},
      {"STOCHTEX_DEVIATION_HIGH", kExpectationDeviationHigh},
      {"STOCHTEX_DEVIATION_CELLS", kExpectationDeviationCells},
      {"STOCHTEX_REMOVED_STEPS_PER_OCTAVE", kRemovedStepsPerOctave},
      {"STOCHTEX_REMOVED_STEPS", kRemovedSteps},
  }};
  std::string decode = "const bvec4 STOCHTEX_DECODE = bvec4(";
  for (int c = 0; c < 4; ++c)
    decode +=
        std::string(c < channels && colour.expects(c) ? "true" : "false") + (c < 3 ? ", " : ");\n");
  return glsl_constants(constants, GlslPrecision::floats) + decode +
         shader_source("gl/colour.glsl");
}

}  // namespace

void add_colour(ExportParts& parts, const ModelColour& colour, int channels,
                std::span<const MapInfo> maps) {
  const std::string entry = "stochtex_" + std::string(parts.method);
  const bool decoded = colour.expects_any();
  std::string srgb_maps;
  for (const MapInfo& map : maps)
    if (map.colour_space == ColourSpace::srgb)
      srgb_maps += (srgb_maps.empty() ? "`" : ", `") + map.name + "`";
  parts.notes += std::string(parts.notes.empty() ? "" : "\n\n") +
                 ReadmeTemplate("colour")
                     .set("entry", entry)
                     .flag("material", !maps.empty())
                     .set("srgb_maps", srgb_maps.empty() ? "none" : srgb_maps)
                     .flag("decoded", decoded)
                     .flag("in_tables", !decoded && colour.decodes())
                     .flag("data", !colour.decodes())
                     .text();
  if (!decoded) return;
  for (const ShaderTexture& texture : parts.textures)
    if (texture.name == "decoded" || texture.name == "removed")
      throw std::logic_error("add_colour: the method already has a texture " + texture.name);
  parts.textures.push_back(decoded_texture());
  parts.textures.push_back(removed_texture(colour, channels));
  if (!maps.empty()) {
    // The material function decodes its srgb maps' channels (export_material.cpp).
    parts.library +=
        colour_library(colour, std::min(channels, 4)) + shader_source("gl/colour_material.glsl");
    for (int c = 0; c < channels; ++c)
      if (colour.expects(c)) parts.decoded_channels.push_back(c);
    return;
  }
  // The entry point is the library's last definition of that name (a fast library may hold the
  // exact one before it, renamed by a macro).
  const std::string definition = "vec4 " + entry + "(";
  const std::size_t at = parts.library.rfind(definition);
  if (at == std::string::npos)
    throw std::logic_error("add_colour: the library does not define " + entry);
  parts.library.replace(at, definition.size(), "vec4 " + entry + "_encoded(");
  parts.library += colour_library(colour, channels) + "\nvec4 " + entry +
                   "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {\n  return stochtex_linear_light(" +
                   entry + "_encoded(p, dpdx, dpdy, seed), dpdx, dpdy);\n}\n";
}

void add_colour(SurfaceShader& shader, const ModelColour& colour, int channels,
                SurfaceMapping mapping) {
  if (!colour.expects_any()) return;
  if (mapping == SurfaceMapping::triplanar_linear) {
    // triplanar_linear.glsl decodes each plane: the functions come before it.
    shader.library =
        colour_library(colour, channels) + "#define STOCHTEX_TRIPLANAR_DECODE\n" + shader.library;
  } else {
    shader.library += colour_library(colour, channels);
    shader.call = "stochtex_surface_linear_light(" + shader.call + ", dpdx, dpdy)";
  }
  shader.textures.push_back(decoded_texture());
  shader.textures.push_back(removed_texture(colour, channels));
}

}  // namespace stochtex::gl
