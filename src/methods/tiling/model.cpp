#include "methods/tiling/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "methods/tiling/params.hpp"
#include "methods/tiling/pyramid.hpp"
#include "methods/tiling/simd.hpp"

namespace stochtex::tiling {

TilingLayout tiling_layout(int channels, Transport transport, Blend blend,
                           std::span<const GroupSpec> groups) {
  TilingLayout layout;
  layout.has_alpha = channels == 2 || channels == 4;
  layout.colour_channels = layout.has_alpha ? channels - 1 : channels;
  if (blend != Blend::histogram) {
    if (!groups.empty()) throw std::invalid_argument("tiling: only the histogram blend has groups");
    return layout;
  }
  std::vector<GroupSpec> specs(groups.begin(), groups.end());
  if (specs.empty()) {
    const bool lut = layout.colour_channels == 3 && transport == Transport::sliced;
    specs.push_back(
        {lut ? GroupTransform::lut : GroupTransform::decorrelated, layout.colour_channels});
    if (layout.has_alpha) specs.push_back({GroupTransform::direct, 1});
  } else {
    layout.image_layout = false;
  }
  int channel = 0;
  for (const GroupSpec& spec : specs) {
    TableGroup group{spec.transform,     channel,           spec.channels,
                     layout.table_count, layout.basis_size, layout.mean_size};
    if (spec.channels < 1 || spec.channels > channels - channel ||
        (spec.transform == GroupTransform::lut &&
         (spec.channels != 3 || transport != Transport::sliced || layout.colour_lut)) ||
        (spec.transform == GroupTransform::direct && spec.channels != 1) ||
        (spec.transform == GroupTransform::radial && spec.channels != 2))
      throw std::invalid_argument("tiling: the channel groups are invalid");
    switch (spec.transform) {
      case GroupTransform::lut:
        layout.colour_lut = true;
        break;
      case GroupTransform::decorrelated:
        layout.table_count += spec.channels;
        layout.basis_size += spec.channels * spec.channels;
        layout.mean_size += spec.channels;
        break;
      case GroupTransform::direct:
        if (layout.image_layout) layout.first_alpha_table = layout.table_count;
        layout.table_count += 1;
        break;
      case GroupTransform::radial:
        layout.table_count += 1;
        break;
    }
    channel += spec.channels;
    layout.groups.push_back(group);
  }
  if (channel != channels) throw std::invalid_argument("tiling: the channel groups are invalid");
  return layout;
}

TilingModel::TilingModel(TilingData data) : data_(std::move(data)) {
  const TilingData& d = data_;
  if (d.channels < 1 || d.channels > kMaxChannels)
    throw std::invalid_argument("tiling: channels must be 1 to " + std::to_string(kMaxChannels));
  if (d.width < 2 || d.height < 2 || d.width > kMaxExemplarSide || d.height > kMaxExemplarSide)
    throw std::invalid_argument("tiling: the exemplar sides must be 2 to 65536 pixels");
  if (!(d.tile_radius >= kParams[0].min_value && d.tile_radius <= kParams[0].max_value))
    throw std::invalid_argument("tiling: tile_radius is out of range");
  if (d.lut_size < 2 || d.lut_size > 64 || d.table_size < 16 || d.table_size > 65536)
    throw std::invalid_argument("tiling: look-up table size out of range");
  for (std::size_t i = kFirstControl; i < kParams.size(); ++i) {
    const double value = control(d, i);
    if (!(value >= kParams[i].min_value && value <= kParams[i].max_value))
      throw std::invalid_argument("tiling: " + std::string(kParams[i].name) + " is out of range");
  }
  if (d.height_blend > 0.0
          ? d.blend != Blend::histogram || d.height_channel < 0 || d.height_channel >= d.channels
          : d.height_channel != -1)
    throw std::invalid_argument(
        "tiling: height_blend needs the histogram blend and a height channel within the channels");
  layout_ = tiling_layout(d.channels, d.transport, d.blend, d.groups);
  has_radial_group_ = std::any_of(
      layout_.groups.begin(), layout_.groups.end(),
      [](const TableGroup& group) { return group.transform == GroupTransform::radial; });
  const auto n = static_cast<std::size_t>(d.lut_size);
  if (d.gaussian.size() != static_cast<std::size_t>(d.width) * d.height * d.channels ||
      d.blend_mean.size() != static_cast<std::size_t>(d.channels) ||
      d.lut.size() != (layout_.colour_lut ? n * n * n * 3 : 0) ||
      d.tables.size() != static_cast<std::size_t>(layout_.table_count) * d.table_size ||
      d.colour_basis.size() != static_cast<std::size_t>(layout_.basis_size) ||
      d.colour_mean.size() != static_cast<std::size_t>(layout_.mean_size))
    throw std::invalid_argument("tiling: an array has the wrong size");
  edge_ = d.tile_radius * std::min(d.width, d.height);

  std::vector<int> widths;
  std::vector<int> heights;
  std::vector<std::vector<float>> texels =
      build_pyramid(d.gaussian, d.width, d.height, d.channels, widths, heights);
  for (std::size_t l = 0; l < texels.size(); ++l) {
    levels_.push_back({widths[l], heights[l], pyramid_.size()});
    pyramid_.insert(pyramid_.end(), texels[l].begin(), texels[l].end());
  }
  simd_ready_ = !transformed() && d.sharpness == 1.0 && d.height_blend == 0.0 &&
                !has_radial_group_ && level_count() <= kSimdMaxLevels &&
                pyramid_.size() < std::size_t{1} << 31;
  if (d.blend != Blend::histogram) return;

  // T^-1 prefiltered per level (pyramid.hpp).
  lut_floats_ = d.lut.size();
  table_floats_ = d.tables.size();
  prefilter_levels(d, layout_, texels, widths, heights, level_luts_, level_tables_);
  simd_ready_ = simd_ready_ && level_luts_.size() < std::size_t{1} << 31 &&
                level_tables_.size() < std::size_t{1} << 31;
}

MipLevel TilingModel::level(int index) const {
  const PyramidLevel& level = levels_[static_cast<std::size_t>(index)];
  return {level.width, level.height,
          static_cast<float>(static_cast<double>(level.width) / data_.width),
          static_cast<float>(static_cast<double>(level.height) / data_.height),
          pyramid_.data() + level.first};
}

}  // namespace stochtex::tiling
