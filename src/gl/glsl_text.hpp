#pragma once
// Writing model data as GLSL constants that read back exactly.

#include <array>
#include <cstdio>
#include <span>
#include <string>

namespace stochtex::gl {

// A float as a GLSL literal that reads back as the same float: 9 significant digits identify a
// float uniquely, and a decimal that close to it rounds to it even through a double. (GLSL has no
// hexadecimal float literal, and not every compiler folds uintBitsToFloat in a const initialiser.)
inline std::string glsl_float(float value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.9g", static_cast<double>(value));
  std::string literal(text.data());
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return literal;
}

inline std::string glsl_int(int value) {
  return std::to_string(value);
}

// "const <type> <name>[n] = <type>[](...);"; GLSL has no empty arrays, so an empty span gives one
// zero element (never read).
template <typename T, typename Format>
std::string glsl_array(const char* type, const char* name, std::span<const T> values,
                       Format format) {
  std::string text = "const " + std::string(type) + " " + name + "[" +
                     std::to_string(values.empty() ? 1 : values.size()) + "] = " + type + "[](";
  if (values.empty()) return text + format(T{}) + ");\n";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i == 0 ? "" : ", ") + format(values[i]);
  return text + ");\n";
}

// vec4 of up to 4 values, zero-padded.
inline std::string glsl_vec4(std::span<const float> values) {
  std::string text = "vec4(";
  for (std::size_t c = 0; c < 4; ++c)
    text += (c == 0 ? "" : ", ") + glsl_float(c < values.size() ? values[c] : 0.0f);
  return text + ")";
}

}  // namespace stochtex::gl
