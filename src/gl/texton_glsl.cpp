#include "gl/texton_glsl.hpp"

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "gl/shaders.hpp"

namespace stochtex::gl {
namespace {

// A float as a GLSL literal that reads back as the same float: 9 significant digits identify a
// float uniquely, and a decimal that close to it rounds to it even through a double. (GLSL has no
// hexadecimal float literal, and not every compiler folds uintBitsToFloat in a const initialiser.)
std::string exact(float value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.9g", static_cast<double>(value));
  std::string literal(text.data());
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return literal;
}

template <typename T, typename Format>
std::string array(const char* type, const char* name, const std::vector<T>& values, Format format) {
  std::string text = "const " + std::string(type) + " " + name + "[" +
                     std::to_string(values.size()) + "] = " + type + "[](";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i == 0 ? "" : ", ") + format(values[i]);
  return text + ");\n";
}

std::string vec4_of(std::span<const float> values) {
  std::string text = "vec4(";
  for (std::size_t c = 0; c < 4; ++c)
    text += (c == 0 ? "" : ", ") + exact(c < values.size() ? values[c] : 0.0f);
  return text + ")";
}

}  // namespace

TextonGlsl texton_glsl(const texton::TextonModel& model) {
  const auto& pyramid = model.pyramid();
  const int channels = model.channels();
  std::vector<int> rows;
  std::vector<float> spacing;
  std::vector<float> first;
  std::vector<float> half;
  int height = 0;
  for (const auto& level : pyramid) {
    rows.push_back(height);
    spacing.push_back(level.spacing);
    first.push_back(level.first_texel);
    half.push_back(level.half_width);
    height += level.stride;
  }
  TextonGlsl glsl;
  glsl.atlas = ImageF(pyramid.front().stride, height, 4);
  for (std::size_t l = 0; l < pyramid.size(); ++l)
    for (int y = 0; y < pyramid[l].stride; ++y)
      for (int x = 0; x < pyramid[l].stride; ++x)
        for (int c = 0; c < channels; ++c)
          glsl.atlas.at(x, rows[l] + y, c) =
              pyramid[l].coefficients[(static_cast<std::size_t>(y) * pyramid[l].stride + x) *
                                          static_cast<std::size_t>(channels) +
                                      static_cast<std::size_t>(c)];

  const auto& cdf = model.cell_count().cdf();
  const auto as_int = [](int v) { return std::to_string(v); };
  std::string& text = glsl.constants;
  text += "const int TEXTON_CHANNELS = " + std::to_string(channels) + ";\n";
  text += "const int TEXTON_ORDER = " + std::to_string(model.order()) + ";\n";
  text += "const float TEXTON_CELL_SIZE = " + exact(static_cast<float>(model.cell_size())) + ";\n";
  text += array("float", "TEXTON_POISSON_CDF", std::vector<float>(cdf.begin(), cdf.end()), exact);
  text +=
      "const uint TEXTON_POISSON_CHUNKS = " + std::to_string(model.cell_count().chunks()) + "u;\n";
  text += "const float TEXTON_INVERSE_SQRT_INTENSITY = " + exact(model.inverse_sqrt_intensity()) +
          ";\n";
  text += "const vec4 TEXTON_CONSTANT_TERM = " + vec4_of(model.constant_term()) + ";\n";
  text += "const vec4 TEXTON_MEAN = " + vec4_of(model.mean()) + ";\n";
  text += "const int TEXTON_LEVELS = " + std::to_string(pyramid.size()) + ";\n";
  text += array("int", "TEXTON_LEVEL_ROW", rows, as_int);
  text += array("float", "TEXTON_LEVEL_SPACING", spacing, exact);
  text += array("float", "TEXTON_LEVEL_FIRST_TEXEL", first, exact);
  text += array("float", "TEXTON_LEVEL_HALF_WIDTH", half, exact);
  return glsl;
}

std::string texton_library_source(const TextonGlsl& glsl) {
  return std::string(kRandomGlsl) + glsl.constants + "uniform sampler2D stochtex_texton_atlas;\n" +
         kTextonGlsl;
}

}  // namespace stochtex::gl
