#pragma once
// The function of a material in an exported shader (`export-shader` of a model with maps,
// docs/shaders.md "Materials"): a struct of its maps,
//
//   struct StochtexMaterial { vec3 albedo; vec3 normal; float roughness; ... };
//   StochtexMaterial stochtex_<method>_material(vec2 p, vec2 dpdx, vec2 dpdy, uint seed);
//
// written after the method's GLSL library (Twin::shader) from the function that gives the model's
// channels: stochtex_<method>'s vec4 for 1 to 4 channels, ExportParts::channels_function beyond.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/gpu.hpp"
#include "stochtex/model.hpp"

namespace stochtex::gl {

// One member of StochtexMaterial: a map, in the model's order.
struct MaterialMember {
  std::string name;  // the map's, or map_<name> where GLSL or HLSL reserves the word
  MapInfo map;
  bool vector = false;  // vec3 (a colour map of 3 channels, a normal map) or float
};

struct MaterialShader {
  std::string function;  // stochtex_<method>_material
  std::vector<MaterialMember> members;
  std::string glsl;  // what follows the method's library
};

// The members of StochtexMaterial for `maps`, in their order. Throws Error(invalid_input) when two
// maps would give the struct the same member.
std::vector<MaterialMember> material_members(std::span<const MapInfo> maps);

// The material function of a model of `channels` channels with `maps` (not empty), whose library
// defines `channels_function` (ExportParts), or stochtex_<method> when that is empty; the channels
// `decoded` become linear light (stochtex_material_linear_light, gl/colour_material.glsl, which
// the library then holds). Throws as material_members does.
MaterialShader material_shader(std::span<const MapInfo> maps, int channels, std::string_view method,
                               const std::string& channels_function,
                               std::span<const int> decoded = {});

// The README's account of the struct in `language` (the templates readme/material*.md): its
// declaration in the language's types, what each member holds, and what a derived normal map
// costs; paragraphs without a final newline.
std::string material_readme(const MaterialShader& material, ShaderLanguage language);

// A member's type in an HLSL or Metal declaration: float3 or float.
std::string_view hlsl_type(const MaterialMember& member);

}  // namespace stochtex::gl
