#pragma once
// The languages of `export-shader --language`: a method's GLSL 4.50 library compiled to SPIR-V by
// glslang, then written as GLSL ES 3.00, HLSL Shader Model 5 or Metal by SPIRV-Cross, the same
// way for every method. Both are linked from Debian 12's packages (glslang-dev,
// libspirv-cross-c-shared-dev).

#include <array>
#include <string>
#include <string_view>

#include "stochtex/gpu.hpp"

namespace stochtex::gl {

// What the exporter and the cross-compiler know of a language: one row per ShaderLanguage, in the
// enum's order (language_row checks it).
struct LanguageRow {
  ShaderLanguage language;
  std::string_view option;         // the --language spelling: "glsl", "essl", "hlsl" or "msl"
  std::string_view title;          // "GLSL 4.50", "GLSL ES 3.00", "HLSL Shader Model 5", ...
  std::string_view extension;      // of the shader file: ".glsl", ".essl", ".hlsl", ".metal"
  std::string_view placement;      // where a cross-compiled library goes in the caller's shader
  std::string_view texel_read;     // how the exact variant reads one texel of a data texture
  std::string_view filtered_read;  // how the fast variant reads its filtered textures
  // The texture types of a 2-D and a 3-D data texture, as the shader declares them.
  std::array<std::string_view, 2> texture_types;
  // The texture format of a data image per TextureEncoding and channel count (1-4); three channels
  // load as RGBA (alpha 1) where the API has no such format or cannot generate its mip-maps.
  std::array<std::array<std::string_view, 4>, 3> formats;
  // Where SPIRV-Cross's text for the fragment entry point begins: it writes the entry point after
  // every function it calls, and nothing after it (empty for GLSL, which is not cross-compiled).
  std::string_view entry_point_start;
};

inline constexpr std::array<LanguageRow, 4> kLanguageRows = {{
    {ShaderLanguage::glsl,
     "glsl",
     "GLSL 4.50",
     ".glsl",
     "Paste or include after `#version 450`.",
     "`texelFetch`",
     "`textureGrad`, `textureLod`",
     {"sampler2D", "sampler3D"},
     {{{"GL_R32F", "GL_RG32F", "GL_RGB32F", "GL_RGBA32F"},
       {"GL_R8", "GL_RG8", "GL_RGB8", "GL_RGBA8"},
       {"GL_R16", "GL_RG16", "GL_RGB16", "GL_RGBA16"}}},
     ""},
    {ShaderLanguage::essl,
     "essl",
     "GLSL ES 3.00",
     ".essl",
     "Paste or include after `#version 300 es`.",
     "`texelFetch`",
     "`textureGrad`, `textureLod`",
     {"highp sampler2D", "highp sampler3D"},
     {{{"R32F", "RG32F", "RGBA32F", "RGBA32F"},
       {"R8", "RG8", "RGBA8", "RGBA8"},
       {"R16_EXT", "RG16_EXT", "RGBA16_EXT", "RGBA16_EXT"}}},
     "\nvoid main()\n"},
    {ShaderLanguage::hlsl,
     "hlsl",
     "HLSL Shader Model 5",
     ".hlsl",
     "Include it in a Shader Model 5 shader.",
     "`Texture2D.Load`",
     "`SampleGrad`, `SampleLevel`",
     {"Texture2D<float4>", "Texture3D<float4>"},
     {{{"DXGI_FORMAT_R32_FLOAT", "DXGI_FORMAT_R32G32_FLOAT", "DXGI_FORMAT_R32G32B32A32_FLOAT",
        "DXGI_FORMAT_R32G32B32A32_FLOAT"},
       {"DXGI_FORMAT_R8_UNORM", "DXGI_FORMAT_R8G8_UNORM", "DXGI_FORMAT_R8G8B8A8_UNORM",
        "DXGI_FORMAT_R8G8B8A8_UNORM"},
       {"DXGI_FORMAT_R16_UNORM", "DXGI_FORMAT_R16G16_UNORM", "DXGI_FORMAT_R16G16B16A16_UNORM",
        "DXGI_FORMAT_R16G16B16A16_UNORM"}}},
     "\nvoid frag_main()\n"},
    {ShaderLanguage::msl,
     "msl",
     "Metal Shading Language 1.2",
     ".metal",
     "Include it in a Metal shader.",
     "`texture2d::read`",
     "`sample` with `gradient2d`, `level`",
     {"texture2d<float>", "texture3d<float>"},
     {{{"MTLPixelFormatR32Float", "MTLPixelFormatRG32Float", "MTLPixelFormatRGBA32Float",
        "MTLPixelFormatRGBA32Float"},
       {"MTLPixelFormatR8Unorm", "MTLPixelFormatRG8Unorm", "MTLPixelFormatRGBA8Unorm",
        "MTLPixelFormatRGBA8Unorm"},
       {"MTLPixelFormatR16Unorm", "MTLPixelFormatRG16Unorm", "MTLPixelFormatRGBA16Unorm",
        "MTLPixelFormatRGBA16Unorm"}}},
     "\nfragment void main0("},
}};

// The row of `language`.
const LanguageRow& language_row(ShaderLanguage language);

// `library` (GLSL 4.50 without `#version`: uniform sampler2D declarations, constants and
// functions, among them `vec4 <function>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)`) in `language`
// (essl, hlsl or msl): every function reachable from `function` kept with its name and parameter
// names, no entry point and no `#version` line, to paste into the caller's shader.
//   essl: `uniform highp sampler2D <name>` as in the GLSL; default precision highp;
//   hlsl: `Texture2D<float4> <name>` and `SamplerState _<name>_sampler` globals, no registers;
//   msl:  each texture2d<float> <name> and `sampler <name>Smplr` become parameters of the
//         functions that read them, `function` included (Metal has no global textures).
// Throws std::invalid_argument, one sentence naming `method` and the language, when the library
// uses what the language lacks (double precision, 64-bit integers); std::logic_error when glslang
// or SPIRV-Cross refuse it (a bug).
std::string cross_compile(std::string_view library, std::string_view function,
                          std::string_view method, ShaderLanguage language);

// glslang's front end (parser and linker) on a complete fragment shader in `language` (glsl:
// GLSL 4.50, essl: GLSL ES 3.00, hlsl: HLSL with the entry point `main`): empty when it compiles,
// else glslang's log. There is no Metal front end here (msl throws std::invalid_argument).
std::string front_end_errors(std::string_view source, ShaderLanguage language);

}  // namespace stochtex::gl
