#pragma once
// The cross-compiled languages of `export-shader --language` (languages.hpp): a method's GLSL
// 4.50 library compiled to SPIR-V by glslang, then written in the language by SPIRV-Cross, the
// same way for every method. Both are linked from Debian 12's packages (glslang-dev,
// libspirv-cross-c-shared-dev).

#include <string>
#include <string_view>

#include "gl/languages.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex::gl {

// `library` (GLSL 4.50 without `#version`: uniform sampler2D declarations, constants and
// functions, among them `vec4 <function>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)`) in `language`
// (essl, hlsl, msl or godot): every function reachable from `function` kept with its name and
// parameter names, the values the GLSL does not name named after what they are (spirv_names.hpp;
// not for godot), no entry point and no `#version` line, to paste into the caller's shader.
//   essl:  `uniform highp sampler2D <name>` as in the GLSL; default precision highp;
//   hlsl:  `Texture2D<float4> <name>` and `SamplerState _<name>_sampler` globals, no registers;
//   msl:   each texture2d<float> <name> and `sampler <name>Smplr` become parameters of the
//          functions that read them, `function` included (Metal has no global textures);
//   godot: `uniform sampler2D <name>;` (or sampler3D) per texture read, then `function` alone,
//          every function it calls inlined (godot_shader.hpp), and the helpers it calls; its
//          texelFetch reads each texel's floats from their bytes (ShaderTexture::float_bytes).
// Throws std::invalid_argument, one sentence naming `method` and the language, when the library
// uses what the language lacks (double precision, 64-bit integers); std::logic_error when glslang
// or SPIRV-Cross refuse it (a bug).
std::string cross_compile(std::string_view library, std::string_view function,
                          std::string_view method, ShaderLanguage language);

// glslang's front end (parser and linker) on a complete fragment shader in `language` (glsl:
// GLSL 4.50, essl: GLSL ES 3.00, hlsl: HLSL with the entry point `main`): empty when it compiles,
// else glslang's log. There is no Metal or Godot front end here (msl and godot throw
// std::invalid_argument; Godot's own parser checks its files, tests/godot).
std::string front_end_errors(std::string_view source, ShaderLanguage language);

}  // namespace stochtex::gl
