#pragma once
// The maps of a material model (stochtex/model.hpp MapInfo): their rules, checked where a layout
// comes in (analysis of a material, a model file), and the kinds' names as files and users write
// them.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/model.hpp"

namespace stochtex {

// The kind named `name` ("colour", "normal", "height", "scalar"), or none.
std::optional<MapKind> map_kind_from_name(std::string_view name);

// What is wrong with `maps` as a material's layout, as the end of a sentence ("map 'x' is
// named twice"), or none: names of 1 to 32 characters of a-z, 0-9 and _, unique; a kind's channel
// count (colour 1 or 3, normal 2, height and scalar 1); at least one map and kMaxChannels channels
// in all.
std::optional<std::string> map_layout_problem(std::span<const MapInfo> maps);

// The maps as the model file's header and `stochtex info --json` write them: {"name", "kind",
// "channels"}, "from", "scale" for a derived normal map, and "colour_space" when not data.
nlohmann::ordered_json maps_json(std::span<const MapInfo> maps);

// The channels of all maps.
int map_channels(std::span<const MapInfo> maps);

// The first channel of each map among the model's channels, in map order (a derived map, which
// has none, gets the channel where the next map starts).
std::vector<int> first_channels(std::span<const MapInfo> maps);

}  // namespace stochtex
