#include "methods/tiling/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/level_of_detail.hpp"
#include "methods/tiling/params.hpp"
#include "methods/tiling/pyramid.hpp"
#include "methods/tiling/simd.hpp"
#include "model/model_colour.hpp"

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
  if (!d.colour.empty() && d.colour.size() != static_cast<std::size_t>(d.channels))
    throw std::invalid_argument("tiling: the colour spaces do not match the channels");
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

  // T^-1 prefiltered per level (pyramid.hpp) and calibrated, or as the model file stored them.
  lut_floats_ = d.lut.size();
  table_floats_ = d.tables.size();
  const bool stored = !d.level_tables.empty();
  decoded_calibrated_ = stored;
  if (stored) {
    if (layout_.colour_lut || d.level_tables.size() != texels.size() * table_floats_)
      throw std::invalid_argument("tiling: the level tables do not match the model");
    level_tables_ = std::move(data_.level_tables);
    data_.level_tables = {};
  } else {
    prefilter_levels(d, layout_, texels, widths, heights, level_luts_, level_tables_);
  }
  simd_ready_ = simd_ready_ && level_luts_.size() < std::size_t{1} << 31 &&
                level_tables_.size() < std::size_t{1} << 31;
  if (!stored) calibrate_colour();
}

// The prefiltered T^-1 of a level (section 5.4) is the expectation over a Gaussian residual of
// the level's Gaussian values, which averages right only when the level's values are Gaussian.
// The patches of a textured exemplar are not (nuts_grey_256: mostly dark background or bright
// nut), and decoding, far from linear on such contrasts, makes the error visible: its renders at
// scale 8 averaged 8 levels of 255 darker than supersampled ones. Each level's decoded tables are
// therefore shifted by what its renders, measured with this evaluator, miss of the mean of point
// samples: kCalibrationSamples evaluations at positions far apart (independent patches), seed 0,
// with footprints of the level and without.
// A shift of all of a table's values shifts its interpolated output by as much.
void TilingModel::measure_levels(
    const std::function<void(int, double, std::span<const float>)>& at_level) const {
  constexpr int kCalibrationSamples = 32768;
  const int channels = data_.channels;
  const std::vector<Vec2d> positions = spread_positions(kCalibrationSamples, 0x9e3779b97f4a7c15ull);
  std::vector<float> out(static_cast<std::size_t>(kCalibrationSamples) * channels);
  const ImageView<float> view{out.data(), kCalibrationSamples, 1, channels,
                              static_cast<std::ptrdiff_t>(kCalibrationSamples) * channels};
  evaluate(positions, {}, 0, view);
  at_level(0, 0.0, out);
  for (int l = 1; l < level_count(); ++l) {
    const double width = std::exp2(l + kLodBias + 1e-6);
    const std::vector<Footprint> footprints(kCalibrationSamples,
                                            Footprint{{width, 0.0}, {0.0, width}});
    evaluate(positions, footprints, 0, view);
    at_level(l, width, out);
  }
}

void TilingModel::calibrate_colour() {
  const int channels = data_.channels;
  std::vector<int> decoded;
  for (int c = 0; c < channels; ++c)
    if (decodes_in_tables(c)) decoded.push_back(c);
  if (decoded.empty() || level_count() < 2) return;
  // The target: the mean of point samples (level 0, decoded exactly), as a supersampled render
  // averages them.
  std::vector<double> target(static_cast<std::size_t>(channels), 0.0);
  measure_levels([&](int l, double, std::span<const float> values) {
    const auto mean_of = [&](int c) {
      double sum = 0.0;
      for (std::size_t i = static_cast<std::size_t>(c); i < values.size(); i += channels)
        sum += values[i];
      return sum / static_cast<double>(values.size() / static_cast<std::size_t>(channels));
    };
    if (l == 0) {
      for (const int c : decoded) target[static_cast<std::size_t>(c)] = mean_of(c);
      return;
    }
    for (const int c : decoded) {
      const auto shift = static_cast<float>(target[static_cast<std::size_t>(c)] - mean_of(c));
      for (const TableGroup& group : layout_.groups) {
        if (c < group.first || c >= group.first + group.channels) continue;
        if (group.transform == GroupTransform::lut) {
          float* lut = level_luts_.data() + static_cast<std::size_t>(l) * lut_floats_;
          for (std::size_t i = static_cast<std::size_t>(c - group.first); i < lut_floats_; i += 3)
            lut[i] += shift;
        } else {
          // A one-channel decorrelated group's output is mean + b t: its table shifts by 1 / b.
          const float scale =
              group.transform == GroupTransform::decorrelated
                  ? 1.0f / data_.colour_basis[static_cast<std::size_t>(group.first_basis)]
                  : 1.0f;
          float* table = level_tables_.data() + static_cast<std::size_t>(l) * table_floats_ +
                         static_cast<std::size_t>(group.first_table) * data_.table_size;
          for (int i = 0; i < data_.table_size; ++i) table[i] += shift * scale;
        }
      }
    }
  });
}

void TilingModel::calibrate_decoded(const std::function<float(int, double)>& removed) {
  if (decoded_calibrated_ || data_.colour.empty() || level_count() < 2) return;
  decoded_calibrated_ = true;
  std::vector<const TableGroup*> groups;
  for (const TableGroup& group : layout_.groups)
    if (group.transform == GroupTransform::decorrelated && group.channels > 1)
      for (int k = 0; k < group.channels; ++k)
        if (data_.colour[static_cast<std::size_t>(group.first + k)] == ColourSpace::srgb) {
          groups.push_back(&group);
          break;
        }
  if (groups.empty()) return;
  const int channels = data_.channels;
  const auto srgb = [&](int c) {
    return data_.colour[static_cast<std::size_t>(c)] == ColourSpace::srgb;
  };
  std::vector<double> target(static_cast<std::size_t>(channels), 0.0);
  measure_levels([&](int l, double width, std::span<const float> values) {
    // The mean of D(v + shift, deviation) over the values v of channel c.
    const auto decoded_mean = [&](int c, float shift, float deviation) {
      double sum = 0.0;
      for (std::size_t i = static_cast<std::size_t>(c); i < values.size(); i += channels)
        sum += expected_decoded(values[i] + shift, deviation);
      return sum / static_cast<double>(values.size() / static_cast<std::size_t>(channels));
    };
    if (l == 0) {
      for (int c = 0; c < channels; ++c)
        if (srgb(c)) target[static_cast<std::size_t>(c)] = decoded_mean(c, 0.0f, removed(c, 0.0));
      return;
    }
    for (const TableGroup* group : groups) {
      // The shift of each output channel that the decoded mean asks for: Newton's method, the
      // slope by central differences.
      const int cc = group->channels;
      std::array<double, kMaxChannels> shift{};
      for (int k = 0; k < cc; ++k) {
        const int c = group->first + k;
        if (!srgb(c)) continue;
        const float deviation = removed(c, width);
        float s = 0.0f;
        for (int step = 0; step < 3; ++step) {
          constexpr float kStep = 1e-3f;
          const double slope =
              (decoded_mean(c, s + kStep, deviation) - decoded_mean(c, s - kStep, deviation)) /
              (2.0 * kStep);
          if (!(slope > 0.0)) break;
          s += static_cast<float>(
              (target[static_cast<std::size_t>(c)] - decoded_mean(c, s, deviation)) / slope);
        }
        shift[static_cast<std::size_t>(k)] = s;
      }
      // The output is mean + B t (from_decorrelated) with B the group's PCA basis, orthonormal:
      // the tables shift by B^T shift, as the analysis projects the colours by B^T.
      float* tables = level_tables_.data() + static_cast<std::size_t>(l) * table_floats_ +
                      static_cast<std::size_t>(group->first_table) * data_.table_size;
      for (int k = 0; k < cc; ++k) {
        double d = 0.0;
        for (int c = 0; c < cc; ++c)
          d += data_.colour_basis[static_cast<std::size_t>(group->first_basis + c * cc + k)] *
               shift[static_cast<std::size_t>(c)];
        for (int i = 0; i < data_.table_size; ++i)
          tables[static_cast<std::size_t>(k) * data_.table_size + i] += static_cast<float>(d);
      }
    }
  });
}

bool TilingModel::decodes_in_tables(int channel) const noexcept {
  for (const TableGroup& group : layout_.groups)
    if (channel >= group.first && channel < group.first + group.channels)
      return tiling::decodes_in_tables(data_, group, channel);
  return false;
}

TilingModel TilingModel::with_colour(std::vector<ColourSpace> colour) const {
  TilingData data = data_;
  data.colour = std::move(colour);
  return TilingModel(std::move(data));
}

MipLevel TilingModel::level(int index) const {
  const PyramidLevel& level = levels_[static_cast<std::size_t>(index)];
  return {level.width, level.height,
          static_cast<float>(static_cast<double>(level.width) / data_.width),
          static_cast<float>(static_cast<double>(level.height) / data_.height),
          pyramid_.data() + level.first};
}

}  // namespace stochtex::tiling
