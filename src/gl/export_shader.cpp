// `stochtex export-shader`: each method's GLSL library (the renderer's own code, with its data
// read from textures instead of storage buffers; Twin::shader in src/methods/<m>/gl_data.cpp) in
// the asked-for language (cross_compile.hpp), the data as RGBA float images, wrappers and a README
// written here the same for every method.

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gl/cross_compile.hpp"
#include "gl/twin.hpp"
#include "model/model_data.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex {
namespace gl {
namespace {

// One exported texture: the image's file stem and the sampler uniform it binds to.
struct Texture {
  std::string stem;
  std::string sampler;
};

const char* const kArguments =
    "`p` is in exemplar pixels (1 unit = 1 pixel of the analysed image), `dpdx`/`dpdy` its "
    "screen\nderivatives (`dFdx(p)`, `dFdy(p)` in a fragment shader; `vec2(0)` for no "
    "filtering) and `seed`\npicks the random pattern. The result's first `channels` "
    "components are the colour.\n\n";

std::string file_extension(ShaderLanguage language) {
  switch (language) {
    case ShaderLanguage::glsl:
      return ".glsl";
    case ShaderLanguage::essl:
      return ".essl";
    case ShaderLanguage::hlsl:
      return ".hlsl";
    case ShaderLanguage::msl:
      return ".metal";
  }
  return {};
}

// Where a cross-compiled library goes in the caller's shader.
const char* placement(ShaderLanguage language) {
  switch (language) {
    case ShaderLanguage::essl:
      return "Paste or include after `#version 300 es`.";
    case ShaderLanguage::hlsl:
      return "Include it in a Shader Model 5 shader.";
    case ShaderLanguage::msl:
      return "Include it in a Metal shader.";
    case ShaderLanguage::glsl:
      break;
  }
  return "";
}

// How the language reads one texel of a data texture.
const char* texel_read(ShaderLanguage language) {
  switch (language) {
    case ShaderLanguage::glsl:
    case ShaderLanguage::essl:
      return "`texelFetch`";
    case ShaderLanguage::hlsl:
      return "`Texture2D.Load`";
    case ShaderLanguage::msl:
      return "`texture2d::read`";
  }
  return "";
}

std::string shader_graph_file(const std::string& method) {
  return "stochtex_" + method + "_shadergraph.hlsl";
}

// The GLSL 4.50 README of an export: files, entry point, binding in plain OpenGL 4.5, and method
// notes.
std::string glsl_readme(const std::string& method, const std::string& title,
                        const std::string& glsl_file, const std::vector<Texture>& textures,
                        const std::string& notes) {
  std::ostringstream text;
  text << "# stochtex " << title << " shader\n\nFiles: `" << glsl_file
       << "` (the noise, self-contained)\nand";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " `" : ", `") << textures[i].stem << ".exr`";
  text << " (the model's data, RGBA float32).\nThe GLSL declares";
  for (const Texture& t : textures) text << " `uniform sampler2D " << t.sampler << ";`";
  text << " and exposes\n\n    vec4 stochtex_" << method
       << "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed);\n\n"
       << kArguments
       << "Binding it in a plain OpenGL 4.5 program (load each EXR with any EXR reader into "
          "`texels`,\n`width` x `height` RGBA floats):\n\n```c\n";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << "// " << textures[i].stem << ".exr on texture unit " << i << "\n"
         << "GLuint texture" << i << ";\nglCreateTextures(GL_TEXTURE_2D, 1, &texture" << i
         << ");\nglTextureStorage2D(texture" << i << ", 1, GL_RGBA32F, width, height);\n"
         << "glTextureSubImage2D(texture" << i
         << ", 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels);\nglBindTextureUnit(" << i
         << ", texture" << i << ");\nglProgramUniform1i(program, glGetUniformLocation(program, \""
         << textures[i].sampler << "\"), " << i << ");\n";
  text << "```\n\n```glsl\n#version 450\n// ... contents of " << glsl_file
       << " ...\nin vec2 uv;  // your surface coordinate\nout vec4 colour;\nvoid main() {\n"
          "  vec2 p = uv * 512.0;  // scaled to exemplar pixels\n  colour = vec4(stochtex_"
       << method << "(p, dFdx(p), dFdy(p), 7u).rgb, 1.0);\n}\n```\n\n"
       << "The textures are read with `texelFetch` (exact texels, no sampler filtering needed): "
          "the shader\ndoes its own interpolation and footprint filtering, the same as the CPU "
          "reference, whose output\nit matches to float rounding (tested).\n";
  if (!notes.empty()) text << "\n" << notes << "\n";
  return text.str();
}

// The binding of the data textures in a cross-compiled language, after the shared introduction.
void write_binding(std::ostringstream& text, ShaderLanguage language, const std::string& method,
                   const std::string& file, const std::vector<Texture>& textures,
                   const std::string& texture_arguments) {
  switch (language) {
    case ShaderLanguage::essl:
      text << "Binding it in WebGL2 (load each EXR into `texels`, a Float32Array of `width` x "
              "`height` RGBA\nfloats). Float textures are not filterable in WebGL2: with the "
              "default filters they are\nincomplete and read as zero, so set NEAREST.\n\n```js\n";
      for (std::size_t i = 0; i < textures.size(); ++i)
        text << "// " << textures[i].stem << ".exr on texture unit " << i << "\n"
             << "gl.activeTexture(gl.TEXTURE0 + " << i << ");\n"
             << "gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());\n"
             << "gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);\n"
             << "gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, "
                "texels);\n"
             << "gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);\n"
             << "gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);\n"
             << "gl.uniform1i(gl.getUniformLocation(program, \"" << textures[i].sampler << "\"), "
             << i << ");\n";
      text << "```\n\n```glsl\n#version 300 es\n// ... contents of " << file
           << " ...\nin highp vec2 uv;  // your surface coordinate\nout highp vec4 colour;\n"
              "void main() {\n  highp vec2 p = uv * 512.0;  // scaled to exemplar pixels\n"
              "  colour = vec4(stochtex_"
           << method << "(p, dFdx(p), dFdy(p), 7u).rgb, 1.0);\n}\n```\n";
      break;
    case ShaderLanguage::hlsl:
      text << "Binding it in Direct3D 11: each EXR as a `DXGI_FORMAT_R32G32B32A32_FLOAT` "
              "texture of one mip level,\nits shader resource view on the `t` register that "
              "shader reflection reports for its name\n(`GetResourceBindingDescByName`); the "
              "sampler states are declared but never used.\n\n```hlsl\n// ... contents of "
           << file
           << " ...\nfloat4 main(float4 position : SV_Position, float2 uv : TEXCOORD0) : "
              "SV_Target {\n  float2 p = uv * 512.0;  // scaled to exemplar pixels\n  return "
              "float4(stochtex_"
           << method << "(p, ddx(p), ddy(p), 7u).rgb, 1.0);\n}\n```\n\n"
           << "Unity: import each EXR with sRGB off, Generate Mip Maps off, Filter Mode Point, "
              "Wrap Mode Clamp,\nCompression None and Format RGBA Float, and set it by name from "
              "a script:\n\n```csharp\n";
      for (const Texture& t : textures)
        text << "material.SetTexture(\"" << t.sampler << "\", " << t.stem << ");\n";
      text << "```\n\nIn Shader Graph, add a Custom Function node of Type File with Source\n`"
           << shader_graph_file(method) << "`, Name `stochtex_" << method
           << "`, precision Float, inputs `p`, `dpdx`,\n`dpdy` (Vector 2) and `seed` (Float, a "
              "whole number below 2^24) and output `colour`\n(Vector 4). It calls `stochtex_"
           << method << "_float`.\n";
      break;
    case ShaderLanguage::msl:
      text << "Metal has no global textures: the function takes each texture and a sampler "
              "(declared, never\nused) as arguments. Binding it: each EXR as an "
              "`MTLPixelFormatRGBA32Float` texture with\n`mipmapLevelCount = 1`, and any "
              "sampler state.\n\n```metal\n// ... contents of "
           << file
           << " ...\nstruct Varyings {\n  float4 position [[position]];\n  float2 uv;  // "
              "your surface coordinate\n};\nfragment float4 shade(Varyings in [[stage_in]]";
      for (std::size_t i = 0; i < textures.size(); ++i)
        text << ",\n                      texture2d<float> " << textures[i].sampler << " [[texture("
             << i << ")]],\n                      sampler " << textures[i].sampler
             << "Smplr [[sampler(" << i << ")]]";
      text << ") {\n  float2 p = in.uv * 512.0;  // scaled to exemplar pixels\n  return "
              "float4(stochtex_"
           << method << "(p, dfdx(p), dfdy(p), 7u" << texture_arguments << ").rgb, 1.0);\n}\n```\n";
      break;
    case ShaderLanguage::glsl:
      break;
  }
}

// The README of a cross-compiled export: the GLSL one's content, in the language's terms.
std::string cross_readme(ShaderLanguage language, const std::string& method,
                         const std::string& title, const std::string& file,
                         const std::string& signature, const std::vector<Texture>& textures,
                         const std::string& notes) {
  const std::string_view language_name = language_title(language);
  std::ostringstream text;
  text << "# stochtex " << title << " shader in " << language_name << "\n\nFiles:\n\n- `" << file
       << "`: the noise, self-contained, cross-compiled from the GLSL 4.50 by\n  glslang and "
          "SPIRV-Cross;\n";
  if (language == ShaderLanguage::hlsl)
    text << "- `" << shader_graph_file(method)
         << "`: the same as a Unity Shader Graph custom "
            "function;\n";
  for (const Texture& t : textures)
    text << "- `" << t.stem << ".exr`: the model's data, RGBA float32, linear values;\n";
  text << "\nThe function keeps the GLSL's signature:\n\n    " << signature << ";\n\n"
       << kArguments;
  std::string texture_arguments;
  for (const Texture& t : textures)
    texture_arguments += ", " + t.sampler + ", " + t.sampler + "Smplr";
  write_binding(text, language, method, file, textures, texture_arguments);
  text << "\nEvery data texture is read texel by texel (" << texel_read(language)
       << "): one mip level, no sampler filtering,\nno sRGB decoding. The shader does its own "
          "interpolation and footprint filtering, the same as\nthe CPU reference.\n";
  if (!notes.empty()) text << "\n" << notes << "\n";
  return text.str();
}

// The comment opening the shader file.
std::string export_header(ShaderLanguage language, const std::string& what,
                          const std::string& method, const std::vector<Texture>& textures) {
  std::ostringstream text;
  if (language == ShaderLanguage::glsl)
    text << "// " << what << " exported by `stochtex export-shader`.\n"
         << "// Paste or include after `#version 450`.\n// Bind";
  else
    text << "// " << what << " exported by\n// `stochtex export-shader --language "
         << language_option(language) << "` (" << language_title(language)
         << "), cross-compiled from the GLSL 4.50\n// by glslang and SPIRV-Cross. "
         << placement(language) << "\n// Bind";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " " : ",\n// ") << textures[i].stem << ".exr as an RGBA32F texture to `"
         << textures[i].sampler << "`";
  text << ",\n// then call stochtex_" << method << "(p, dpdx, dpdy, seed"
       << (language == ShaderLanguage::msl ? ", <textures, samplers>" : "")
       << "). See README.md.\n\n";
  return text.str();
}

// Shader Graph's Custom Function (File mode) calls <name>_float with the node's ports.
TextFile shader_graph_wrapper(const std::string& method, const std::string& what,
                              const std::string& hlsl, const std::vector<Texture>& textures) {
  std::string guard = "STOCHTEX_" + method + "_SHADERGRAPH_INCLUDED";
  std::transform(guard.begin(), guard.end(), guard.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  std::ostringstream text;
  text << "// " << what
       << ": a Unity Shader Graph custom function, exported by\n// `stochtex "
          "export-shader --language hlsl`. Custom Function node: Type File, this file, Name\n"
          "// stochtex_"
       << method
       << ", precision Float; inputs p, dpdx, dpdy (Vector 2), seed (Float); output colour\n"
          "// (Vector 4). Set";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " " : ", ") << textures[i].sampler;
  text << " on the material by script. See README.md.\n#ifndef " << guard << "\n#define " << guard
       << "\n\n"
       << hlsl << "\nvoid stochtex_" << method
       << "_float(float2 p, float2 dpdx, float2 dpdy, uint seed, out float4 colour) {\n"
       << "  colour = stochtex_" << method << "(p, dpdx, dpdy, seed);\n}\n\n#endif  // " << guard
       << "\n";
  return {shader_graph_file(method), text.str()};
}

ShaderExport assemble_export(ExportParts parts, ShaderLanguage language) {
  const std::string method(parts.method);
  std::vector<Texture> textures;
  for (const NamedImage& image : parts.images)
    textures.push_back({image.name, "stochtex_" + image.name});
  ShaderExport result;
  result.shader.name = "stochtex_" + method + file_extension(language);
  if (language == ShaderLanguage::glsl) {
    result.shader.text = export_header(language, parts.what, method, textures) + parts.library;
    result.readme = glsl_readme(method, parts.title, result.shader.name, textures, parts.notes);
  } else {
    const std::string function = "stochtex_" + method;
    const std::string source = cross_compile(parts.library, function, method, language);
    const std::size_t name = source.find(function + "(");
    const std::size_t line = source.rfind('\n', name) + 1;
    const std::string signature = source.substr(line, source.find('\n', name) - line);
    result.shader.text = export_header(language, parts.what, method, textures) + source;
    if (language == ShaderLanguage::hlsl)
      result.wrappers.push_back(shader_graph_wrapper(method, parts.what, source, textures));
    result.readme = cross_readme(language, method, parts.title, result.shader.name, signature,
                                 textures, parts.notes);
  }
  result.images = std::move(parts.images);
  return result;
}

}  // namespace

}  // namespace gl

ShaderExport export_shader(const Model& model, const ShaderExportOptions& options) {
  if (model.empty()) throw std::invalid_argument("export_shader: the model is empty");
  return std::visit(
      [&](const auto& method_model) {
        return gl::assemble_export(
            gl::Twin<std::decay_t<decltype(method_model)>>::shader(method_model), options.language);
      },
      model.data().model);
}

}  // namespace stochtex
