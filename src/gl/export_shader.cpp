// `stochtex export-shader`: each method's GLSL library (the renderer's own code, with its data
// read from textures instead of storage buffers; Twin::shader in src/methods/<m>/gl_data.cpp) in
// the asked-for variant and language (languages.hpp, cross_compile.hpp), the data as images
// (exact: RGBA float; fast: the formats ShaderTexture names), wrappers and a README, written here
// the same for every method; the README's text is the templates of readme/ (readme.hpp), filled
// with the export's values.

#include <algorithm>
#include <array>
#include <cctype>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gl/colour.hpp"
#include "gl/cross_compile.hpp"
#include "gl/export_godot.hpp"
#include "gl/export_material.hpp"
#include "gl/readme.hpp"
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

// The README's account of the entry point's arguments and result (a material's: its struct in
// `language`'s types).
std::string arguments(const Entry& entry, ShaderLanguage language) {
  return ReadmeTemplate("arguments")
      .flag("material", entry.material != nullptr)
      .set("maps", entry.material ? material_readme(*entry.material, language) : "")
      .text();
}

// The GLSL entry point's signature.
std::string glsl_signature(const Entry& entry) {
  return ReadmeTemplate("glsl_signature")
      .flag("material", entry.material != nullptr)
      .set("function", entry.function())
      .text();
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

// A GLSL 4.50 fragment shader calling the entry point.
std::string glsl_usage(const Entry& entry, const std::string& file) {
  return ReadmeTemplate("glsl_usage")
      .set("file", file)
      .set("colour", example_colour(entry, entry.function() + "(p, dFdx(p), dFdy(p), 7u)", "vec3"))
      .text();
}

// `make(texture, unit)` for each of `textures` (unit: its index), joined by `separator`.
template <typename Make>
std::string join_textures(const std::vector<ShaderTexture>& textures, Make make,
                          std::string_view separator = "\n") {
  std::vector<std::string> parts;
  for (std::size_t unit = 0; unit < textures.size(); ++unit)
    parts.push_back(make(textures[unit], unit));
  return join(parts, separator);
}

constexpr std::array<const char*, 4> kChannelNames = {"grey", "grey + alpha", "RGB", "RGBA"};

std::string file_format(const ShaderTexture& t) {
  const char* channels = kChannelNames[static_cast<std::size_t>(t.image.channels() - 1)];
  constexpr std::array<const char*, 3> kEncodings = {"OpenEXR float32", "PNG 8-bit", "PNG 16-bit"};
  return std::string(kEncodings[static_cast<std::size_t>(t.encoding)]) + " " + channels;
}

// The texture format of `t` in `language`'s API (GL_RGB16, DXGI_FORMAT_..., MTLPixelFormat...).
std::string texture_format(ShaderLanguage language, const ShaderTexture& t) {
  return std::string(language_row(language).formats[static_cast<std::size_t>(
      t.encoding)][static_cast<std::size_t>(t.image.channels() - 1)]);
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

// The fast variant's introduction, its data files with their texture settings in `language`'s
// terms and the colour spaces: the part of the README every language shares.
std::string fast_data(ShaderLanguage language, const std::vector<ShaderTexture>& textures) {
  const LanguageRow& row = language_row(language);
  const std::string rows = join_textures(textures, [&](const ShaderTexture& t, std::size_t) {
    return ReadmeTemplate("fast_data_row")
        .set("file", t.file_name())
        .set("texture_type", std::string(row.texture_types[t.depth == 1 ? 0 : 1]))
        .set("name", t.name)
        .set("file_format", file_format(t))
        .set("texture_format", texture_format(language, t))
        .flag("volume", t.depth != 1)
        .set("width", std::to_string(t.image.width()))
        .set("height", std::to_string(t.image.height() / t.depth))
        .set("depth", std::to_string(t.depth))
        .set("filter", filter_text(t))
        .set("wrap", wrap_text(t.wrap))
        .flag("mipmaps", t.mip_levels != 1)
        .set("last_level", std::to_string(t.mip_levels - 1))
        .text();
  });
  return ReadmeTemplate("fast_data")
      .flag("cross_compiled", language != ShaderLanguage::glsl)
      .set("rows", rows)
      .text();
}

// README.md of a fast GLSL export: files with their texture settings, entry point, colour spaces,
// binding in plain OpenGL 4.5, and method notes.
std::string glsl_fast_readme(const Entry& entry, const std::string& title, const std::string& file,
                             const std::vector<ShaderTexture>& textures, const std::string& notes) {
  const std::string bindings =
      join_textures(textures, [](const ShaderTexture& t, std::size_t unit) {
        constexpr std::array<const char*, 3> kValues = {"floats", "bytes", "16-bit samples"};
        constexpr std::array<const char*, 4> kLayouts = {"GL_RED", "GL_RG", "GL_RGB", "GL_RGBA"};
        constexpr std::array<const char*, 3> kTypes = {"GL_FLOAT", "GL_UNSIGNED_BYTE",
                                                       "GL_UNSIGNED_SHORT"};
        constexpr std::array<const char*, 3> kMinFilters = {"GL_NEAREST", "GL_LINEAR",
                                                            "GL_LINEAR_MIPMAP_LINEAR"};
        constexpr std::array<const char*, 3> kWraps = {"GL_CLAMP_TO_EDGE", "GL_CLAMP_TO_BORDER",
                                                       "GL_REPEAT"};
        const auto encoding = static_cast<std::size_t>(t.encoding);
        return ReadmeTemplate("glsl_fast_texture")
            .set("file", t.file_name())
            .set("unit", std::to_string(unit))
            .set("values", kValues[encoding])
            .flag("volume", t.depth > 1)
            .set("levels", std::to_string(t.mip_levels))
            .set("format", texture_format(ShaderLanguage::glsl, t))
            .set("width", std::to_string(t.image.width()))
            .set("height", std::to_string(t.image.height() / t.depth))
            .set("depth", std::to_string(t.depth))
            .set("layout", kLayouts[static_cast<std::size_t>(t.image.channels() - 1)])
            .set("type", kTypes[encoding])
            .flag("mipmaps", t.mip_levels > 1)
            .set("min_filter", kMinFilters[static_cast<std::size_t>(t.filter)])
            .set("mag_filter", t.filter == TextureFilter::nearest ? "GL_NEAREST" : "GL_LINEAR")
            .flag("anisotropic", t.filter == TextureFilter::mipmap)
            .set("wrap", kWraps[static_cast<std::size_t>(t.wrap)])
            .set("name", t.name)
            .text();
      });
  return ReadmeTemplate("glsl_fast")
      .set("title", title)
      .set("file", file)
      .set("signature", glsl_signature(entry))
      .set("arguments", arguments(entry, ShaderLanguage::glsl))
      .set("data", fast_data(ShaderLanguage::glsl, textures))
      .set("textures", bindings)
      .set("usage", glsl_usage(entry, file))
      .flag("notes", !notes.empty())
      .set("method_notes", notes)
      .text();
}

std::string shader_graph_file(const std::string& method) {
  return "stochtex_" + method + "_shadergraph.hlsl";
}

// The Shader Graph port type of a material's member.
std::string shader_graph_type(const MaterialMember& member) {
  return member.vector ? "Vector 3" : "Float";
}

// The GLSL 4.50 README of an exact export: files, entry point, binding in plain OpenGL 4.5, and
// method notes.
std::string glsl_exact_readme(const Entry& entry, const std::string& title, const std::string& file,
                              const std::vector<ShaderTexture>& textures,
                              const std::string& notes) {
  std::vector<std::string> data_files;
  std::vector<std::string> uniforms;
  for (const ShaderTexture& t : textures) {
    data_files.push_back("`" + t.name + ".exr`");
    uniforms.push_back("`uniform sampler2D stochtex_" + t.name + ";`");
  }
  return ReadmeTemplate("glsl_exact")
      .set("title", title)
      .set("file", file)
      .set("data_files", join(data_files, ", "))
      .set("uniforms", join(uniforms, " "))
      .set("signature", glsl_signature(entry))
      .set("arguments", arguments(entry, ShaderLanguage::glsl))
      .set("textures", join_textures(textures,
                                     [](const ShaderTexture& t, std::size_t unit) {
                                       return ReadmeTemplate("glsl_exact_texture")
                                           .set("name", t.name)
                                           .set("unit", std::to_string(unit))
                                           .text();
                                     }))
      .set("usage", glsl_usage(entry, file))
      .flag("notes", !notes.empty())
      .set("method_notes", notes)
      .text();
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

// The README's section on binding the data in a cross-compiled language, after the shared
// introduction (fast: after the data table): the template binding_<name>.md with the values it
// needs, `signature` being the cross-compiled entry point's.
std::string binding(ShaderLanguage language, bool fast, const Entry& entry, const std::string& file,
                    const std::string& signature, const std::vector<ShaderTexture>& textures) {
  const LanguageRow& row = language_row(language);
  const std::string function = entry.function();
  ReadmeTemplate text("binding_" + std::string(row.name));
  text.flag("fast", fast).set("file", file);
  switch (language) {
    case ShaderLanguage::essl:
      text.set("colour", example_colour(entry, function + "(p, dFdx(p), dFdy(p), 7u)", "vec3"))
          .set("textures", join_textures(textures, [](const ShaderTexture& t, std::size_t unit) {
                 return ReadmeTemplate("binding_essl_texture")
                     .set("file", t.file_name())
                     .set("unit", std::to_string(unit))
                     .set("name", t.name)
                     .text();
               }));
      break;
    case ShaderLanguage::hlsl: {
      std::vector<std::string> outputs;
      if (entry.material)
        for (const MaterialMember& member : entry.material->members)
          outputs.push_back("`" + member.name + "` (" + shader_graph_type(member) + ")");
      text.set("colour", example_colour(entry, function + "(p, ddx(p), ddy(p), 7u)", "float3"))
          .set("textures",
               join_textures(
                   textures,
                   [](const ShaderTexture& t, std::size_t) {
                     return ReadmeTemplate("binding_hlsl_texture").set("name", t.name).text();
                   }))
          .set("shader_graph_file", shader_graph_file(entry.method))
          .set("function", function)
          .flag("material", entry.material != nullptr)
          .set("outputs", join(outputs, ", "));
      break;
    }
    case ShaderLanguage::msl: {
      std::string call_arguments;
      std::string locals;
      extra_parameters(signature, call_arguments, locals);
      text.set("colour",
               example_colour(entry, function + "(p, dfdx(p), dfdy(p), 7u" + call_arguments + ")",
                              "float3"))
          .set("textures", join_textures(
                               textures,
                               [&row](const ShaderTexture& t, std::size_t unit) {
                                 return ReadmeTemplate("binding_msl_texture")
                                     .set("texture_type",
                                          std::string(row.texture_types[t.depth == 1 ? 0 : 1]))
                                     .set("name", t.name)
                                     .set("unit", std::to_string(unit))
                                     .text();
                               },
                               ""))
          .flag("private_variables", !locals.empty())
          .set("variables", locals);
      break;
    }
    case ShaderLanguage::glsl:
    case ShaderLanguage::godot:
      throw std::logic_error("binding: GLSL and Godot have READMEs of their own");
  }
  return text.text();
}

// The README of a cross-compiled export: the GLSL one's content, in the language's terms.
std::string cross_readme(ShaderLanguage language, ShaderVariant variant, const Entry& entry,
                         const std::string& title, const std::string& file,
                         const std::string& signature, const std::vector<ShaderTexture>& textures,
                         const std::string& notes) {
  const LanguageRow& row = language_row(language);
  const bool fast = variant == ShaderVariant::fast;
  return ReadmeTemplate("cross")
      .set("title", title)
      .flag("fast", fast)
      .set("language", std::string(row.title))
      .set("file", file)
      .flag("shader_graph", language == ShaderLanguage::hlsl)
      .set("shader_graph_file", shader_graph_file(entry.method))
      .set("data_files", join_textures(textures,
                                       [fast](const ShaderTexture& t, std::size_t) {
                                         return ReadmeTemplate("cross_data_file")
                                             .set("file", t.file_name())
                                             .flag("fast", fast)
                                             .text();
                                       }))
      .set("signature", signature)
      .set("arguments", arguments(entry, language))
      .set("data", fast ? fast_data(language, textures) : "")
      .set("binding", binding(language, fast, entry, file, signature, textures))
      .set("texel_read", std::string(row.texel_read))
      .flag("notes", !notes.empty())
      .set("method_notes", notes)
      .text();
}

// The comment opening the shader file.
std::string export_header(ShaderLanguage language, const std::string& what, const Entry& entry,
                          const std::vector<ShaderTexture>& textures, ShaderVariant variant) {
  std::ostringstream text;
  if (language == ShaderLanguage::glsl)
    text << "// " << what << " exported by `stochtex export-shader`.\n"
         << "// Paste or include after `#version 450`.\n// Bind";
  else if (language == ShaderLanguage::godot)
    text << "// " << what << " exported by\n// `stochtex export-shader --language godot` ("
         << language_row(language).title
         << "), written from the GLSL 4.50\n// through SPIR-V (glslang, spirv-opt, SPIRV-Cross) "
            "with every function inlined.\n// "
         << language_row(language).placement << "\n// Set";
  else
    text << "// " << what << " exported by\n// `stochtex export-shader --language "
         << language_row(language).name << "` (" << language_row(language).title
         << "), cross-compiled from the GLSL 4.50\n// by glslang and SPIRV-Cross. "
         << language_row(language).placement << "\n// Bind";
  for (std::size_t i = 0; i < textures.size(); ++i) {
    text << (i == 0 ? " " : ",\n// ");
    if (language == ShaderLanguage::godot)
      text << "stochtex_" << textures[i].name << " to " << textures[i].file_name()
           << " (imported as its .import file says)";
    else
      text << textures[i].file_name() << " as "
           << (variant == ShaderVariant::exact ? std::string("an RGBA32F")
                                               : "a " + texture_format(language, textures[i]))
           << " texture to `stochtex_" << textures[i].name << "`";
  }
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
                 member.name + " (" + shader_graph_type(member) + ")";
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
  text << " on the material by script (the Unity package\n// unity/com.stochtex.textures binds "
          "them). See README.md.\n#ifndef "
       << guard << "\n#define " << guard
       << "\n\n// Unity gives a texture's filter and wrap to the sampler named sampler<texture>.\n";
  for (const ShaderTexture& t : textures)
    text << "#define _stochtex_" << t.name << "_sampler samplerstochtex_" << t.name << "\n";
  text << "\n"
       << hlsl << "\nvoid " << entry.function()
       << "_float(float2 p, float2 dpdx, float2 dpdy, uint seed" << parameters << ") {\n"
       << body << "}\n\n#endif  // " << guard << "\n";
  return {shader_graph_file(entry.method), text.str()};
}

// manifest.json: the files, the entry point's outputs (the Shader Graph function's ports: `colour`
// or a material's maps) with what each holds, and each texture as the README's table says.
std::string manifest(const Entry& entry, ShaderVariant variant, ShaderLanguage language,
                     const ShaderExport& files, bool linear_light) {
  nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
  if (entry.material)
    for (const MaterialMember& member : entry.material->members)
      outputs.push_back(
          {{"name", member.name},
           {"components", member.vector ? 3 : 1},
           {"kind", map_kind_name(member.map.kind)},
           {"colour", member.map.colour_space == ColourSpace::srgb ? "linear" : "data"}});
  else
    outputs.push_back(
        {{"name", "colour"}, {"components", 4}, {"colour", linear_light ? "linear" : "data"}});
  nlohmann::ordered_json textures = nlohmann::ordered_json::array();
  for (const ShaderTexture& t : files.textures) {
    textures.push_back(
        {{"uniform", "stochtex_" + t.name},
         {"file", t.file_name()},
         {"encoding", encoding_name(t.encoding)},
         {"channels", t.image.channels()},
         {"width", t.image.width()},
         {"height", t.image.height() / t.depth},
         {"depth", t.depth},
         {"filter", filter_name(t.filter)},
         {"wrap", wrap_name(t.wrap)},
         {"mip_levels", t.mip_levels},
         // Godot's import turns anisotropic filtering off (export_godot.cpp).
         {"anisotropy",
          t.filter == TextureFilter::mipmap && language != ShaderLanguage::godot ? 16 : 1}});
    if (t.float_bytes) textures.back()["float_bytes"] = true;
  }
  nlohmann::ordered_json json = {
      {"format", "stochtex-shader-export"},
      {"version", 1},
      {"method", entry.method},
      {"variant", variant == ShaderVariant::fast ? "fast" : "exact"},
      {"language", language_row(language).name},
      {"entry", entry.function()},
      {"shader", files.shader.name},
  };
  if (language == ShaderLanguage::hlsl) json["shader_graph"] = shader_graph_file(entry.method);
  if (language == ShaderLanguage::godot) {
    json["canvas_shader"] = godot_canvas_file(entry.method);
    json["scene"] = godot_scene_file(entry.method);
  }
  json["outputs"] = outputs;
  json["textures"] = textures;
  return json.dump(1) + "\n";
}

// The Godot README: its files, the steps in Godot 3, the data files' import settings, precision,
// what differs in Godot 4, and the method's notes. `border`: a texture was clamped to a border,
// which Godot 3 lacks; `linear`: the function returns linear light (a model in the srgb colour
// space), else the model's values.
std::string godot_readme(const Entry& entry, const ExportParts& parts, const GodotFiles& files,
                         bool border, bool linear) {
  const bool fast = parts.variant == ShaderVariant::fast;
  const std::string& method = entry.method;
  std::vector<std::string> data_files;
  std::vector<std::string> hints;
  bool float_bytes = false;
  bool half_floats = false;
  const std::string rows = join_textures(parts.textures, [&](const ShaderTexture& t, std::size_t) {
    const int width = t.float_bytes ? t.image.width() / 8 : t.image.width();
    const int height = t.image.height() / t.depth;
    data_files.push_back("- `" + t.file_name() + "` and `" + t.file_name() + ".import`: " +
                         (t.float_bytes ? "float32 data, as bytes" : "data, as floats") + ";");
    hints.push_back("`stochtex_" + t.name + " : " + godot4_hint(t) + "`");
    float_bytes = float_bytes || t.float_bytes;
    half_floats = half_floats || !t.float_bytes;
    const std::string size = std::to_string(width) + " x " + std::to_string(height) +
                             (t.depth > 1 ? " x " + std::to_string(t.depth) : "");
    return ReadmeTemplate("godot_data_row")
        .set("file", t.file_name())
        .set("texture_type", t.depth == 1 ? "sampler2D" : "sampler3D")
        .set("name", t.name)
        .set("contents", t.float_bytes ? size + " RGBA float32 texels as their bytes (" +
                                             std::to_string(8 * width) + " x " +
                                             std::to_string(height) + " grey + alpha, LA8)"
                                       : size + " " + (t.image.channels() == 4 ? "RGBA" : "RGB") +
                                             " float32, imported as half floats")
        .flag("volume", t.depth > 1)
        .set("depth", std::to_string(t.depth))
        .set("filter", t.filter == TextureFilter::nearest ? "off (read texel by texel)" : "on")
        .set("mipmaps", t.mip_levels > 1 ? "on (generated at import), anisotropic off" : "off")
        .set("repeat", t.wrap == TextureWrap::repeat ? "on" : "off (clamp to edge)")
        .text();
  });
  return ReadmeTemplate("godot")
      .set("title", parts.title)
      .flag("fast", fast)
      .set("file", files.spatial.name)
      .set("canvas_file", godot_canvas_file(method))
      .set("scene_file", godot_scene_file(method))
      .set("gdshader_file", godot4_file(method))
      .set("size", std::to_string(kGodotSceneSize))
      .set("function", entry.function())
      .set("signature", glsl_signature(entry))
      .set("data_files", join(data_files))
      .set("arguments", arguments(entry, ShaderLanguage::godot))
      .set("rows", rows)
      .flag("float_bytes", float_bytes)
      .flag("half_floats", half_floats)
      .flag("border", border)
      .flag("linear", linear)
      .set("hints", join(hints, ", "))
      .flag("notes", !parts.notes.empty())
      .set("method_notes", parts.notes)
      .text();
}

// The export of a method's parts: a model of one image exposes stochtex_<method>, a material (a
// model with `maps`) its material function after the library; `colour`: the model's (a model of
// one image in the srgb colour space returns linear light).
ShaderExport assemble_export(ExportParts parts, ShaderLanguage language,
                             std::span<const MapInfo> maps, int channels,
                             const ModelColour& colour) {
  const bool linear_light = colour.decodes();
  const std::string method(parts.method);
  if (language == ShaderLanguage::godot) {
    if (!maps.empty())
      throw std::invalid_argument(
          "a material exports a struct of its maps, which Godot 3's shading language does not "
          "have; analyse each map by itself to export it for Godot");
    const bool border =
        std::any_of(parts.textures.begin(), parts.textures.end(),
                    [](const ShaderTexture& t) { return t.wrap == TextureWrap::clamp_to_border; });
    std::vector<std::string> exported_names;
    for (const ShaderTexture& t : parts.textures) exported_names.push_back(t.file_name());
    godot_textures(parts.textures, method);
    // The notes name the files of the other languages: a float image is a PNG here.
    for (std::size_t k = 0; k < parts.textures.size(); ++k) {
      const std::string from = "`" + exported_names[k] + "`";
      const std::string to = "`" + parts.textures[k].file_name() + "`";
      for (std::size_t at = parts.notes.find(from); at != std::string::npos;
           at = parts.notes.find(from, at + to.size()))
        parts.notes.replace(at, from.size(), to);
    }
    const Entry entry{method, nullptr};
    const std::string function = entry.function();
    const std::string library = cross_compile(parts.library, function, method, language);
    GodotFiles files = godot_files(
        method, function, export_header(language, parts.what, entry, parts.textures, parts.variant),
        library, parts.textures, channels, colour);
    ShaderExport result;
    result.readme = godot_readme(entry, parts, files, border, linear_light);
    result.shader = std::move(files.spatial);
    result.wrappers = std::move(files.others);
    result.textures = std::move(parts.textures);
    result.manifest = manifest(entry, parts.variant, language, result, linear_light);
    return result;
  }
  std::optional<MaterialShader> material;
  if (!maps.empty()) {
    material =
        material_shader(maps, channels, method, parts.channels_function, parts.decoded_channels);
    parts.library += material->glsl;
  }
  const Entry entry{method, material ? &*material : nullptr};
  parts.notes +=
      std::string(parts.notes.empty() ? "" : "\n\n") +
      ReadmeTemplate("engines").flag("fast", parts.variant == ShaderVariant::fast).text();
  ShaderExport result;
  result.shader.name = "stochtex_" + method + std::string(language_row(language).extension);
  const std::string header =
      export_header(language, parts.what, entry, parts.textures, parts.variant);
  if (language == ShaderLanguage::glsl) {
    result.shader.text = header + parts.library;
    result.readme =
        parts.variant == ShaderVariant::exact
            ? glsl_exact_readme(entry, parts.title, result.shader.name, parts.textures, parts.notes)
            : glsl_fast_readme(entry, parts.title, result.shader.name, parts.textures, parts.notes);
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
  result.manifest = manifest(entry, parts.variant, language, result, linear_light);
  return result;
}

}  // namespace

}  // namespace gl

std::string ShaderTexture::file_name() const {
  return name + (encoding == TextureEncoding::exr_float32 ? ".exr" : ".png");
}

std::string_view encoding_name(TextureEncoding encoding) {
  constexpr std::array<std::string_view, 3> kNames = {"exr_float32", "png8", "png16"};
  return kNames[static_cast<std::size_t>(encoding)];
}

std::string_view filter_name(TextureFilter filter) {
  constexpr std::array<std::string_view, 3> kNames = {"nearest", "linear", "mipmap"};
  return kNames[static_cast<std::size_t>(filter)];
}

std::string_view wrap_name(TextureWrap wrap) {
  constexpr std::array<std::string_view, 3> kNames = {"clamp_to_edge", "clamp_to_border", "repeat"};
  return kNames[static_cast<std::size_t>(wrap)];
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
        gl::ExportParts parts = gl::Twin<Method>::shader(method_model, options.variant);
        gl::add_colour(parts, model.data().colour, model.channels(), model.maps());
        return gl::assemble_export(std::move(parts), options.language, model.maps(),
                                   model.channels(), model.data().colour);
      },
      model.data().model);
}

}  // namespace stochtex
