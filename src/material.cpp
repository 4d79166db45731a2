// Materials (stochtex/material.hpp, docs/materials.md): the maps checked, normal maps turned into
// slopes, the channels interleaved into one exemplar, analysed by the registry with the layout.

#include "stochtex/material.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "model/map_layout.hpp"
#include "model/model_data.hpp"
#include "registry.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

// A decoded normal (2v - 1) this much shorter or longer than 1 is not a normal: the shipped maps'
// decoded lengths lie within 0.733..1.149, 99.9 % of their pixels within 0.2 of 1
// (data/materials/ATTRIBUTION.md), while colour images given as normal maps have mean lengths of
// 0.24 to 0.85 or spreads beyond 0.18.
constexpr double kMinMeanLength = 0.85;
constexpr double kMaxMeanLength = 1.15;
constexpr double kLengthTolerance = 0.2;
constexpr double kMinShareNearUnit = 0.95;
// Tangent-space normals face out of the surface: at most 1 % of pixels may face away.
constexpr double kMinShareFacingOut = 0.99;
// The average normal of a tangent-space map is close to the surface's (0, 0, 1): the shipped
// maps' average tilts by 0.009; a colour image that passes the rules above (a caustics photo) by
// 0.91.
constexpr double kMaxMeanTilt = 0.25;
// Pixels whose normal faces away or lies nearly flat get this much z, so that their slopes stay
// finite: |s| <= sqrt(1 - z^2) / z = 9.95.
constexpr double kMinNormalZ = 0.1;

struct Names {
  std::array<std::string_view, 5> normal{"normal", "normals", "normal_map", "nrm", "norm"};
  std::array<std::string_view, 4> height{"height", "displacement", "disp", "bump"};
  std::array<std::string_view, 13> scalar{"roughness",        "glossiness", "gloss",     "metallic",
                                          "metalness",        "ao",         "occlusion", "cavity",
                                          "specular",         "opacity",    "alpha",     "mask",
                                          "ambient_occlusion"};
};

template <std::size_t N>
bool listed(const std::array<std::string_view, N>& list, std::string_view name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::string described(const MaterialMap& map) {
  return "'" + map.source + "' (" + map.name + ")";
}

// Whether the channels of a 3-channel map are one grey channel saved as RGB.
bool grey_in_rgb(ImageView<const float> image) {
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.at(x, y, 1) != image.at(x, y, 0) || image.at(x, y, 2) != image.at(x, y, 0))
        return false;
  return true;
}

// The channels `map` gives the material: its own, or one of a grey image saved as RGB.
int channels_taken(const MaterialMap& map, MapKind kind) {
  const int channels = map.image.channels;
  if (channels == 2 || channels == 4)
    throw Error(ErrorCode::invalid_input,
                described(map) + " has an alpha channel; give the alpha as a map of its own, " +
                    "e.g. --map opacity=FILE, and this map without it");
  switch (kind) {
    case MapKind::normal:
      if (channels != 3)
        throw Error(ErrorCode::invalid_input,
                    described(map) + " has 1 channel; a normal map has 3 (red x, green y, blue z)");
      return 2;
    case MapKind::height:
    case MapKind::scalar:
      if (channels == 3 && !grey_in_rgb(map.image))
        throw Error(ErrorCode::invalid_input,
                    described(map) + " has different red, green and blue values; a " +
                        std::string(map_kind_name(kind)) +
                        " map has one channel: save it as grey, or give it as a colour map (" +
                        map.name + ":colour=FILE)");
      return 1;
    case MapKind::colour:
      break;
  }
  return channels;
}

// Refuses a map that is not a tangent-space normal map, decoded n = 2v - 1 (v in 0..1).
void check_normal_map(const MaterialMap& map) {
  const auto pixels = static_cast<double>(map.image.width) * map.image.height;
  double length_sum = 0.0;
  double near_unit = 0.0;
  double facing_out = 0.0;
  double mean_x = 0.0;
  double mean_y = 0.0;
  for (int y = 0; y < map.image.height; ++y)
    for (int x = 0; x < map.image.width; ++x) {
      const double nx = 2.0 * map.image.at(x, y, 0) - 1.0;
      const double ny = 2.0 * map.image.at(x, y, 1) - 1.0;
      const double nz = 2.0 * map.image.at(x, y, 2) - 1.0;
      const double length = std::sqrt(nx * nx + ny * ny + nz * nz);
      length_sum += length;
      near_unit += std::abs(length - 1.0) <= kLengthTolerance ? 1.0 : 0.0;
      facing_out += nz > 0.0 ? 1.0 : 0.0;
      if (length > 0.0) {
        mean_x += nx / length;
        mean_y += ny / length;
      }
    }
  const double mean_length = length_sum / pixels;
  const std::string not_one = described(map) + " is not a tangent-space normal map: ";
  const auto percent = [](double share) { return std::to_string(std::lround(100.0 * share)); };
  if (mean_length < kMinMeanLength || mean_length > kMaxMeanLength ||
      near_unit / pixels < kMinShareNearUnit) {
    char mean[16];
    std::snprintf(mean, sizeof(mean), "%.2f", mean_length);
    throw Error(ErrorCode::invalid_input,
                not_one + "its decoded vectors (2v - 1) have a mean length of " + mean + " and " +
                    percent(near_unit / pixels) +
                    " % lie within 0.2 of length 1 (a normal map's are near 1); give it as a "
                    "colour map (" +
                    map.name + ":colour=FILE) if it is not a normal map");
  }
  if (facing_out / pixels < kMinShareFacingOut)
    throw Error(ErrorCode::invalid_input,
                not_one + percent(1.0 - facing_out / pixels) +
                    " % of its normals face away from the surface (blue below 0.5)");
  const double tilt = std::hypot(mean_x, mean_y) / pixels;
  if (tilt > kMaxMeanTilt)
    throw Error(
        ErrorCode::invalid_input,
        not_one + "its average normal leans " +
            std::to_string(std::lround(std::asin(std::min(tilt, 1.0)) * 180.0 / std::numbers::pi)) +
            " degrees from the surface's, where a tangent-space map's stands nearly "
            "upright");
}

// The slopes (-n_x / n_z, -n_y / n_z) of the renormalised decoded normal, y up.
std::array<float, 2> slopes(const MaterialMap& map, int x, int y, bool y_down) {
  double nx = 2.0 * map.image.at(x, y, 0) - 1.0;
  double ny = 2.0 * map.image.at(x, y, 1) - 1.0;
  double nz = 2.0 * map.image.at(x, y, 2) - 1.0;
  if (y_down) ny = -ny;
  const double length = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (length == 0.0) return {0.0f, 0.0f};
  nx /= length;
  ny /= length;
  nz /= length;
  if (nz < kMinNormalZ) {
    // Keep the direction in the plane, lift z to the minimum.
    const double planar = std::hypot(nx, ny);
    const double keep = planar > 0.0 ? std::sqrt(1.0 - kMinNormalZ * kMinNormalZ) / planar : 0.0;
    nx *= keep;
    ny *= keep;
    nz = kMinNormalZ;
  }
  return {static_cast<float>(-nx / nz), static_cast<float>(-ny / nz)};
}

// The maps' layout, every map checked (material_exemplar's rules).
std::vector<MapInfo> material_layout(std::span<const MaterialMap> maps) {
  if (maps.empty()) throw Error(ErrorCode::invalid_input, "a material needs at least one map");
  std::vector<MapInfo> layout;
  const MaterialMap& first = maps.front();
  for (const MaterialMap& map : maps) {
    validate_exemplar(map.image, map.source);
    if (map.image.width != first.image.width || map.image.height != first.image.height)
      throw Error(ErrorCode::invalid_input,
                  described(map) + " is " + std::to_string(map.image.width) + "x" +
                      std::to_string(map.image.height) + " but " + described(first) + " is " +
                      std::to_string(first.image.width) + "x" + std::to_string(first.image.height) +
                      "; the maps of a material must be the same size, aligned pixel for pixel");
    const MapKind kind = map.kind.value_or(default_map_kind(map.name));
    if (kind != MapKind::colour && map.colour_space != ColourSpace::data)
      throw Error(ErrorCode::invalid_input, described(map) + " is a " +
                                                std::string(map_kind_name(kind)) +
                                                " map, which is data, not " +
                                                std::string(colour_space_name(map.colour_space)) +
                                                " colour; give it as data or as a colour map");
    layout.push_back({map.name, kind, channels_taken(map, kind), {}, 0.0, map.colour_space});
    if (kind == MapKind::normal) check_normal_map(map);
  }
  if (const auto problem = map_layout_problem(layout))
    throw Error(ErrorCode::invalid_input, "the material " + *problem);
  return layout;
}

// The maps' channels side by side, a normal map as its slopes.
ImageF interleave(std::span<const MaterialMap> maps, std::span<const MapInfo> layout,
                  const MaterialOptions& options) {
  const int width = maps.front().image.width;
  const int height = maps.front().image.height;
  ImageF exemplar(width, height, map_channels(layout));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int c = 0;
      for (std::size_t m = 0; m < maps.size(); ++m) {
        if (layout[m].kind == MapKind::normal && layout[m].channels == 2) {
          const auto s = slopes(maps[m], x, y, options.normal_y_down);
          exemplar.at(x, y, c++) = s[0];
          exemplar.at(x, y, c++) = s[1];
        } else {
          for (int k = 0; k < layout[m].channels; ++k)
            exemplar.at(x, y, c++) = maps[m].image.at(x, y, k);
        }
      }
    }
  return exemplar;
}

// The height map's gradient at (x, y) by central differences, wrapping at the borders, y up
// (towards row 0): render_maps's derivative at scale 1.
std::array<double, 2> height_gradient(ImageView<const float> height, int x, int y) {
  const auto at = [&](int i, int j) {
    return static_cast<double>(
        height.at((i + height.width) % height.width, (j + height.height) % height.height, 0));
  };
  return {0.5 * (at(x + 1, y) - at(x - 1, y)), -0.5 * (at(x, y + 1) - at(x, y - 1))};
}

// Derives the material's normal map from its height map (MaterialOptions::derive_normals) when
// the method derives normals and the normal map's slopes follow the height's gradient (the least
// squares fit s = k grad h over both axes correlates by kMinDerivedFit or more): the normal map
// gets no channels and the fit's k. Returns the exemplar's mean squared slope |s|^2, or 0 when
// the normal map stays synthesised.
double derive_normals(std::span<const MaterialMap> maps, std::vector<MapInfo>& layout,
                      std::string_view method, const MaterialOptions& options) {
  const auto normal = std::find_if(layout.begin(), layout.end(),
                                   [](const MapInfo& map) { return map.kind == MapKind::normal; });
  const auto height = std::find_if(layout.begin(), layout.end(),
                                   [](const MapInfo& map) { return map.kind == MapKind::height; });
  if (!options.derive_normals || !method_info(method).derives_normals || normal == layout.end() ||
      height == layout.end())
    return 0.0;
  const MaterialMap& normal_map = maps[static_cast<std::size_t>(normal - layout.begin())];
  const ImageView<const float> height_map =
      maps[static_cast<std::size_t>(height - layout.begin())].image;
  double slope_gradient = 0.0, gradient_squared = 0.0, slope_squared = 0.0;
  for (int y = 0; y < height_map.height; ++y)
    for (int x = 0; x < height_map.width; ++x) {
      const auto s = slopes(normal_map, x, y, options.normal_y_down);
      const auto g = height_gradient(height_map, x, y);
      slope_gradient += s[0] * g[0] + s[1] * g[1];
      gradient_squared += g[0] * g[0] + g[1] * g[1];
      slope_squared += static_cast<double>(s[0]) * s[0] + static_cast<double>(s[1]) * s[1];
    }
  if (!(gradient_squared > 0.0 && slope_squared > 0.0)) return 0.0;
  const double fit = slope_gradient / std::sqrt(gradient_squared * slope_squared);
  if (fit < kMinDerivedFit) return 0.0;
  normal->channels = 0;
  normal->derived_from = height->name;
  normal->slope_scale = slope_gradient / gradient_squared;
  return slope_squared / (static_cast<double>(height_map.width) * height_map.height);
}

// The model with its derived normal map's slope scale set so that the slopes of its own height
// have the exemplar's mean squared slope: a Gaussian-model method's height has the exemplar's
// spectrum only approximately, and its gradient, weighted towards high frequencies, shows the
// difference (measured on rock_sandstone: the least squares scale gave lrp slopes of mean
// magnitude 1.47 and gabor 0.37, against the exemplar's 0.52). The model's height is measured on
// a kCalibrationSide² render of seed 0 by central differences, as render_maps takes them.
constexpr int kCalibrationSide = 256;
Model with_calibrated_slopes(const Model& model, double mean_square_slope) {
  ModelData data = model.data();
  const auto normal = std::find_if(data.maps.begin(), data.maps.end(),
                                   [](const MapInfo& map) { return !map.derived_from.empty(); });
  int height_channel = 0;
  for (const MapInfo& map : data.maps) {
    if (map.name == normal->derived_from) break;
    height_channel += map.channels;
  }
  ImageF rendered(kCalibrationSide, kCalibrationSide, model.channels());
  render(model, Grid{{0.0, 0.0}, 1.0, kCalibrationSide, kCalibrationSide}, 0, rendered.view());
  double gradient_squared = 0.0;
  for (int y = 1; y + 1 < kCalibrationSide; ++y)
    for (int x = 1; x + 1 < kCalibrationSide; ++x) {
      const double dx = 0.5 * (static_cast<double>(rendered.at(x + 1, y, height_channel)) -
                               rendered.at(x - 1, y, height_channel));
      const double dy = 0.5 * (static_cast<double>(rendered.at(x, y + 1, height_channel)) -
                               rendered.at(x, y - 1, height_channel));
      gradient_squared += dx * dx + dy * dy;
    }
  gradient_squared /= static_cast<double>(kCalibrationSide - 2) * (kCalibrationSide - 2);
  if (!(gradient_squared > 0.0)) return model;
  normal->slope_scale =
      std::copysign(std::sqrt(mean_square_slope / gradient_squared), normal->slope_scale);
  return Model(std::make_shared<const ModelData>(std::move(data)));
}

}  // namespace

MapKind default_map_kind(std::string_view name) {
  const Names names;
  if (listed(names.normal, name)) return MapKind::normal;
  if (listed(names.height, name)) return MapKind::height;
  if (listed(names.scalar, name)) return MapKind::scalar;
  return MapKind::colour;
}

MaterialExemplar material_exemplar(std::span<const MaterialMap> maps,
                                   const MaterialOptions& options) {
  std::vector<MapInfo> layout = material_layout(maps);
  ImageF exemplar = interleave(maps, layout, options);
  return {std::move(layout), std::move(exemplar)};
}

Model analyze_material(std::string_view method, std::span<const MaterialMap> maps,
                       const ParamValues& params, std::uint32_t seed,
                       const MaterialOptions& options,
                       const std::function<void(double)>& progress) {
  resolve_params(method, params);
  std::vector<MapInfo> layout = material_layout(maps);
  const double mean_square_slope = derive_normals(maps, layout, method, options);
  std::string names;
  for (const MapInfo& map : layout)
    names += (names.empty() ? "" : ", ") + map.name + " " + std::to_string(map.channels);
  const int max_channels = method_info(method).max_channels;
  if (map_channels(layout) > max_channels)
    throw Error(ErrorCode::invalid_input,
                "method " + std::string(method) + " analyses 1 to " + std::to_string(max_channels) +
                    " channels, but this material has " + std::to_string(map_channels(layout)) +
                    " (" + names + "); choose another method or fewer maps");
  const std::string source = "the material of " + maps.front().source + " and " +
                             std::to_string(maps.size() - 1) + " more maps";
  const ImageView<const float> first = maps.front().image;
  check_analysis_request(method, first.width, first.height, map_channels(layout), source);
  const ImageF exemplar = interleave(maps, layout, options);
  const Model model =
      analyze_exemplar(method, exemplar.view(), params, seed, source, progress, std::move(layout));
  return mean_square_slope > 0.0 ? with_calibrated_slopes(model, mean_square_slope) : model;
}

}  // namespace stochtex
