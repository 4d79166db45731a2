#pragma once
// Materials: several aligned maps of one surface (albedo, normal, roughness, height, ...) analysed
// into one model whose channels are the maps' side by side (MapInfo, stochtex/model.hpp), so that
// every method keeps the maps' cross-correlations (docs/materials.md).
//
// Linking: material_exemplar and analyze_material are in stochtex::analysis; split_maps is in
// stochtex::runtime.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"

namespace stochtex {

// One map as read from its file: values as the file holds them (8-bit 0..255 as 0..1), a normal
// map encoded as 0.5 + 0.5 n.
struct MaterialMap {
  std::string name;              // e.g. "albedo"; 1 to 32 of a-z, 0-9 and _
  std::optional<MapKind> kind;   // none: default_map_kind(name)
  ImageView<const float> image;  // 1 to 4 channels, the same size for every map
  std::string source;            // the file, named in messages
  // What its values are (stochtex/colour.hpp): srgb or linear for a colour map (albedo, base
  // colour, emission) read with its colour; every other kind is data.
  ColourSpace colour_space = ColourSpace::data;
};

struct MaterialOptions {
  // Normal maps with green pointing down the image (DirectX's convention) instead of up.
  bool normal_y_down = false;
  // analyze_material with a method that derives normals (MethodInfo::derives_normals): a normal
  // map that follows the height map's gradient (correlation at least kMinDerivedFit) is derived
  // from the synthesised height, its slopes slope_scale times the height's gradient, the scale
  // fitted by least squares on the exemplar; false synthesises it as two channels of its own.
  bool derive_normals = true;
};
inline constexpr double kMinDerivedFit = 0.5;

// The kind a map named `name` gets when none is given: normal for normal, normals, normal_map,
// nrm; height for height, displacement, disp, bump; scalar for roughness, glossiness, metallic,
// metalness, ao, occlusion, ambient_occlusion, cavity, specular, opacity, alpha, mask; colour
// otherwise.
MapKind default_map_kind(std::string_view name);

// The maps checked and interleaved into one exemplar: each map's channels in the order given, a
// normal map as its 2 slopes (-n_x / n_z, -n_y / n_z) of the renormalised decoded normal n =
// 2v - 1. Throws Error(invalid_input) with one sentence naming the file when a map is unusable:
// any exemplar rule (validate_exemplar; a constant map is refused: leave it out), maps of
// different sizes, a channel count its kind cannot take, a normal map that is not one (decoded
// lengths far from 1, facing away, tilted on average), a repeated or malformed name.
struct MaterialExemplar {
  std::vector<MapInfo> maps;
  ImageF exemplar;
};
MaterialExemplar material_exemplar(std::span<const MaterialMap> maps,
                                   const MaterialOptions& options = {});

// analyze() of the material's exemplar: a model that knows its maps. Refuses, before any work, a
// material of more channels than the method analyses (MethodInfo::max_channels).
Model analyze_material(std::string_view method, std::span<const MaterialMap> maps,
                       const ParamValues& params = {}, std::uint32_t seed = 0,
                       const MaterialOptions& options = {},
                       const std::function<void(double)>& progress = {});

// A render of a material model cut into its maps, in the model's order: colour, height and scalar
// maps as rendered, a normal map as the unit normal normalize(-s_x, -s_y, 1) of its rendered
// slopes, encoded 0.5 + 0.5 n (y up) in 3 channels. `rendered` has model.channels() channels; a
// model without maps gives one image named "image". A derived normal map needs the height around
// each pixel: render_maps.
std::vector<NamedImage> split_maps(const Model& model, ImageView<const float> rendered);

// The maps of `grid`: `render_grid` renders the model's channels of a grid (stochtex::render, or
// the GL backend), here the grid with a one-pixel margin when a normal map is derived, whose
// slopes are then slope_scale times the height's central differences over the grid's spacing
// (scale), y up; then split_maps.
using GridRenderFunction = std::function<void(const Grid&, ImageView<float>)>;
std::vector<NamedImage> render_maps(const Model& model, const Grid& grid,
                                    const GridRenderFunction& render_grid);

}  // namespace stochtex
