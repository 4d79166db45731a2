#include "model/map_layout.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "stochtex/material.hpp"

namespace stochtex {
namespace {

// The one list of map kinds with the names files and users write.
constexpr std::array<std::pair<MapKind, std::string_view>, 4> kKindNames{{
    {MapKind::colour, "colour"},
    {MapKind::normal, "normal"},
    {MapKind::height, "height"},
    {MapKind::scalar, "scalar"},
}};

constexpr std::size_t kMaxMapNameLength = 32;
constexpr double kMaxSlopeScale = 1e6;

bool valid_name(const std::string& name) {
  return !name.empty() && name.size() <= kMaxMapNameLength &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
         });
}

bool valid_channels(MapKind kind, int channels) {
  switch (kind) {
    case MapKind::colour:
      return channels == 1 || channels == 3;
    case MapKind::normal:
      return channels == 2;
    case MapKind::height:
    case MapKind::scalar:
      return channels == 1;
  }
  return false;
}

}  // namespace

std::string_view map_kind_name(MapKind kind) {
  for (const auto& [k, name] : kKindNames)
    if (k == kind) return name;
  return "unknown";
}

std::optional<MapKind> map_kind_from_name(std::string_view name) {
  for (const auto& [kind, kind_name] : kKindNames)
    if (kind_name == name) return kind;
  return std::nullopt;
}

nlohmann::ordered_json maps_json(std::span<const MapInfo> maps) {
  auto list = nlohmann::ordered_json::array();
  for (const MapInfo& map : maps) {
    nlohmann::ordered_json entry{
        {"name", map.name}, {"kind", map_kind_name(map.kind)}, {"channels", map.channels}};
    if (!map.derived_from.empty()) {
      entry["from"] = map.derived_from;
      entry["scale"] = map.slope_scale;
    }
    if (map.colour_space != ColourSpace::data)
      entry["colour_space"] = colour_space_name(map.colour_space);
    list.push_back(entry);
  }
  return list;
}

int map_channels(std::span<const MapInfo> maps) {
  int channels = 0;
  for (const MapInfo& map : maps) channels += map.channels;
  return channels;
}

std::vector<int> first_channels(std::span<const MapInfo> maps) {
  std::vector<int> first;
  int channel = 0;
  for (const MapInfo& map : maps) {
    first.push_back(channel);
    channel += map.channels;
  }
  return first;
}

std::optional<std::string> map_layout_problem(std::span<const MapInfo> maps) {
  if (maps.empty()) return "has no maps";
  std::set<std::string, std::less<>> names;
  long long channels = 0;
  for (const MapInfo& map : maps) {
    if (!valid_name(map.name))
      return "has a map named '" + map.name.substr(0, kMaxMapNameLength) +
             "'; map names are 1 to 32 characters of a-z, 0-9 and _";
    if (!names.insert(map.name).second) return "names the map '" + map.name + "' twice";
    if (!map.derived_from.empty()) {
      const auto source = std::find_if(maps.begin(), maps.end(), [&](const MapInfo& other) {
        return other.name == map.derived_from && other.kind == MapKind::height;
      });
      if (map.kind != MapKind::normal || map.channels != 0 || source == maps.end() ||
          !std::isfinite(map.slope_scale) || map.slope_scale == 0.0 ||
          std::abs(map.slope_scale) > kMaxSlopeScale)
        return "derives the map '" + map.name + "' from '" + map.derived_from.substr(0, 32) +
               "', which needs a normal map of no channels of its own, a height map of that "
               "name and a finite, non-zero slope scale of at most 1e6";
      continue;
    }
    if (!valid_channels(map.kind, map.channels))
      return "gives the " + std::string(map_kind_name(map.kind)) + " map '" + map.name + "' " +
             std::to_string(map.channels) +
             " channels (colour maps have 1 or 3, normal maps 2 slopes, height and scalar maps 1)";
    channels += map.channels;
  }
  if (channels > kMaxChannels)
    return "has " + std::to_string(channels) + " channels in " + std::to_string(maps.size()) +
           " maps, more than the " + std::to_string(kMaxChannels) + " a material may have";
  return std::nullopt;
}

namespace {

// The maps of `rendered`, whose channels are those of `maps` side by side (each map's own).
std::vector<NamedImage> split(std::span<const MapInfo> maps, ImageView<const float> rendered) {
  std::vector<NamedImage> images;
  int first = 0;
  for (const MapInfo& map : maps) {
    const bool normal = map.kind == MapKind::normal;
    ImageF image(rendered.width, rendered.height, normal ? 3 : map.channels);
    for (int y = 0; y < rendered.height; ++y)
      for (int x = 0; x < rendered.width; ++x) {
        if (!normal) {
          for (int c = 0; c < map.channels; ++c) image.at(x, y, c) = rendered.at(x, y, first + c);
          continue;
        }
        // n = normalize(-s_x, -s_y, 1) of the slopes s = (-n_x / n_z, -n_y / n_z).
        const double sx = rendered.at(x, y, first);
        const double sy = rendered.at(x, y, first + 1);
        const double length = std::sqrt(sx * sx + sy * sy + 1.0);
        image.at(x, y, 0) = static_cast<float>(0.5 - 0.5 * sx / length);
        image.at(x, y, 1) = static_cast<float>(0.5 - 0.5 * sy / length);
        image.at(x, y, 2) = static_cast<float>(0.5 + 0.5 / length);
      }
    images.push_back({map.name, std::move(image)});
    first += map.channels;
  }
  return images;
}

bool has_derived_map(const Model& model) {
  return std::any_of(model.maps().begin(), model.maps().end(),
                     [](const MapInfo& map) { return !map.derived_from.empty(); });
}

}  // namespace

std::vector<NamedImage> split_maps(const Model& model, ImageView<const float> rendered) {
  if (has_derived_map(model))
    throw std::invalid_argument(
        "split_maps: this material derives its normal map from the height around each pixel; "
        "render it with render_maps");
  if (!model.maps().empty()) return split(model.maps(), rendered);
  ImageF image(rendered.width, rendered.height, rendered.channels);
  for (int y = 0; y < rendered.height; ++y)
    for (int x = 0; x < rendered.width; ++x)
      for (int c = 0; c < rendered.channels; ++c) image.at(x, y, c) = rendered.at(x, y, c);
  std::vector<NamedImage> images;
  images.push_back({"image", std::move(image)});
  return images;
}

std::vector<NamedImage> render_maps(const Model& model, const Grid& grid,
                                    const GridRenderFunction& render_grid) {
  if (!has_derived_map(model)) {
    ImageF image(grid.width, grid.height, model.channels());
    render_grid(grid, image.view());
    return split_maps(model, image.view());
  }
  // The grid with a one-pixel margin, for the height's central differences.
  Grid wide = grid;
  wide.width += 2;
  wide.height += 2;
  wide.first_pixel_x -= 1;
  wide.first_pixel_y -= 1;
  ImageF rendered(wide.width, wide.height, model.channels());
  render_grid(wide, rendered.view());
  // Every map's channels (a derived normal map's two slopes) in the grid.
  std::vector<MapInfo> maps(model.maps().begin(), model.maps().end());
  const std::vector<int> first_channel = first_channels(maps);  // of each map in `rendered`
  for (MapInfo& map : maps)
    if (!map.derived_from.empty()) map.channels = 2;
  ImageF full(grid.width, grid.height, map_channels(maps));
  int target = 0;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    if (model.maps()[m].derived_from.empty()) {
      for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x)
          for (int c = 0; c < maps[m].channels; ++c)
            full.at(x, y, target + c) = rendered.at(x + 1, y + 1, first_channel[m] + c);
    } else {
      const auto height =
          std::find_if(model.maps().begin(), model.maps().end(),
                       [&](const MapInfo& other) { return other.name == maps[m].derived_from; });
      const int h = first_channel[static_cast<std::size_t>(height - model.maps().begin())];
      const double k = maps[m].slope_scale / (2.0 * grid.scale);
      for (int y = 0; y < grid.height; ++y)
        for (int x = 0; x < grid.width; ++x) {
          const double dx =
              static_cast<double>(rendered.at(x + 2, y + 1, h)) - rendered.at(x, y + 1, h);
          const double dy =
              static_cast<double>(rendered.at(x + 1, y + 2, h)) - rendered.at(x + 1, y, h);
          full.at(x, y, target) = static_cast<float>(k * dx);
          full.at(x, y, target + 1) = static_cast<float>(-k * dy);  // y up: towards row 0
        }
    }
    target += maps[m].channels;
  }
  return split(maps, full.view());
}

}  // namespace stochtex
