#pragma once
// Writing model data as GLSL constants that read back exactly, and as RGBA float textures.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "stochtex/image.hpp"

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

// A double as a GLSL double literal that reads back exactly (17 significant digits).
inline std::string glsl_double(double value) {
  std::array<char, 40> text{};
  std::snprintf(text.data(), text.size(), "%.17g", value);
  std::string literal(text.data());
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return literal + "lf";
}

inline std::string glsl_int(int value) {
  return std::to_string(value);
}

// A uint as a hexadecimal GLSL literal (hash stream ids read as in core/hash.hpp).
inline std::string glsl_uint_hex(std::uint32_t value) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "0x%08xu", value);
  return text.data();
}

// Which arithmetic a method's GLSL keeps where it matches the CPU to the last bit: `doubles`
// (OpenGL 4.0+, the `--gl-filter exact` twins) or `floats` only (the `--gl-filter hardware` path
// and the targets without doubles: GLSL ES 3.00 for WebGL2, most engines' pixel shaders, Metal).
enum class GlslPrecision { doubles, floats };

// One GLSL source written for both precisions, as compiled for `precision`. Blocks
//   #ifdef STOCHTEX_FLOAT / (float lines) / #else / (double lines) / #endif
// (not nested, `#else` optional) keep the float lines for `floats` and the double lines for
// `doubles`, without the directive lines; for `floats` the code outside `//` comments also
// becomes float-only: the types double and dvecN become float and vecN, double literals (`0.5lf`)
// float ones. So the double text is unchanged where both precisions share it, and the float text
// is the same maths, written once. Throws std::logic_error on unbalanced blocks.
std::string glsl_precision_variant(std::string_view source, GlslPrecision precision);

// A constant that C++ and a GLSL twin share: written once, in C++, and declared in GLSL from the
// C++ value by glsl_constants (GLSL type from the value's: int, uint, float or double).
struct GlslConstant {
  const char* name;
  std::variant<int, std::uint32_t, float, double> value;
};

// "const <type> <name> = <value>;" per constant, every value reading back exactly; with
// GlslPrecision::floats a double constant is declared as the float nearest it (as the C++ float
// path rounds it, static_cast<float>).
inline std::string glsl_constants(std::span<const GlslConstant> constants,
                                  GlslPrecision precision = GlslPrecision::doubles) {
  std::string text;
  for (const GlslConstant& constant : constants) {
    const auto [type, value] = std::visit(
        [precision](auto v) -> std::pair<const char*, std::string> {
          using T = decltype(v);
          if constexpr (std::is_same_v<T, int>) return {"int", glsl_int(v)};
          if constexpr (std::is_same_v<T, std::uint32_t>) return {"uint", glsl_uint_hex(v)};
          if constexpr (std::is_same_v<T, float>) return {"float", glsl_float(v)};
          if constexpr (std::is_same_v<T, double>) {
            if (precision == GlslPrecision::floats)
              return {"float", glsl_float(static_cast<float>(v))};
            return {"double", glsl_double(v)};
          }
        },
        constant.value);
    text += "const " + std::string(type) + " " + constant.name + " = " + value + ";\n";
  }
  return text;
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

// Where a method's GLSL reads its large arrays from: storage buffers (the renderer), or RGBA32F
// textures read with texelFetch (an exported shader: engines load them from EXR files).
enum class DataSource { storage_buffers, textures };

// Rows of data textures: 1024 RGBA texels, so 64 M floats fit GL 4.5's guaranteed 16384 rows.
inline constexpr int kDataTextureWidth = 1024;

// `values` packed four floats per RGBA texel in row-major texel order (zero-padded).
inline ImageF pack_rgba(std::span<const float> values) {
  const std::size_t texels = std::max<std::size_t>((values.size() + 3) / 4, 1);
  ImageF image(kDataTextureWidth,
               static_cast<int>((texels + kDataTextureWidth - 1) / kDataTextureWidth), 4);
  for (std::size_t i = 0; i < values.size(); ++i)
    image.at(static_cast<int>(i / 4 % kDataTextureWidth),
             static_cast<int>(i / 4 / kDataTextureWidth), static_cast<int>(i % 4)) = values[i];
  return image;
}

// GLSL reading float `index` of a pack_rgba texture bound to `sampler`.
inline std::string glsl_packed_read(const std::string& sampler, const std::string& function) {
  const std::string width = std::to_string(kDataTextureWidth);
  return "uniform sampler2D " + sampler + ";\nfloat " + function +
         "(int index) {\n  int texel = index >> 2;\n  return texelFetch(" + sampler +
         ", ivec2(texel % " + width + ", texel / " + width + "), 0)[index & 3];\n}\n";
}

}  // namespace stochtex::gl
