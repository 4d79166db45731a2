// `stochtex export-shader`: each method's GLSL library (the renderer's own code, with its data
// read from textures instead of storage buffers; Twin::shader in src/methods/<m>/gl_data.cpp) in
// the asked-for variant and language (cross_compile.hpp), the data as images (exact: RGBA float;
// fast: the formats ShaderTexture names), wrappers and a README written here the same for every
// method.

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gl/cross_compile.hpp"
#include "gl/export_material.hpp"
#include "gl/twin.hpp"
#include "model/model_data.hpp"
#include "stochtex/error.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex {
namespace gl {
namespace {

// What an export's README, header and wrappers name: the method and, for a material, its
// function (export_material.hpp); otherwise stochtex_<method>.
struct Entry {
  std::string method;
  const MaterialShader* material = nullptr;

  std::string function() const { return material ? material->function : "stochtex_" + method; }
};

// The arguments of the entry point and what it returns.
std::string arguments(const Entry& entry) {
  return std::string(
             "`p` is in exemplar pixels (1 unit = 1 pixel of the analysed image), `dpdx`/`dpdy` "
             "its screen\nderivatives (`dFdx(p)`, `dFdy(p)` in a fragment shader; `vec2(0)` for "
             "no filtering) and `seed`\npicks the random pattern.") +
         (entry.material ? "\n\n"
                         : " The result's first `channels` components are the colour.\n\n");
}

// The GLSL entry point's documentation: its signature and arguments (a material: and its struct).
std::string entry_point(const Entry& entry) {
  const std::string type = entry.material ? "StochtexMaterial " : "vec4 ";
  std::string text = "\n\n    " + type + entry.function() +
                     "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed);\n\n" + arguments(entry);
  if (entry.material) text += material_readme(*entry.material, ShaderLanguage::glsl) + "\n";
  return text;
}

// An example's RGB colour from `call`, the entry point's result in a language whose 3-vector is
// `vec3`: its .rgb, or a material's first member of 3 components (else its first, as grey).
std::string example_colour(const Entry& entry, const std::string& call, std::string_view vec3) {
  if (!entry.material) return call + ".rgb";
  const std::vector<MaterialMember>& members = entry.material->members;
  const auto vector = std::find_if(members.begin(), members.end(),
                                   [](const MaterialMember& member) { return member.vector; });
  if (vector != members.end()) return call + "." + vector->name;
  return std::string(vec3) + "(" + call + "." + members.front().name + ")";
}

// A fragment shader calling the entry point.
std::string usage(const Entry& entry, const std::string& glsl_file) {
  return "```glsl\n#version 450\n// ... contents of " + glsl_file +
         " ...\nin vec2 uv;  // your surface coordinate\nout vec4 colour;\nvoid main() {\n"
         "  vec2 p = uv * 512.0;  // scaled to exemplar pixels\n  colour = vec4(" +
         example_colour(entry, entry.function() + "(p, dFdx(p), dFdy(p), 7u)", "vec3") +
         ", 1.0);\n}\n```\n\n";
}

constexpr std::array<const char*, 4> kChannelNames = {"grey", "grey + alpha", "RGB", "RGBA"};

std::string file_format(const ShaderTexture& t) {
  const char* channels = kChannelNames[static_cast<std::size_t>(t.image.channels() - 1)];
  constexpr std::array<const char*, 3> kEncodings = {"OpenEXR float32", "PNG 8-bit", "PNG 16-bit"};
  return std::string(kEncodings[static_cast<std::size_t>(t.encoding)]) + " " + channels;
}

// The texture format of `t` in `language`'s API (GL_RGB16, DXGI_FORMAT_..., MTLPixelFormat...).
std::string_view texture_format(ShaderLanguage language, const ShaderTexture& t) {
  return language_row(language).formats[static_cast<std::size_t>(t.encoding)]
                                       [static_cast<std::size_t>(t.image.channels() - 1)];
}

std::string texture_shape(const ShaderTexture& t) {
  const int height = t.image.height() / t.depth;
  if (t.depth == 1)
    return "2-D " + std::to_string(t.image.width()) + " x " + std::to_string(height);
  return "3-D " + std::to_string(t.image.width()) + " x " + std::to_string(height) + " x " +
         std::to_string(t.depth) + " (the image's " + std::to_string(t.depth) + " slices of " +
         std::to_string(height) + " rows, top to bottom)";
}

std::string filter_text(const ShaderTexture& t) {
  switch (t.filter) {
    case TextureFilter::nearest:
      return "nearest (read texel by texel)";
    case TextureFilter::linear:
      return t.depth == 1 ? "bilinear" : "trilinear";
    case TextureFilter::mipmap:
      break;
  }
  return "trilinear mip-mapped, anisotropic up to 16x";
}

std::string wrap_text(TextureWrap wrap) {
  constexpr std::array<const char*, 3> kWraps = {"clamp to edge",
                                                 "clamp to border (transparent black)", "repeat"};
  return kWraps[static_cast<std::size_t>(wrap)];
}

std::string mip_text(const ShaderTexture& t) {
  if (t.mip_levels == 1) return "none";
  return "generated by the engine (2 x 2 box, glGenerateMipmap), levels 0-" +
         std::to_string(t.mip_levels - 1);
}

// The fast variant's introduction, its data files with their texture settings in `language`'s
// terms and the colour spaces: the part of the README every language shares.
std::string fast_data_section(ShaderLanguage language, const std::vector<ShaderTexture>& textures) {
  std::ostringstream text;
  text << "This is the GLSL that `stochtex render --backend gl --gl-filter hardware` runs"
       << (language == ShaderLanguage::glsl ? "" : " (cross-compiled)")
       << ", its data\nread through the samplers the table below sets up. It is not the CPU "
          "render pixel for pixel\n(`export-shader --variant exact` for that): see the notes "
          "at the end.\n\n"
          "## Data files\n\n| file | texture | file format | texture format | filter | wrap | "
          "mip-maps |\n|---|---|---|---|---|---|---|\n";
  const LanguageRow& row = language_row(language);
  for (const ShaderTexture& t : textures)
    text << "| `" << t.file_name() << "` | `" << row.texture_types[t.depth == 1 ? 0 : 1]
         << " stochtex_" << t.name << "` | " << file_format(t) << " | "
         << texture_format(language, t) << ", " << texture_shape(t) << " | " << filter_text(t)
         << " | " << wrap_text(t.wrap) << " | " << mip_text(t) << " |\n";
  text << "\nPNG values are sample / 255 (8-bit) or sample / 65535 (16-bit). A 3-D texture's "
          "image holds its\nslices stacked top to bottom, so its texels in row order are the "
          "3-D texture's in x, y, z order:\nupload the whole image as the 3-D texture's data "
          "(Unity: a Texture3D from the pixels; Unreal: a\nvolume texture from the image as "
          "1 x depth tiles).\n\n"
          "## Colour spaces\n\nEvery data file is linear data, not colour: import it without "
          "sRGB decoding (GL: the UNORM\nformats above, never SRGB8; Unity: \"sRGB (Color "
          "Texture)\" off; Unreal: sRGB off) and without\nchanging its values. Engine block "
          "compression (BC7, ASTC) works but adds its own error, not\nmeasured here. The "
          "result has the values of the analysed exemplar file (PNG bytes / 255, not\ndecoded "
          "from sRGB), the CPU render's: for an ordinary sRGB exemplar it is sRGB-encoded, so "
          "a\nlinear-space engine converts it to linear before lighting (or writes it "
          "unconverted to a\nnon-sRGB target) and then shows the CPU render's colours.\n\n";
  return text.str();
}

// README.md of a fast export: files with their texture settings, entry point, colour spaces,
// binding in plain OpenGL 4.5, and method notes.
std::string fast_readme(const Entry& entry, const std::string& title, const std::string& glsl_file,
                        const std::vector<ShaderTexture>& textures, const std::string& notes) {
  std::ostringstream text;
  text << "# stochtex " << title << " shader (fast variant)\n\nFiles: `" << glsl_file
       << "` (the noise, self-contained) and the data images below. It exposes"
       << entry_point(entry) << fast_data_section(ShaderLanguage::glsl, textures)
       << "## Binding in plain OpenGL 4.5\n\n```c\n";
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const ShaderTexture& t = textures[i];
    const bool volume = t.depth > 1;
    const std::string id = "texture" + std::to_string(i);
    const int height = t.image.height() / t.depth;
    text << "// " << t.file_name() << " on texture unit " << i << ": `texels` as loaded ("
         << (t.encoding == TextureEncoding::exr_float32
                 ? "floats"
                 : (t.encoding == TextureEncoding::png8 ? "bytes" : "16-bit samples"))
         << ")\nGLuint " << id << ";\nglCreateTextures("
         << (volume ? "GL_TEXTURE_3D" : "GL_TEXTURE_2D") << ", 1, &" << id << ");\n";
    if (volume)
      text << "glTextureStorage3D(" << id << ", " << t.mip_levels << ", "
           << texture_format(ShaderLanguage::glsl, t) << ", " << t.image.width() << ", " << height
           << ", " << t.depth << ");\nglTextureSubImage3D(" << id << ", 0, 0, 0, 0, "
           << t.image.width() << ", " << height << ", " << t.depth;
    else
      text << "glTextureStorage2D(" << id << ", " << t.mip_levels << ", "
           << texture_format(ShaderLanguage::glsl, t) << ", " << t.image.width() << ", " << height
           << ");\nglTextureSubImage2D(" << id << ", 0, 0, 0, " << t.image.width() << ", "
           << height;
    constexpr std::array<const char*, 4> kLayouts = {"GL_RED", "GL_RG", "GL_RGB", "GL_RGBA"};
    constexpr std::array<const char*, 3> kTypes = {"GL_FLOAT", "GL_UNSIGNED_BYTE",
                                                   "GL_UNSIGNED_SHORT"};
    text << ", " << kLayouts[static_cast<std::size_t>(t.image.channels() - 1)] << ", "
         << kTypes[static_cast<std::size_t>(t.encoding)] << ", texels);\n";
    if (t.mip_levels > 1) text << "glGenerateTextureMipmap(" << id << ");\n";
    constexpr std::array<const char*, 3> kMinFilters = {"GL_NEAREST", "GL_LINEAR",
                                                        "GL_LINEAR_MIPMAP_LINEAR"};
    const bool nearest = t.filter == TextureFilter::nearest;
    text << "glTextureParameteri(" << id << ", GL_TEXTURE_MIN_FILTER, "
         << kMinFilters[static_cast<std::size_t>(t.filter)] << ");\nglTextureParameteri(" << id
         << ", GL_TEXTURE_MAG_FILTER, " << (nearest ? "GL_NEAREST" : "GL_LINEAR") << ");\n";
    if (t.filter == TextureFilter::mipmap)
      text << "glTextureParameterf(" << id << ", GL_TEXTURE_MAX_ANISOTROPY, 16.0f);\n";
    constexpr std::array<const char*, 3> kWraps = {"GL_CLAMP_TO_EDGE", "GL_CLAMP_TO_BORDER",
                                                   "GL_REPEAT"};
    for (const char* axis : {"S", "T", "R"}) {
      if (!volume && axis[0] == 'R') continue;
      text << "glTextureParameteri(" << id << ", GL_TEXTURE_WRAP_" << axis << ", "
           << kWraps[static_cast<std::size_t>(t.wrap)] << ");\n";
    }
    text << "glBindTextureUnit(" << i << ", " << id
         << ");\nglProgramUniform1i(program, glGetUniformLocation(program, \"stochtex_" << t.name
         << "\"), " << i << ");\n";
  }
  text << "```\n\n" << usage(entry, glsl_file);
  if (!notes.empty()) text << notes << "\n";
  return text.str();
}

std::string shader_graph_file(const std::string& method) {
  return "stochtex_" + method + "_shadergraph.hlsl";
}

// The GLSL 4.50 README of an export: files, entry point, binding in plain OpenGL 4.5, and method
// notes.
std::string glsl_readme(const Entry& entry, const std::string& title, const std::string& glsl_file,
                        const std::vector<ShaderTexture>& textures, const std::string& notes) {
  std::ostringstream text;
  text << "# stochtex " << title << " shader\n\nFiles: `" << glsl_file
       << "` (the noise, self-contained)\nand";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " `" : ", `") << textures[i].name << ".exr`";
  text << " (the model's data, RGBA float32).\nThe GLSL declares";
  for (const ShaderTexture& t : textures) text << " `uniform sampler2D stochtex_" << t.name << ";`";
  text << " and exposes" << entry_point(entry)
       << "Binding it in a plain OpenGL 4.5 program (load each EXR with any EXR reader into "
          "`texels`,\n`width` x `height` RGBA floats):\n\n```c\n";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << "// " << textures[i].name << ".exr on texture unit " << i << "\n"
         << "GLuint texture" << i << ";\nglCreateTextures(GL_TEXTURE_2D, 1, &texture" << i
         << ");\nglTextureStorage2D(texture" << i << ", 1, GL_RGBA32F, width, height);\n"
         << "glTextureSubImage2D(texture" << i
         << ", 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels);\nglBindTextureUnit(" << i
         << ", texture" << i << ");\nglProgramUniform1i(program, glGetUniformLocation(program, \""
         << "stochtex_" << textures[i].name << "\"), " << i << ");\n";
  text << "```\n\n"
       << usage(entry, glsl_file)
       << "The textures are read with `texelFetch` (exact texels, no sampler filtering needed): "
          "the shader\ndoes its own interpolation and footprint filtering, the same as the CPU "
          "reference, whose output\nit matches to float rounding (tested).\n";
  if (!notes.empty()) text << "\n" << notes << "\n";
  return text.str();
}

// The Shader Graph node's outputs, as the README names them.
std::string shader_graph_outputs(const Entry& entry) {
  if (!entry.material) return "output `colour`\n(Vector 4)";
  std::string text = "outputs";
  for (const MaterialMember& member : entry.material->members)
    text += std::string(&member == &entry.material->members.front() ? " `" : ", `") + member.name +
            "` (" + (member.vector ? "Vector 3" : "Float") + ")";
  return text;
}

// The binding of the data textures in a cross-compiled language, after the shared introduction
// (fast: after the data table). `call_arguments` follow `seed` in the example's call (Metal: the
// textures, samplers and the variables SPIRV-Cross made of the library's private globals, which
// `locals` declares).
void write_binding(std::ostringstream& text, ShaderLanguage language, ShaderVariant variant,
                   const Entry& entry, const std::string& file,
                   const std::vector<ShaderTexture>& textures, const std::string& call_arguments,
                   const std::string& locals) {
  const bool fast = variant == ShaderVariant::fast;
  switch (language) {
    case ShaderLanguage::essl:
      if (fast) {
        text << "## Binding in WebGL2\n\nEach file as a `TEXTURE_2D` or `TEXTURE_3D` "
                "(`texStorage2D`/`texStorage3D` with the\nformat and levels of the table, "
                "`texSubImage` with the file's values as `UNSIGNED_BYTE`,\n`UNSIGNED_SHORT` or "
                "`FLOAT`), `generateMipmap` where it has mip-maps, the filter and wrap of\nthe "
                "table, and `gl.uniform1i` with its sampler's name; an RGB file loads as RGBA "
                "(alpha 1),\nsince `generateMipmap` needs a colour-renderable format. WebGL2 "
                "lacks some of this: the 16-bit\nformats need `EXT_texture_norm16`, a float "
                "texture needs `OES_texture_float_linear` to be filtered\nand "
                "`EXT_color_buffer_float` for its mip-maps, and there is no clamp to border "
                "(CLAMP_TO_EDGE\ninstead reads the texton texture's zero padding at level 0, "
                "not at coarser levels; not measured).\n\n```glsl";
      } else {
        text << "Binding it in WebGL2 (load each EXR into `texels`, a Float32Array of `width` x "
                "`height` RGBA\nfloats). Float textures are not filterable in WebGL2: with the "
                "default filters they are\nincomplete and read as zero, so set NEAREST.\n\n```js\n";
        for (std::size_t i = 0; i < textures.size(); ++i)
          text << "// " << textures[i].file_name() << " on texture unit " << i << "\n"
               << "gl.activeTexture(gl.TEXTURE0 + " << i << ");\n"
               << "gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());\n"
               << "gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);\n"
               << "gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, "
                  "texels);\n"
               << "gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);\n"
               << "gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);\n"
               << "gl.uniform1i(gl.getUniformLocation(program, \""
               << "stochtex_" << textures[i].name << "\"), " << i << ");\n";
        text << "```\n\n```glsl";
      }
      text << "\n#version 300 es\n// ... contents of " << file
           << " ...\nin highp vec2 uv;  // your surface coordinate\nout highp vec4 colour;\n"
              "void main() {\n  highp vec2 p = uv * 512.0;  // scaled to exemplar pixels\n"
              "  colour = vec4("
           << example_colour(entry, entry.function() + "(p, dFdx(p), dFdy(p), 7u)", "vec3")
           << ", 1.0);\n}\n```\n";
      break;
    case ShaderLanguage::hlsl:
      if (fast)
        text << "## Binding in Direct3D 11\n\nEach file as a `Texture2D` or `Texture3D` of the "
                "table's format and mip levels (generated with\n`GenerateMips`), its shader "
                "resource view on the `t` register that shader reflection reports for\nits name "
                "(`GetResourceBindingDescByName`), and a sampler state with the table's filter "
                "and wrap\n(`D3D11_FILTER_ANISOTROPIC` with `MaxAnisotropy = 16`, "
                "`MIN_MAG_MIP_LINEAR` or `MIN_MAG_MIP_POINT`;\n`D3D11_TEXTURE_ADDRESS_WRAP`, "
                "`CLAMP` or `BORDER` with border colour 0) on the register of\n"
                "`_stochtex_<name>_sampler`.\n\n```hlsl\n// ... contents of ";
      else
        text << "Binding it in Direct3D 11: each EXR as a `DXGI_FORMAT_R32G32B32A32_FLOAT` "
                "texture of one mip level,\nits shader resource view on the `t` register that "
                "shader reflection reports for its name\n(`GetResourceBindingDescByName`); the "
                "sampler states are declared but never used.\n\n```hlsl\n// ... contents of ";
      text << file
           << " ...\nfloat4 main(float4 position : SV_Position, float2 uv : TEXCOORD0) : "
              "SV_Target {\n  float2 p = uv * 512.0;  // scaled to exemplar pixels\n  return "
              "float4("
           << example_colour(entry, entry.function() + "(p, ddx(p), ddy(p), 7u)", "float3")
           << ", 1.0);\n}\n```\n\n";
      if (fast)
        text << "Unity: import each file with sRGB off, Compression None, Generate Mip Maps on "
                "where the table has\nmip-maps, Filter Mode Trilinear (mip-mapped), Bilinear or "
                "Point and Wrap Mode Repeat or Clamp\n(Unity has no border colour: Clamp, as for "
                "WebGL2 above); make a 3-D table a `Texture3D` from the\nimage's pixels by "
                "script. Set each by name from a script:\n\n```csharp\n";
      else
        text << "Unity: import each EXR with sRGB off, Generate Mip Maps off, Filter Mode Point, "
                "Wrap Mode Clamp,\nCompression None and Format RGBA Float, and set it by name from "
                "a script:\n\n```csharp\n";
      for (const ShaderTexture& t : textures)
        text << "material.SetTexture(\"stochtex_" << t.name << "\", " << t.name << ");\n";
      text << "```\n\nIn Shader Graph, add a Custom Function node of Type File with Source\n`"
           << shader_graph_file(entry.method) << "`, Name `" << entry.function()
           << "`, precision Float, inputs `p`, `dpdx`,\n`dpdy` (Vector 2) and `seed` (Float, a "
              "whole number below 2^24) and "
           << shader_graph_outputs(entry) << ". It calls `" << entry.function() << "_float`.\n";
      break;
    case ShaderLanguage::msl:
      if (fast)
        text << "## Binding in Metal\n\nMetal has no global textures or variables: the function "
                "takes each texture and its sampler as\narguments, and the library's private "
                "variables as `thread` references the caller declares.\nEach file as an "
                "`MTLTexture` of the table's type, format and mip levels (generated with a\nblit "
                "encoder's `generateMipmapsForTexture`), its sampler an `MTLSamplerState` with "
                "the table's\nfilter (`minFilter`, `magFilter`, `mipFilter` linear and "
                "`maxAnisotropy = 16` for mip-mapped ones)\nand wrap (`Repeat`, `ClampToEdge` or "
                "`ClampToBorderColor` with `TransparentBlack`).\n\n```metal\n// ... contents of ";
      else
        text << "Metal has no global textures: the function takes each texture and a sampler "
                "(declared, never\nused) as arguments"
             << (locals.empty() ? ""
                                : ", and the library's private variables as `thread` references "
                                  "the caller\ndeclares")
             << ". Binding it: each EXR as an `MTLPixelFormatRGBA32Float` texture with\n"
                "`mipmapLevelCount = 1`, and any sampler state.\n\n```metal\n// ... contents of ";
      text << file
           << " ...\nstruct Varyings {\n  float4 position [[position]];\n  float2 uv;  // "
              "your surface coordinate\n};\nfragment float4 shade(Varyings in [[stage_in]]";
      for (std::size_t i = 0; i < textures.size(); ++i)
        text << ",\n                      "
             << language_row(language).texture_types[textures[i].depth == 1 ? 0 : 1] << " stochtex_"
             << textures[i].name << " [[texture(" << i
             << ")]],\n                      sampler stochtex_" << textures[i].name
             << "Smplr [[sampler(" << i << ")]]";
      text << ") {\n"
           << locals
           << "  float2 p = in.uv * 512.0;  // scaled to exemplar pixels\n  return "
              "float4("
           << example_colour(entry,
                             entry.function() + "(p, dfdx(p), dfdy(p), 7u" + call_arguments + ")",
                             "float3")
           << ", 1.0);\n}\n```\n";
      break;
    case ShaderLanguage::glsl:
      break;
  }
}

// The arguments that follow `seed` in the cross-compiled `signature` (Metal: textures, samplers
// and `thread T& name` references to the library's private globals), each as ", name", and the
// declarations of the references' variables.
void extra_parameters(const std::string& signature, std::string& arguments, std::string& locals) {
  const std::size_t open = signature.find('(');
  const std::string list = signature.substr(open + 1, signature.rfind(')') - open - 1);
  std::size_t start = 0;
  for (int index = 0; start <= list.size(); ++index) {
    std::size_t end = list.find(", ", start);
    if (end == std::string::npos) end = list.size();
    const std::string parameter = list.substr(start, end - start);
    start = end + 2;
    if (index < 4) continue;  // p, dpdx, dpdy, seed
    const std::string name = parameter.substr(parameter.rfind(' ') + 1);
    arguments += ", " + name;
    if (parameter.starts_with("thread ") && !parameter.starts_with("thread const ")) {
      const std::string type = parameter.substr(7, parameter.find('&') - 7);
      locals += "  " + type + " " + name + ";\n";
    }
  }
}

// The README of a cross-compiled export: the GLSL one's content, in the language's terms.
std::string cross_readme(ShaderLanguage language, ShaderVariant variant, const Entry& entry,
                         const std::string& title, const std::string& file,
                         const std::string& signature, const std::vector<ShaderTexture>& textures,
                         const std::string& notes) {
  const LanguageRow& row = language_row(language);
  const bool fast = variant == ShaderVariant::fast;
  std::ostringstream text;
  text << "# stochtex " << title << " shader" << (fast ? " (fast variant)" : "") << " in "
       << row.title << "\n\nFiles:\n\n- `" << file
       << "`: the noise, self-contained, cross-compiled from the GLSL 4.50 by\n  glslang and "
          "SPIRV-Cross;\n";
  if (language == ShaderLanguage::hlsl)
    text << "- `" << shader_graph_file(entry.method)
         << "`: the same as a Unity Shader Graph custom "
            "function;\n";
  for (const ShaderTexture& t : textures)
    text << "- `" << t.file_name() << "`: "
         << (fast ? "the model's data, as the table below says;\n"
                  : "the model's data, RGBA float32, linear values;\n");
  text << "\nThe function keeps the GLSL's signature:\n\n    " << signature << ";\n\n"
       << arguments(entry);
  if (entry.material) text << material_readme(*entry.material, language) << "\n";
  if (fast) text << fast_data_section(language, textures);
  std::string call_arguments;
  std::string locals;
  extra_parameters(signature, call_arguments, locals);
  write_binding(text, language, variant, entry, file, textures, call_arguments, locals);
  if (!fast)
    text << "\nEvery data texture is read texel by texel (" << row.texel_read
         << "): one mip level, no sampler filtering,\nno sRGB decoding. The shader does its own "
            "interpolation and footprint filtering, the same as\nthe CPU reference.\n";
  if (!notes.empty()) text << "\n" << notes << "\n";
  return text.str();
}

// The comment opening the shader file.
std::string export_header(ShaderLanguage language, const std::string& what, const Entry& entry,
                          const std::vector<ShaderTexture>& textures, ShaderVariant variant) {
  std::ostringstream text;
  if (language == ShaderLanguage::glsl)
    text << "// " << what << " exported by `stochtex export-shader`.\n"
         << "// Paste or include after `#version 450`.\n// Bind";
  else
    text << "// " << what << " exported by\n// `stochtex export-shader --language "
         << language_row(language).name << "` (" << language_row(language).title
         << "), cross-compiled from the GLSL 4.50\n// by glslang and SPIRV-Cross. "
         << language_row(language).placement << "\n// Bind";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " " : ",\n// ") << textures[i].file_name() << " as "
         << (variant == ShaderVariant::exact
                 ? std::string("an RGBA32F")
                 : "a " + std::string(texture_format(language, textures[i])))
         << " texture to `stochtex_" << textures[i].name << "`";
  text << ",\n// then call " << entry.function() << "(p, dpdx, dpdy, seed"
       << (language == ShaderLanguage::msl ? ", <textures, samplers>" : "")
       << "). See README.md.\n\n";
  return text.str();
}

// Shader Graph's Custom Function (File mode) calls <name>_float with the node's ports: the
// inputs and `colour`, or a material's maps, one output each.
TextFile shader_graph_wrapper(const Entry& entry, const std::string& what, const std::string& hlsl,
                              const std::vector<ShaderTexture>& textures) {
  std::string guard = "STOCHTEX_" + entry.method + "_SHADERGRAPH_INCLUDED";
  std::transform(guard.begin(), guard.end(), guard.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  std::string outputs = "output colour\n// (Vector 4)";
  std::string parameters = ", out float4 colour";
  std::string body = "  colour = " + entry.function() + "(p, dpdx, dpdy, seed);\n";
  if (entry.material) {
    outputs = "outputs";
    parameters.clear();
    body = "  StochtexMaterial material = " + entry.function() + "(p, dpdx, dpdy, seed);\n";
    for (const MaterialMember& member : entry.material->members) {
      outputs += std::string(&member == &entry.material->members.front() ? "\n// " : ", ") +
                 member.name + (member.vector ? " (Vector 3)" : " (Float)");
      parameters += ", out " + std::string(hlsl_type(member)) + " " + member.name;
      body += "  " + member.name + " = material." + member.name + ";\n";
    }
  }
  std::ostringstream text;
  text << "// " << what
       << ": a Unity Shader Graph custom function, exported by\n// `stochtex "
          "export-shader --language hlsl`. Custom Function node: Type File, this file, Name\n"
          "// "
       << entry.function() << ", precision Float; inputs p, dpdx, dpdy (Vector 2), seed (Float); "
       << outputs << ". Set";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " " : ", ") << "stochtex_" << textures[i].name;
  text << " on the material by script. See README.md.\n#ifndef " << guard << "\n#define " << guard
       << "\n\n"
       << hlsl << "\nvoid " << entry.function()
       << "_float(float2 p, float2 dpdx, float2 dpdy, uint seed" << parameters << ") {\n"
       << body << "}\n\n#endif  // " << guard << "\n";
  return {shader_graph_file(entry.method), text.str()};
}

// The export of a method's parts: a model of one image exposes stochtex_<method>, a material (a
// model with `maps`) its material function after the library.
ShaderExport assemble_export(ExportParts parts, ShaderLanguage language,
                             std::span<const MapInfo> maps, int channels) {
  const std::string method(parts.method);
  std::optional<MaterialShader> material;
  if (!maps.empty()) {
    material = material_shader(maps, channels, method, parts.channels_function);
    parts.library += material->glsl;
  }
  const Entry entry{method, material ? &*material : nullptr};
  ShaderExport result;
  result.shader.name = "stochtex_" + method + std::string(language_row(language).extension);
  const std::string header =
      export_header(language, parts.what, entry, parts.textures, parts.variant);
  if (language == ShaderLanguage::glsl) {
    result.shader.text = header + parts.library;
    result.readme =
        parts.variant == ShaderVariant::exact
            ? glsl_readme(entry, parts.title, result.shader.name, parts.textures, parts.notes)
            : fast_readme(entry, parts.title, result.shader.name, parts.textures, parts.notes);
  } else {
    const std::string function = entry.function();
    const std::string source = cross_compile(parts.library, function, method, language);
    const std::size_t name = source.find(function + "(");
    const std::size_t line = source.rfind('\n', name) + 1;
    const std::string signature = source.substr(line, source.find('\n', name) - line);
    result.shader.text = header + source;
    if (language == ShaderLanguage::hlsl)
      result.wrappers.push_back(shader_graph_wrapper(entry, parts.what, source, parts.textures));
    result.readme = cross_readme(language, parts.variant, entry, parts.title, result.shader.name,
                                 signature, parts.textures, parts.notes);
  }
  result.textures = std::move(parts.textures);
  return result;
}

}  // namespace

}  // namespace gl

std::string ShaderTexture::file_name() const {
  return name + (encoding == TextureEncoding::exr_float32 ? ".exr" : ".png");
}

ShaderExport export_shader(const Model& model, const ShaderExportOptions& options) {
  if (model.empty()) throw std::invalid_argument("export_shader: the model is empty");
  if (model.maps().empty() && model.channels() > kMaxImageChannels)
    throw Error(ErrorCode::invalid_input,
                "export-shader writes a vec4 function for a model of one image, and this model "
                "has " +
                    std::to_string(model.channels()) +
                    " channels and no maps; analyse the maps with `stochtex analyze --map` to "
                    "export one function returning each of them");
  return std::visit(
      [&](const auto& method_model) -> ShaderExport {
        using Method = std::decay_t<decltype(method_model)>;
        return gl::assemble_export(gl::Twin<Method>::shader(method_model, options.variant),
                                   options.language, model.maps(), model.channels());
      },
      model.data().model);
}

}  // namespace stochtex
