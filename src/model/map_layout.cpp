#include "model/map_layout.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

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

int map_channels(std::span<const MapInfo> maps) {
  int channels = 0;
  for (const MapInfo& map : maps) channels += map.channels;
  return channels;
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

}  // namespace stochtex

namespace stochtex {

std::vector<NamedImage> split_maps(const Model& model, ImageView<const float> rendered) {
  std::vector<NamedImage> images;
  if (model.maps().empty()) {
    ImageF image(rendered.width, rendered.height, rendered.channels);
    for (int y = 0; y < rendered.height; ++y)
      for (int x = 0; x < rendered.width; ++x)
        for (int c = 0; c < rendered.channels; ++c) image.at(x, y, c) = rendered.at(x, y, c);
    images.push_back({"image", std::move(image)});
    return images;
  }
  int first = 0;
  for (const MapInfo& map : model.maps()) {
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

}  // namespace stochtex
