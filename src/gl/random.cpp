// The embedded GLSL files, and random.glsl with the stream constants of core/hash.hpp declared
// from the C++ enum.

#include <array>
#include <span>
#include <stdexcept>
#include <string>

#include "core/hash.hpp"
#include "gl/shaders.hpp"

namespace stochtex::gl {
namespace {

constexpr auto stream(Stream s) {
  return static_cast<std::uint32_t>(s);
}

constexpr std::array<GlslConstant, 5> kStreams = {{
    {"STREAM_POINTS", stream(Stream::points)},
    {"STREAM_PHASES", stream(Stream::phases)},
    {"STREAM_OFFSETS", stream(Stream::offsets)},
    {"STREAM_ANALYSIS", stream(Stream::analysis)},
    {"STREAM_KERNELS", stream(Stream::kernels)},
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

}  // namespace stochtex::gl
