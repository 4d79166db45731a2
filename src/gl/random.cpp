// The embedded GLSL files; random.glsl with the stream constants of core/hash.hpp declared from
// the C++ enum, and float_math.glsl with the constants of core/float_math.hpp.

#include <array>
#include <span>
#include <stdexcept>
#include <string>

#include "core/float_math.hpp"
#include "core/hash.hpp"
#include "gl/shaders.hpp"

namespace stochtex::gl {
namespace {

constexpr auto stream(Stream s) {
  return static_cast<std::uint32_t>(s);
}

constexpr std::array<GlslConstant, 6> kStreams = {{
    {"STREAM_POINTS", stream(Stream::points)},
    {"STREAM_PHASES", stream(Stream::phases)},
    {"STREAM_OFFSETS", stream(Stream::offsets)},
    {"STREAM_ANALYSIS", stream(Stream::analysis)},
    {"STREAM_KERNELS", stream(Stream::kernels)},
    {"STREAM_SIGNS", stream(Stream::signs)},
}};

constexpr std::array<GlslConstant, 3> kFloatMath = {{
    {"FLOAT_MATH_TWO_PI", kTwoPi},
    {"FLOAT_MATH_EXP_FLOOR", kExpFloor},
    {"FLOAT_MATH_EXP_CEILING", kExpCeiling},
}};

}  // namespace

std::string shader_source(std::string_view name) {
  if (const EmbeddedFile* file = find_embedded(embedded_files(), name))
    return std::string(file->text);
  throw std::logic_error("no embedded GLSL file " + std::string(name));
}

std::span<const GlslConstant> random_constants() {
  return kStreams;
}

std::string random_source() {
  return glsl_constants(kStreams) + shader_source("gl/random.glsl");
}

std::span<const GlslConstant> float_math_constants() {
  return kFloatMath;
}

std::string float_math_source() {
  return glsl_constants(kFloatMath) + shader_source("gl/float_math.glsl");
}

}  // namespace stochtex::gl
