// The tiling model's arrays in and out of the model file (.stx, docs/design.md §7).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "methods/tiling/model.hpp"
#include "methods/tiling/params.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"

namespace stochtex::tiling {

TilingModel TilingModel::from_record(const ModelRecord& record, const std::string& source) {
  // Scalars are checked against the analysis parameters' ranges (params.hpp).
  const auto read = [&](const char* name, double low, double high, bool integer) {
    return record.scalar_in(name, low, high, integer, source);
  };
  const auto read_param = [&](std::string_view name) {
    return record.param_scalar(name, kParams, source);
  };
  TilingData data;
  data.channels = static_cast<int>(read("channels", 1, kMaxChannels, true));
  data.width = static_cast<int>(read("width", 2, kMaxExemplarSide, true));
  data.height = static_cast<int>(read("height", 2, kMaxExemplarSide, true));
  data.tile_radius = read_param("tile_radius");
  data.transport = static_cast<Transport>(static_cast<int>(read_param("transport")));
  data.lut_size = static_cast<int>(read_param("lut_size"));
  data.table_size = static_cast<int>(read_param("table_size"));
  data.blend = static_cast<Blend>(static_cast<int>(read_param("blend")));
  // The artist controls: absent at their defaults (to_record).
  const auto read_control = [&](std::size_t index) {
    const ParamInfo& info = kParams[index];
    return record.scalars.contains(info.name) ? read_param(info.name) : info.default_value;
  };
  data.rotation = read_control(kFirstControl);
  data.scale_jitter = read_control(kFirstControl + 1);
  data.sharpness = read_control(kFirstControl + 2);
  data.height_blend = read_control(kFirstControl + 3);
  // Resolved by the analysis (on or off); absent from a model made before the parameter existed.
  const auto made_tileable = record.params.find("make_tileable");
  data.made_tileable = made_tileable != record.params.end() &&
                       made_tileable->second == static_cast<double>(MakeTileable::on);
  if (data.height_blend > 0.0)
    data.height_channel = static_cast<int>(read("height_channel", 0, data.channels - 1, true));
  const auto take = [&](const std::string& name, const std::vector<std::int64_t>& shape) {
    const NamedArray& array = record.array(name, shape, source);
    if (!within_model_range(array.values))
      throw Error(ErrorCode::format, "'" + source +
                                         "' holds values that are not finite or beyond "
                                         "+-1e12 in tiling array '" +
                                         name + "'; re-run `stochtex analyze`");
    return array.values;
  };
  // A material's groups: (channels, transform) rows, checked by tiling_layout.
  const auto grouped = std::find_if(record.arrays.begin(), record.arrays.end(),
                                    [](const NamedArray& array) { return array.name == "groups"; });
  TilingLayout layout;
  try {
    if (grouped != record.arrays.end()) {
      const std::vector<std::int64_t> shape = grouped->shape;
      if (shape.size() != 2 || shape[0] < 1 || shape[0] > data.channels || shape[1] != 2)
        throw std::invalid_argument("the groups array has the wrong shape");
      const std::vector<float> rows = take("groups", shape);
      for (std::size_t i = 0; i < rows.size(); i += 2) {
        if (rows[i] != std::floor(rows[i]) || rows[i + 1] < 0.0f || rows[i + 1] > 3.0f ||
            rows[i + 1] != std::floor(rows[i + 1]))
          throw std::invalid_argument("a group is invalid");
        data.groups.push_back({static_cast<GroupTransform>(static_cast<int>(rows[i + 1])),
                               static_cast<int>(rows[i])});
      }
    }
    layout = tiling_layout(data.channels, data.transport, data.blend, data.groups);
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid tiling model (" + e.what() +
                                       "); re-run `stochtex analyze`");
  }
  const std::int64_t n = data.lut_size;
  const std::int64_t cc = layout.colour_channels;
  data.gaussian = take("gaussian", {data.height, data.width, data.channels});
  data.blend_mean = take("blend_mean", {data.channels});
  if (layout.colour_lut) data.lut = take("lut", {n, n, n, 3});
  if (layout.table_count > 0) data.tables = take("tables", {layout.table_count, data.table_size});
  if (!layout.colour_lut && layout.table_count > 0 &&
      std::any_of(record.arrays.begin(), record.arrays.end(),
                  [](const NamedArray& array) { return array.name == "level_tables"; })) {
    std::int64_t levels = 1;
    for (int w = data.width, h = data.height; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2)
      ++levels;
    data.level_tables = take("level_tables", {levels, layout.table_count, data.table_size});
  }
  if (layout.basis_size > 0 && layout.image_layout) {
    data.colour_basis = take("colour_basis", {cc, cc});
    data.colour_mean = take("colour_mean", {cc});
  } else if (layout.basis_size > 0) {
    data.colour_basis = take("colour_basis", {layout.basis_size});
    data.colour_mean = take("colour_mean", {layout.mean_size});
  }
  data.colour = record.channel_spaces(data.channels);
  if (std::all_of(data.colour.begin(), data.colour.end(),
                  [](ColourSpace space) { return space == ColourSpace::data; }))
    data.colour.clear();
  try {
    return TilingModel(std::move(data));
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid tiling model (" + e.what() +
                                       "); re-run `stochtex analyze`");
  }
}

void TilingModel::resolve_params(ParamValues& params) const {
  // The radius used, also when the analysis chose it (tile_radius = 0): `stochtex info` shows it.
  params["tile_radius"] = data_.tile_radius;
  params["make_tileable"] =
      static_cast<double>(data_.made_tileable ? MakeTileable::on : MakeTileable::off);
}

ModelRecord TilingModel::to_record(const ParamValues& params) const {
  const TilingData& d = data_;
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  resolve_params(record.params);
  record.scalars = {{"channels", d.channels},
                    {"width", d.width},
                    {"height", d.height},
                    {"tile_radius", d.tile_radius},
                    {"transport", static_cast<int>(d.transport)},
                    {"lut_size", d.lut_size},
                    {"table_size", d.table_size},
                    {"blend", static_cast<int>(d.blend)}};
  for (std::size_t i = kFirstControl; i < kParams.size(); ++i) {
    const std::string name(kParams[i].name);
    if (control(d, i) == kParams[i].default_value)
      record.params.erase(name);
    else
      record.scalars[name] = record.params[name] = control(d, i);
  }
  if (d.height_blend > 0.0) record.scalars["height_channel"] = d.height_channel;
  const std::int64_t n = d.lut_size;
  const std::int64_t cc = layout_.colour_channels;
  record.arrays.push_back({"gaussian", {d.height, d.width, d.channels}, d.gaussian});
  record.arrays.push_back({"blend_mean", {d.channels}, d.blend_mean});
  if (layout_.colour_lut) record.arrays.push_back({"lut", {n, n, n, 3}, d.lut});
  if (layout_.table_count > 0)
    record.arrays.push_back({"tables", {layout_.table_count, d.table_size}, d.tables});
  if (!layout_.colour_lut && !level_tables_.empty())
    record.arrays.push_back(
        {"level_tables", {level_count(), layout_.table_count, d.table_size}, level_tables_});
  if (!d.colour_basis.empty() && layout_.image_layout) {
    record.arrays.push_back({"colour_basis", {cc, cc}, d.colour_basis});
    record.arrays.push_back({"colour_mean", {cc}, d.colour_mean});
  } else if (!d.colour_basis.empty()) {
    record.arrays.push_back({"colour_basis", {layout_.basis_size}, d.colour_basis});
    record.arrays.push_back({"colour_mean", {layout_.mean_size}, d.colour_mean});
  }
  if (!d.groups.empty()) {
    std::vector<float> rows;
    for (const GroupSpec& group : d.groups) {
      rows.push_back(static_cast<float>(group.channels));
      rows.push_back(static_cast<float>(static_cast<int>(group.transform)));
    }
    record.arrays.push_back({"groups", {static_cast<std::int64_t>(d.groups.size()), 2}, rows});
  }
  return record;
}

}  // namespace stochtex::tiling
