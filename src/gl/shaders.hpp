#pragma once
// The GLSL files compiled into the library: src/gl/*.glsl and src/methods/*/*.glsl, embedded as
// strings by CMake (cmake/embed_files.cmake), so the files stay the single source and editors see
// them as GLSL. The exports' README templates, src/gl/readme/*.md (readme.hpp), are embedded with
// them.

#include <span>
#include <string>
#include <string_view>

#include "core/embedded_file.hpp"
#include "gl/glsl_text.hpp"

namespace stochtex::gl {

// Every embedded GLSL file and README template (generated: build/generated/shaders.cpp).
std::span<const EmbeddedFile> embedded_files();

// The text of the GLSL file at `name`, its path under src/ ("gl/random.glsl",
// "methods/texton/evaluate.glsl"). Throws std::logic_error for a file that is not embedded.
std::string shader_source(std::string_view name);

// random.glsl preceded by the stream constants of core/hash.hpp (STREAM_POINTS, ...), declared
// from the C++ enum: what every method's GLSL library starts with.
std::string random_source();
// The stream constants random_source() declares.
std::span<const GlslConstant> random_constants();

// float_math.glsl preceded by the constants of core/float_math.hpp: cos_turns and exp_float, the
// CPU's polynomials, for the methods whose C++ evaluators use them.
std::string float_math_source();
// The constants float_math_source() declares.
std::span<const GlslConstant> float_math_constants();

}  // namespace stochtex::gl
