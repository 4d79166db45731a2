// The function of a material in an exported shader (export_material.hpp).

#include "gl/export_material.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "gl/cross_compile.hpp"
#include "gl/glsl_text.hpp"
#include "gl/readme.hpp"
#include "gl/shaders.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {
namespace {

// Whether `name` cannot be a member: a parameter or variable of the Shader Graph function, whose
// outputs the members name, or a word GLSL 4.50, GLSL ES 3.00 or HLSL refuse as a struct's member
// (a keyword or reserved word: `sample`, `line`, ...), as their front ends say.
bool reserved_word(const std::string& name) {
  for (const char* taken : {"p", "dpdx", "dpdy", "seed", "material"})
    if (name == taken) return true;
  const std::string declaration = "struct S { float " + name + "; };\n";
  return !front_end_errors("#version 450\n" + declaration + "void main() {}\n",
                           ShaderLanguage::glsl)
              .empty() ||
         !front_end_errors(
              "#version 300 es\nprecision highp float;\n" + declaration + "void main() {}\n",
              ShaderLanguage::essl)
              .empty() ||
         !front_end_errors(declaration + "float4 main() : SV_Target { return 0.0; }\n",
                           ShaderLanguage::hlsl)
              .empty();
}

// channels[first], ... as a GLSL float or vec3.
std::string channel_values(int first, bool vector) {
  const auto channel = [](int c) { return "channels[" + std::to_string(c) + "]"; };
  if (!vector) return channel(first);
  return "vec3(" + channel(first) + ", " + channel(first + 1) + ", " + channel(first + 2) + ")";
}

int first_channel(std::span<const MapInfo> maps, const std::string& name) {
  int first = 0;
  for (const MapInfo& map : maps) {
    if (map.name == name) break;
    first += map.channels;
  }
  return first;
}

}  // namespace

std::string_view hlsl_type(const MaterialMember& member) {
  return member.vector ? "float3" : "float";
}

std::vector<MaterialMember> material_members(std::span<const MapInfo> maps) {
  std::vector<MaterialMember> members;
  for (const MapInfo& map : maps) {
    MaterialMember member{map.name, map, map.kind == MapKind::normal || map.channels == 3};
    if (reserved_word(member.name)) member.name = "map_" + member.name;
    const auto other =
        std::find_if(members.begin(), members.end(),
                     [&](const MaterialMember& before) { return before.name == member.name; });
    if (other != members.end())
      throw Error(ErrorCode::invalid_input,
                  "export-shader: the maps '" + other->map.name + "' and '" + map.name +
                      "' would both be the member " + member.name +
                      " of the material's struct (map_ prefixes the names GLSL or HLSL reserve "
                      "and the shader's own); rename one of them and analyse again");
    members.push_back(std::move(member));
  }
  return members;
}

MaterialShader material_shader(std::span<const MapInfo> maps, int channels, std::string_view method,
                               const std::string& channels_function, std::span<const int> decoded) {
  if (channels > 4 && channels_function.empty())
    throw std::logic_error("material_shader: the " + std::string(method) +
                           " library gives no function of more than 4 channels");
  MaterialShader material;
  material.function = "stochtex_" + std::string(method) + "_material";
  material.members = material_members(maps);

  std::ostringstream text;
  const std::string count = std::to_string(channels);
  text << "\n// The material (`export-shader` of a model with maps, docs/shaders.md).\n"
       << "const int STOCHTEX_MATERIAL_CHANNELS = " << count << ";\n"
       << "// The model's channels at p, the maps' side by side in their order (a normal map of "
          "its own as its\n// 2 slopes; a derived one has none).\n"
       << "float[STOCHTEX_MATERIAL_CHANNELS] stochtex_material_channels(vec2 p, vec2 dpdx, vec2 "
          "dpdy,\n                                                              uint seed) {\n";
  // The method's values: returned as they are, or into `channels` to decode some.
  const std::string result =
      decoded.empty() ? "  return " : "  float channels[STOCHTEX_MATERIAL_CHANNELS] = ";
  if (channels_function.empty()) {
    text << "  vec4 value = stochtex_" << method << "(p, dpdx, dpdy, seed);\n"
         << result << "float[STOCHTEX_MATERIAL_CHANNELS](";
    for (int c = 0; c < channels; ++c) text << (c == 0 ? "" : ", ") << "value[" << c << "]";
    text << ");\n";
  } else {
    text << result << channels_function << "(p, dpdx, dpdy, seed);\n";
  }
  if (!decoded.empty()) {
    text << "  // The sRGB maps' channels as linear light, the CPU render's "
            "(colour_material.glsl).\n"
         << "  float width = sqrt(abs(dpdx.x * dpdy.y - dpdx.y * dpdy.x));\n";
    for (const int c : decoded)
      text << "  channels[" << c << "] = stochtex_material_linear_light(channels[" << c
           << "], width, " << c << ");\n";
    text << "  return channels;\n";
  }
  text << "}\n";
  const bool normals = std::any_of(maps.begin(), maps.end(),
                                   [](const MapInfo& map) { return map.kind == MapKind::normal; });
  if (normals) text << "\n" << shader_source("gl/material.glsl");
  text << "\nstruct StochtexMaterial {\n";
  for (const MaterialMember& member : material.members)
    text << "  " << (member.vector ? "vec3 " : "float ") << member.name << ";\n";
  text << "};\n\n// Every map of the material at p, with the arguments of stochtex_" << method
       << ".\nStochtexMaterial " << material.function
       << "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {\n"
       << "  float channels[STOCHTEX_MATERIAL_CHANNELS] = stochtex_material_channels(p, dpdx, "
          "dpdy, seed);\n  StochtexMaterial material;\n";
  int first = 0;
  for (const MaterialMember& member : material.members) {
    const MapInfo& map = member.map;
    text << "  material." << member.name << " = ";
    if (!map.derived_from.empty())
      text << "stochtex_normal(stochtex_derived_slopes(p, dpdx, dpdy, seed, "
           << first_channel(maps, map.derived_from) << ", "
           << glsl_float(static_cast<float>(map.slope_scale)) << "));\n";
    else if (map.kind == MapKind::normal)
      text << "stochtex_normal(vec2(channels[" << first << "], channels[" << first + 1 << "]));\n";
    else
      text << channel_values(first, member.vector) << ";\n";
    first += map.channels;
  }
  text << "  return material;\n}\n";
  material.glsl = text.str();
  return material;
}

std::string material_readme(const MaterialShader& material, ShaderLanguage language) {
  const bool glsl = language == ShaderLanguage::glsl || language == ShaderLanguage::essl;
  std::vector<std::string> members;
  std::vector<std::string> derived;
  for (const MaterialMember& member : material.members) {
    const MapInfo& map = member.map;
    const std::string declaration =
        std::string(glsl ? (member.vector ? "vec3" : "float") : hlsl_type(member)) + " " +
        member.name + ";";
    constexpr std::size_t kCommentColumn = 24;
    members.push_back(
        ReadmeTemplate("material_member")
            .set("declaration", declaration)
            .set("padding",
                 std::string(std::max(kCommentColumn, declaration.size() + 1) - declaration.size(),
                             ' '))
            .set("kind", std::string(map_kind_name(map.kind)))
            .set("map", map.name)
            .flag("derived", !map.derived_from.empty())
            .set("source", map.derived_from)
            .text());
    if (!map.derived_from.empty())
      derived.push_back(ReadmeTemplate("material_derived")
                            .set("member", member.name)
                            .set("scale", glsl_float(static_cast<float>(map.slope_scale)))
                            .set("source", map.derived_from)
                            .text());
  }
  return ReadmeTemplate("material")
      .set("members", join(members))
      .flag("derived", !derived.empty())
      .set("derived_maps", join(derived))
      .text();
}

}  // namespace stochtex::gl
