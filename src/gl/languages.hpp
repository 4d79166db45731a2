#pragma once
// The languages of `export-shader --language`: one table, kLanguageRows, from which everything
// else that names them is made: the CLI's option, its help and `stochtex languages` (which
// scripts read), the studio's `/api/languages` and its export route, the exporter's file names,
// header comments and README, the cross-compiler (cross_compile.hpp) and the tests that cover
// every language. A language's README section on binding the data is the template
// readme/binding_<name>.md (readme.hpp); glsl, the methods' own source, has READMEs of its own.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "stochtex/gpu.hpp"

namespace stochtex::gl {

// What the exporter, the cross-compiler and the interfaces know of a language: one row per
// ShaderLanguage, in the enum's order (checked below).
struct LanguageRow {
  ShaderLanguage language;
  std::string_view name;        // the --language spelling and the studio's: "glsl", "essl", ...
  std::string_view title;       // "GLSL 4.50", "GLSL ES 3.00", "HLSL Shader Model 5", ...
  std::string_view targets;     // the APIs and engines that run it, for --help and listings
  std::string_view extension;   // of the shader file: ".glsl", ".essl", ".hlsl", ".metal", ...
  std::string_view placement;   // where a cross-compiled library goes in the caller's shader
  std::string_view texel_read;  // how the exact variant reads one texel of a data texture
  // The texture types of a 2-D and a 3-D data texture, as the shader declares them.
  std::array<std::string_view, 2> texture_types;
  // The texture format of a data image per TextureEncoding and channel count (1-4); three channels
  // load as RGBA (alpha 1) where the API has no such format or cannot generate its mip-maps.
  std::array<std::array<std::string_view, 4>, 3> formats;
  // Where SPIRV-Cross's text for the fragment entry point begins: it writes the entry point after
  // every function it calls, and nothing after it (empty for GLSL, which is not cross-compiled).
  std::string_view entry_point_start;
};

inline constexpr std::array<LanguageRow, 5> kLanguageRows = {{
    {ShaderLanguage::glsl,
     "glsl",
     "GLSL 4.50",
     "OpenGL 4.5",
     ".glsl",
     "Paste or include after `#version 450`.",
     "`texelFetch`",
     {"sampler2D", "sampler3D"},
     {{{"GL_R32F", "GL_RG32F", "GL_RGB32F", "GL_RGBA32F"},
       {"GL_R8", "GL_RG8", "GL_RGB8", "GL_RGBA8"},
       {"GL_R16", "GL_RG16", "GL_RGB16", "GL_RGBA16"}}},
     ""},
    {ShaderLanguage::essl,
     "essl",
     "GLSL ES 3.00",
     "WebGL2, OpenGL ES 3.0",
     ".essl",
     "Paste or include after `#version 300 es`.",
     "`texelFetch`",
     {"highp sampler2D", "highp sampler3D"},
     {{{"R32F", "RG32F", "RGBA32F", "RGBA32F"},
       {"R8", "RG8", "RGBA8", "RGBA8"},
       {"R16_EXT", "RG16_EXT", "RGBA16_EXT", "RGBA16_EXT"}}},
     "\nvoid main()\n"},
    {ShaderLanguage::hlsl,
     "hlsl",
     "HLSL Shader Model 5",
     "Direct3D 11, Unity and its Shader Graph, Unreal",
     ".hlsl",
     "Include it in a Shader Model 5 shader.",
     "`Texture2D.Load`",
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
     "Metal on macOS and iOS",
     ".metal",
     "Include it in a Metal shader.",
     "`texture2d::read`",
     {"texture2d<float>", "texture3d<float>"},
     {{{"MTLPixelFormatR32Float", "MTLPixelFormatRG32Float", "MTLPixelFormatRGBA32Float",
        "MTLPixelFormatRGBA32Float"},
       {"MTLPixelFormatR8Unorm", "MTLPixelFormatRG8Unorm", "MTLPixelFormatRGBA8Unorm",
        "MTLPixelFormatRGBA8Unorm"},
       {"MTLPixelFormatR16Unorm", "MTLPixelFormatRG16Unorm", "MTLPixelFormatRGBA16Unorm",
        "MTLPixelFormatRGBA16Unorm"}}},
     "\nfragment void main0("},
    // Godot's files (export_godot.hpp): a float image read texel by texel as its floats' bytes
    // in a grey + alpha PNG (png8), a filtered image as OpenEXR, which Godot imports as half
    // floats.
    {ShaderLanguage::godot,
     "godot",
     "Godot 3 shading language",
     "Godot 3.2 and later 3.x (GLES3)",
     ".shader",
     "A complete spatial shader: copy its uniforms and functions into another Godot 3 shader.",
     "`texelFetch` of eight LA8 texels, the float32 values' bytes",
     {"sampler2D", "sampler3D"},
     {{{"RGBH (half floats)", "RGBH (half floats)", "RGBH (half floats)", "RGBAH (half floats)"},
       {"LA8", "LA8", "LA8", "LA8"},
       {"RGBH (half floats)", "RGBH (half floats)", "RGBH (half floats)", "RGBAH (half floats)"}}},
     "\nvoid main()\n"},
}};

// kLanguageRows holds one row per ShaderLanguage, in the enum's order.
constexpr bool rows_in_enum_order() {
  for (std::size_t i = 0; i < kLanguageRows.size(); ++i)
    if (static_cast<std::size_t>(kLanguageRows[i].language) != i) return false;
  return true;
}
static_assert(rows_in_enum_order(), "kLanguageRows must follow ShaderLanguage's order");

// The row of `language`.
constexpr const LanguageRow& language_row(ShaderLanguage language) {
  return kLanguageRows[static_cast<std::size_t>(language)];
}

// The row called `name` (its --language spelling), or nullptr.
const LanguageRow* find_language(std::string_view name);

// The names as a sentence lists them: "glsl, essl, hlsl or msl".
std::string language_names();

// `stochtex languages`: one line per language, its name, title, targets and shader file, and
// which is the default (ShaderExportOptions's).
std::string languages_text();

// `stochtex languages --json` and the studio's `/api/languages`: an array of one object per
// language, in the table's order: {"name", "title", "targets", "extension", "default"}.
std::string languages_json();

}  // namespace stochtex::gl
