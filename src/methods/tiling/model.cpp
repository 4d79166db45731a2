#include "methods/tiling/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/colour_statistics.hpp"
#include "core/cpu_target.hpp"
#include "core/level_of_detail.hpp"
#include "core/triplanar.hpp"
#include "methods/tiling/params.hpp"
#include "methods/tiling/simd.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"

namespace stochtex::tiling {
namespace {

// Strata of the quadrature that prefilters T^-1 (see prefilter_kernel).
constexpr int kPrefilterStrata = 64;
constexpr int kMaxExemplarSide = 1 << 16;

// Level l + 1 averages 2 x 2 texels of level l with periodic wrap, so every level keeps the mean
// of G exactly and the exemplar's period (texels_per_pixel = level width / exemplar width).
std::vector<std::vector<float>> build_pyramid(const std::vector<float>& base, int width, int height,
                                              int channels, std::vector<int>& widths,
                                              std::vector<int>& heights) {
  std::vector<std::vector<float>> levels{base};
  widths = {width};
  heights = {height};
  while (widths.back() > 1 || heights.back() > 1) {
    const int w = widths.back();
    const int h = heights.back();
    const int next_w = (w + 1) / 2;
    const int next_h = (h + 1) / 2;
    const std::vector<float>& current = levels.back();
    std::vector<float> next(static_cast<std::size_t>(next_w) * next_h * channels, 0.0f);
    for (int y = 0; y < next_h; ++y)
      for (int x = 0; x < next_w; ++x)
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = (2 * x + dx) % w;
            const int sy = (2 * y + dy) % h;
            for (int c = 0; c < channels; ++c)
              next[(static_cast<std::size_t>(y) * next_w + x) * channels + c] +=
                  0.25f * current[(static_cast<std::size_t>(sy) * w + sx) * channels + c];
          }
    levels.push_back(std::move(next));
    widths.push_back(next_w);
    heights.push_back(next_h);
  }
  return levels;
}

// The variance of each channel of a pyramid level's texels (width x height x channels).
std::vector<double> level_variances(const std::vector<float>& texels, int width, int height,
                                    int channels) {
  const ImageView<const float> level{texels.data(), width, height, channels,
                                     static_cast<std::ptrdiff_t>(width) * channels};
  return channel_variances(level, channel_means(level));
}

// One row of a banded matrix: entries first .. first + weights.size() - 1.
struct KernelRow {
  int first = 0;
  std::vector<float> weights;
};

// The prefiltered inverse of a pyramid level (our reading of Deliot & Heitz 2019, section
// "prefiltering the look-up table"): a level-l texel is the mean g of the G values under it, and
// the filtered output wanted is the mean of T^-1 over those values, not T^-1(g). For a Gaussian
// field the level-0 values under a texel of mean g spread as N(g, r^2) with r^2 = var(G_0) -
// var(G_l), so T^-1_l(g) = E[T^-1(z)], z ~ N(g, r^2). At the top level (one texel, r = sigma)
// a constant fetch returns the exemplar's mean colour, not T^-1(1/2), its median. The expectation
// is a midpoint rule over `kPrefilterStrata` equal-probability strata of N(g, r^2), each read from
// the table like the evaluator does (linear interpolation in the erf parameterisation, eq. 22);
// row i is the table cell at g_i = 1/2 + sigma Phi^-1((i + 1/2) / size).
std::vector<KernelRow> prefilter_kernel(int size, double residual_deviation) {
  std::vector<KernelRow> rows(static_cast<std::size_t>(size));
  std::vector<double> strata(kPrefilterStrata);
  for (int q = 0; q < kPrefilterStrata; ++q)
    strata[q] = normal_quantile((q + 0.5) / kPrefilterStrata);
  std::vector<double> dense(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) {
    std::fill(dense.begin(), dense.end(), 0.0);
    const double centre = kGaussianMean + kGaussianDeviation * normal_quantile((i + 0.5) / size);
    int first = size;
    int last = -1;
    for (int q = 0; q < kPrefilterStrata; ++q) {
      const auto g = static_cast<float>(centre + residual_deviation * strata[q]);
      int cell = 0;
      const float t = table_coordinate(gaussian_to_uniform(g), size, cell);
      dense[cell] += (1.0 - t) / kPrefilterStrata;
      dense[cell + 1] += static_cast<double>(t) / kPrefilterStrata;
      first = std::min(first, cell);
      last = std::max(last, cell + 1);
    }
    rows[i].first = first;
    rows[i].weights.assign(dense.begin() + first, dense.begin() + last + 1);
  }
  return rows;
}

// out[i] = sum_a K[i][a] in[a] along one axis of a table with `stride` floats between cells and
// `count` independent lines, each line's origin given by line_origin(line). Each sum adds its
// terms in the order of a; the sums of a block of lines and components run side by side (a
// model load is bound by this loop: one sum at a time waits on every addition).
template <typename Origin>
void apply_kernel(const std::vector<KernelRow>& rows, const std::vector<float>& in,
                  std::vector<float>& out, std::size_t stride, std::size_t lines, int components,
                  Origin line_origin) {
  constexpr std::size_t kBlock = 8;
  std::array<std::size_t, kBlock * 3> origins{};
  std::array<double, kBlock * 3> sums{};
  for (std::size_t line = 0; line < lines; line += kBlock) {
    std::size_t chains = 0;
    for (std::size_t l = line; l < std::min(line + kBlock, lines); ++l)
      for (int c = 0; c < components; ++c) origins[chains++] = line_origin(l) + c;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      std::fill_n(sums.begin(), chains, 0.0);
      const float* from = in.data() + static_cast<std::size_t>(rows[i].first) * stride;
      for (std::size_t k = 0; k < rows[i].weights.size(); ++k) {
        const float weight = rows[i].weights[k];  // a float product, added in double
        for (std::size_t j = 0; j < chains; ++j) sums[j] += weight * from[origins[j] + k * stride];
      }
      for (std::size_t j = 0; j < chains; ++j)
        out[origins[j] + i * stride] = static_cast<float>(sums[j]);
    }
  }
}

// prefilter_kernel for a radial table (GroupTransform::radial): the level's texel is the mean g of
// slopes in Gaussian space spread as N(g, r^2 I) in 2-D, and the filtered slope wanted is the mean
// of T^-1 over them, E[|s|(|z|) z / |z|], z ~ N(g, r^2 I) (centred). By symmetry it points along g
// with a magnitude that depends on |g| alone: row i holds it at the cell's radius. The expectation
// is a midpoint rule over kRadialStrata^2 equal-probability strata of the 2-D Gaussian.
constexpr int kRadialStrata = 16;

void prefilter_radial(const std::vector<float>& base, int table, int size, double spread,
                      std::vector<float>& out) {
  std::vector<double> strata(kRadialStrata);
  for (int q = 0; q < kRadialStrata; ++q)
    strata[q] = spread * normal_quantile((q + 0.5) / kRadialStrata);
  const float* slopes = base.data() + static_cast<std::ptrdiff_t>(table) * size;
  for (int i = 0; i < size; ++i) {
    const double rho = uniform_to_radius((i + 0.5) / size);
    double sum = 0.0;
    for (const double a : strata)
      for (const double b : strata) {
        const double x = rho + a;
        const double length = std::hypot(x, b);
        if (length > 0.0)
          sum += radial_lookup(slopes, size, static_cast<float>(length)) * (x / length);
      }
    out[static_cast<std::size_t>(table) * size + i] =
        static_cast<float>(sum / (kRadialStrata * kRadialStrata));
  }
}

float table_lookup(const float* table, int size, float g) noexcept {
  int cell = 0;
  const float t = table_coordinate(gaussian_to_uniform(g), size, cell);
  return table[cell] + t * (table[cell + 1] - table[cell]);
}

// Artist control i of kParams (i >= kFirstControl) in the data.
double control(const TilingData& data, std::size_t index) {
  const double values[] = {data.rotation, data.scale_jitter, data.sharpness, data.height_blend};
  return values[index - kFirstControl];
}

}  // namespace

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

  // T^-1 prefiltered per level (see prefilter_kernel); the residual deviation differs per channel.
  lut_floats_ = d.lut.size();
  table_floats_ = d.tables.size();
  const std::vector<double> base_variance =
      level_variances(texels.front(), d.width, d.height, d.channels);
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const std::vector<double> variance =
        level_variances(texels[l], levels_[l].width, levels_[l].height, d.channels);
    const auto residual = [&](int channel) {
      return l == 0 ? 0.0 : std::sqrt(std::max(0.0, base_variance[channel] - variance[channel]));
    };
    std::vector<float> lut = d.lut;
    std::vector<float> tables = d.tables;
    for (const TableGroup& group : layout_.groups) {
      if (l == 0) break;
      if (group.transform == GroupTransform::lut) {
        std::vector<float> scratch(lut.size());
        // Axis c of the table is channel first + c of G; the layout is [z][y][x][colour].
        const int f = group.first;
        apply_kernel(prefilter_kernel(d.lut_size, residual(f)), lut, scratch, 3, n * n, 3,
                     [&](std::size_t line) { return line * n * 3; });
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 1)), scratch, lut, n * 3, n * n, 3,
                     [&](std::size_t line) { return (line / n) * n * n * 3 + (line % n) * 3; });
        apply_kernel(prefilter_kernel(d.lut_size, residual(f + 2)), lut, scratch, n * n * 3, n * n,
                     3, [&](std::size_t line) { return line * 3; });
        lut = std::move(scratch);
        continue;
      }
      if (group.transform == GroupTransform::radial) {
        // Both slopes of G spread alike (T is isotropic): one residual for the pair.
        const double spread = std::hypot(residual(group.first), residual(group.first + 1));
        prefilter_radial(d.tables, group.first_table, d.table_size,
                         spread * std::numbers::sqrt2 / 2.0, tables);
        continue;
      }
      // Table k of a group is read at channel first + k of G.
      const int count = group.transform == GroupTransform::direct ? 1 : group.channels;
      for (int k = 0; k < count; ++k) {
        const int t = group.first_table + k;
        const auto size = static_cast<std::size_t>(d.table_size);
        apply_kernel(prefilter_kernel(d.table_size, residual(group.first + k)), d.tables, tables, 1,
                     1, 1, [&](std::size_t) { return static_cast<std::size_t>(t) * size; });
      }
    }
    level_luts_.insert(level_luts_.end(), lut.begin(), lut.end());
    level_tables_.insert(level_tables_.end(), tables.begin(), tables.end());
  }
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
  if (layout.basis_size > 0 && layout.image_layout) {
    data.colour_basis = take("colour_basis", {cc, cc});
    data.colour_mean = take("colour_mean", {cc});
  } else if (layout.basis_size > 0) {
    data.colour_basis = take("colour_basis", {layout.basis_size});
    data.colour_mean = take("colour_mean", {layout.mean_size});
  }
  try {
    return TilingModel(std::move(data));
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid tiling model (" + e.what() +
                                       "); re-run `stochtex analyze`");
  }
}

ModelRecord TilingModel::to_record(const ParamValues& params) const {
  const TilingData& d = data_;
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  // The radius used, also when the analysis chose it (tile_radius = 0): `stochtex info` shows it.
  record.params["tile_radius"] = d.tile_radius;
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

double TilingModel::footprint_width(const Footprint* footprint) noexcept {
  if (footprint == nullptr) return 0.0;
  // Isotropic: the longer axis decides, as GPU trilinear filtering does without anisotropy.
  return std::max(std::hypot(footprint->dpdx.x, footprint->dpdx.y),
                  std::hypot(footprint->dpdy.x, footprint->dpdy.y));
}

LevelOfDetail TilingModel::level_of_detail(double width) const noexcept {
  // Section 5.4: the footprint is the derivative of the position *before* the random offsets (a
  // translation does not change it), so the three patches read the same level (unless scale
  // jitter scales a patch's footprint; a rotation keeps its width).
  if (!(width > 1.0)) return {};
  const double lod = std::log2(width) - kLodBias;
  const int top = level_count() - 1;
  if (!(lod > 0.0)) return {};
  if (lod >= top) return {top, 0.0f};
  const int level = static_cast<int>(lod);
  return {level, static_cast<float>(lod - level)};
}

LevelOfDetail TilingModel::split_level(double lod) const noexcept {
  // A mean of levels may round past the top one: clamped there with no blend, as
  // level_of_detail does (a blend at the top would read beyond the pyramid).
  const int top = level_count() - 1;
  if (lod >= top) return {top, 0.0f};
  return {static_cast<int>(lod), static_cast<float>(lod - static_cast<int>(lod))};
}

LevelOfDetail TilingModel::blended_gaussian(Vec2d position, double footprint_width,
                                            std::uint32_t seed, float* g) const noexcept {
  const int channels = data_.channels;
  const LatticePoint lattice = triangle_lattice(position, edge_);
  const LevelOfDetail lod = level_of_detail(footprint_width);
  const Point2f wrapped = wrap_position(position, data_.width, data_.height);
  const bool transformed = this->transformed();
  const auto max_angle = static_cast<float>(data_.rotation * (std::numbers::pi / 180.0));
  const auto jitter = static_cast<float>(data_.scale_jitter);
  const auto edge = static_cast<float>(edge_);
  float weight[3] = {lattice.weight[0], lattice.weight[1], lattice.weight[2]};
  sharpen_weights(weight, static_cast<float>(data_.sharpness));
  float acc[kMaxChannels] = {};
  float weight_squares = 0.0f;
  double weighted_lod = 0.0;
  // The height-aware blend and the turn of a normal map's slopes: each patch fetched apart, then
  // turned (turn_slopes) and weighted by its height (below).
  const bool height_aware = data_.height_blend > 0.0;
  const bool turned = transformed && has_radial_group_;
  float patch[3][kMaxChannels];
  double patch_level[3] = {};
  for (int v = 0; v < 3; ++v) {
    const float w = weight[v];
    weight_squares += w * w;
    const Point2f offset =
        vertex_offset(lattice.vertex_x[v], lattice.vertex_y[v], seed, data_.width, data_.height);
    float x = wrapped.x + offset.x;
    float y = wrapped.y + offset.y;
    LevelOfDetail patch_lod = lod;
    PatchTransform m{1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
    if (transformed) {
      m = patch_transform(lattice.vertex_x[v], lattice.vertex_y[v], seed, max_angle, jitter);
      const Point2f shift =
          patch_shift(m, lattice.from_vertex_x[v], lattice.from_vertex_y[v], edge);
      x += shift.x;
      y += shift.y;
      patch_lod = level_of_detail(footprint_width * m.scale);
      weighted_lod +=
          static_cast<double>(w) * w * (patch_lod.level + static_cast<double>(patch_lod.blend));
    }
    const MipLevel fine = level(patch_lod.level);
    if (height_aware || turned) {
      std::fill_n(patch[v], channels, 0.0f);
      fetch_bilinear(fine, channels, x, y, 1.0f - patch_lod.blend, patch[v]);
      if (patch_lod.blend > 0.0f)
        fetch_bilinear(level(std::min(patch_lod.level + 1, level_count() - 1)), channels, x, y,
                       patch_lod.blend, patch[v]);
      patch_level[v] = patch_lod.level + static_cast<double>(patch_lod.blend);
      if (turned)
        for (const TableGroup& group : layout_.groups)
          if (group.transform == GroupTransform::radial)
            turn_slopes(m,
                        data_.tables.data() +
                            static_cast<std::ptrdiff_t>(group.first_table) * data_.table_size,
                        data_.table_size, patch[v] + group.first);
      continue;
    }
    fetch_bilinear(fine, channels, x, y, w * (1.0f - patch_lod.blend), acc);
    if (patch_lod.blend > 0.0f)
      fetch_bilinear(level(std::min(patch_lod.level + 1, level_count() - 1)), channels, x, y,
                     w * patch_lod.blend, acc);
  }
  if (height_aware || turned) {
    // The same variance-preserving blend (eq. 13 of Heitz & Neyret 2018, DOI 10.1145/3233304) of
    // the patches kept apart, with the weights from their Gaussianised heights when height_blend is
    // on: sum w' = 1, normalised by sqrt(sum w'^2).
    if (height_aware) {
      const float heights[3] = {patch[0][data_.height_channel], patch[1][data_.height_channel],
                                patch[2][data_.height_channel]};
      height_blend_weights(weight, heights, static_cast<float>(data_.height_blend));
    }
    weight_squares = 0.0f;
    weighted_lod = 0.0;
    for (int v = 0; v < 3; ++v) {
      const float w = weight[v];
      weight_squares += w * w;
      weighted_lod += static_cast<double>(w) * w * patch_level[v];
      for (int c = 0; c < channels; ++c) acc[c] += w * patch[v][c];
    }
  }
  // Eq. (8)/(13): (sum w G - E[G]) / sqrt(sum w^2) + E[G], with sum w = 1; eq. (3) for linear.
  const float inverse_norm = data_.blend == Blend::linear ? 1.0f : 1.0f / std::sqrt(weight_squares);
  for (int c = 0; c < channels; ++c)
    g[c] = (acc[c] - data_.blend_mean[c]) * inverse_norm + data_.blend_mean[c];
  return data_.scale_jitter > 0.0 ? split_level(weighted_lod / weight_squares) : lod;
}

void TilingModel::inverse_at_level(const float* g, int level, float* out) const noexcept {
  const std::span<const float> tables = level_tables(level);
  const int size = data_.table_size;
  for (const TableGroup& group : layout_.groups) {
    const float* gg = g + group.first;
    float* o = out + group.first;
    if (group.transform == GroupTransform::lut) {
      // Trilinear fetch of the 3-D table at U of eq. (22), [z][y][x][colour] layout.
      const std::span<const float> lut = level_lut(level);
      const int n = data_.lut_size;
      int cell[3];
      float t[3];
      for (int c = 0; c < 3; ++c) t[c] = table_coordinate(gaussian_to_uniform(gg[c]), n, cell[c]);
      const std::ptrdiff_t step_y = static_cast<std::ptrdiff_t>(n) * 3;
      const std::ptrdiff_t step_z = step_y * n;
      const float* base = lut.data() + cell[2] * step_z + cell[1] * step_y + cell[0] * 3;
      float acc[3];
      for (int c = 0; c < 3; ++c) {
        const float* p = base + c;
        const float x00 = p[0] + t[0] * (p[3] - p[0]);
        const float x10 = p[step_y] + t[0] * (p[step_y + 3] - p[step_y]);
        const float x01 = p[step_z] + t[0] * (p[step_z + 3] - p[step_z]);
        const float x11 = p[step_z + step_y] + t[0] * (p[step_z + step_y + 3] - p[step_z + step_y]);
        const float y0 = x00 + t[1] * (x10 - x00);
        const float y1 = x01 + t[1] * (x11 - x01);
        acc[c] = y0 + t[2] * (y1 - y0);
      }
      for (int c = 0; c < 3; ++c) o[c] = acc[c];
    } else if (group.transform == GroupTransform::decorrelated) {
      // 1-D tables per decorrelated channel, then back to the group's basis.
      const int cc = group.channels;
      const float* basis = data_.colour_basis.data() + group.first_basis;
      const float* mean = data_.colour_mean.data() + group.first_mean;
      float decorrelated[kMaxChannels];
      for (int c = 0; c < cc; ++c)
        decorrelated[c] = table_lookup(
            tables.data() + static_cast<std::ptrdiff_t>(group.first_table + c) * size, size, gg[c]);
      for (int c = 0; c < cc; ++c) {
        float value = mean[c];
        for (int k = 0; k < cc; ++k) value += basis[c * cc + k] * decorrelated[k];
        o[c] = value;
      }
    } else if (group.transform == GroupTransform::radial) {
      // The magnitude from the (prefiltered) radial table, along g's direction from the centre.
      const float dx = gg[0] - kGaussianMean;
      const float dy = gg[1] - kGaussianMean;
      const float rho = std::sqrt(dx * dx + dy * dy);
      const float magnitude =
          rho > 0.0f
              ? radial_lookup(tables.data() + static_cast<std::ptrdiff_t>(group.first_table) * size,
                              size, rho) /
                    rho
              : 0.0f;
      o[0] = magnitude * dx;
      o[1] = magnitude * dy;
    } else {
      o[0] = table_lookup(tables.data() + static_cast<std::ptrdiff_t>(group.first_table) * size,
                          size, gg[0]);
    }
  }
}

void TilingModel::inverse_transform(const float* g, LevelOfDetail lod, float* out) const noexcept {
  const int channels = data_.channels;
  if (data_.blend != Blend::histogram) {
    for (int c = 0; c < channels; ++c) out[c] = g[c];
    return;
  }
  inverse_at_level(g, lod.level, out);
  if (lod.blend > 0.0f) {
    float coarse[kMaxChannels];
    inverse_at_level(g, lod.level + 1, coarse);
    for (int c = 0; c < channels; ++c) out[c] += lod.blend * (coarse[c] - out[c]);
  }
}

void TilingModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                           std::uint32_t seed, ImageView<float> out) const noexcept {
  if (simd_ready_ && simd_enabled()) return evaluate_simd(positions, footprints, seed, out);
  for (std::size_t index = 0; index < positions.size(); ++index) {
    float g[kMaxChannels];
    const LevelOfDetail lod = blended_gaussian(
        positions[index], footprint_width(footprints.empty() ? nullptr : &footprints[index]), seed,
        g);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    inverse_transform(g, lod, &out.at(x, y, 0));
  }
}

SimdTiling TilingModel::simd_tiling() const noexcept {
  SimdTiling m;
  m.channels = data_.channels;
  m.width = data_.width;
  m.height = data_.height;
  m.edge = edge_;
  m.linear = data_.blend == Blend::linear;
  m.inverse = data_.blend == Blend::histogram;
  m.blend_mean = data_.blend_mean.data();
  m.pyramid = pyramid_.data();
  m.level_count = level_count();
  for (int l = 0; l < m.level_count; ++l) {
    const MipLevel mip = level(l);
    const auto i = static_cast<std::size_t>(l);
    m.level_width[i] = mip.width;
    m.level_height[i] = mip.height;
    m.level_first[i] = static_cast<std::int32_t>(levels_[i].first);
    m.texels_per_pixel_x[i] = mip.texels_per_pixel_x;
    m.texels_per_pixel_y[i] = mip.texels_per_pixel_y;
  }
  m.groups = layout_.groups;
  m.lut_size = data_.lut_size;
  m.table_size = data_.table_size;
  m.luts = level_luts_.data();
  m.lut_floats = static_cast<std::int32_t>(lut_floats_);
  m.tables = level_tables_.data();
  m.table_floats = static_cast<std::int32_t>(table_floats_);
  m.colour_basis = data_.colour_basis.data();
  m.colour_mean = data_.colour_mean.data();
  return m;
}

void TilingModel::evaluate_simd(std::span<const Vec2d> positions,
                                std::span<const Footprint> footprints, std::uint32_t seed,
                                ImageView<float> out) const noexcept {
  const SimdTiling m = simd_tiling();
  std::int32_t levels[kSimdBatch];
  float blends[kSimdBatch];
  // A render's footprints repeat: the level of detail of the last one is kept.
  Footprint last{};
  LevelOfDetail last_lod = level_of_detail(&last);
  for (std::size_t first = 0; first < positions.size(); first += kSimdBatch) {
    const std::size_t size = std::min(kSimdBatch, positions.size() - first);
    for (std::size_t i = 0; i < size; ++i) {
      LevelOfDetail lod;
      if (!footprints.empty()) {
        const Footprint& f = footprints[first + i];
        if (f.dpdx.x != last.dpdx.x || f.dpdx.y != last.dpdx.y || f.dpdy.x != last.dpdy.x ||
            f.dpdy.y != last.dpdy.y) {
          last = f;
          last_lod = level_of_detail(&f);
        }
        lod = last_lod;
      }
      levels[i] = lod.level;
      blends[i] = lod.blend;
    }
    evaluate_lanes(m, positions.subspan(first, size), levels, blends, seed, out, first);
  }
}

void TilingModel::evaluate_triplanar(std::span<const SurfacePoint> points, double sharpness,
                                     std::uint32_t seed, ImageView<float> out) const noexcept {
  const int channels = data_.channels;
  const std::vector<float>& mean = data_.blend_mean;
  for (std::size_t index = 0; index < points.size(); ++index) {
    const SurfacePoint& p = points[index];
    const std::array<double, 3> weights = triplanar_weights(p.normal, sharpness);
    double acc[kMaxChannels] = {};
    double weight_squares = 0.0;
    double lod = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double w = weights[static_cast<std::size_t>(k)];
      if (w == 0.0) continue;
      // Plane k's footprint: the 3-D footprint projected on the plane, as a 2-D render's.
      const Footprint footprint{on_plane(p.dpdx, k), on_plane(p.dpdy, k)};
      float g[kMaxChannels];
      const LevelOfDetail plane_lod = blended_gaussian(
          on_plane(p.position, k), footprint_width(&footprint), triplanar_seed(k, seed), g);
      for (int c = 0; c < channels; ++c) acc[c] += w * (g[c] - mean[c]);
      weight_squares += w * w;
      lod += w * w * (plane_lod.level + static_cast<double>(plane_lod.blend));
    }
    // The same operator as the lattice blend (eq. 13), with the normal's weights.
    const double inverse_norm =
        data_.blend == Blend::linear ? 1.0 : 1.0 / std::sqrt(weight_squares);
    float g[kMaxChannels];
    for (int c = 0; c < channels; ++c) g[c] = static_cast<float>(acc[c] * inverse_norm + mean[c]);
    // One T^-1 look-up, prefiltered for the w^2-weighted mean of the planes' levels: the blend's
    // variance is the w^2-weighted mean of the planes' (eq. 13), so is, to first order, the
    // residual variance r^2 the prefiltered table assumes (see prefilter_kernel). It is
    // continuous where the dominant plane changes (the dominant plane's level jumps there).
    // Measured (metal_grey_256, normal (1, 0.5, 0), footprint 8 x 2 pixels, mean against a 12 x 12
    // supersampled reference): bias -0.0003 (w^2), -0.0003 (dominant plane), -0.0010 (w),
    // -0.0144 (finest level: a coarse plane's values read through too sharp a table).
    const LevelOfDetail look_up = split_level(lod / weight_squares);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    inverse_transform(g, look_up, &out.at(x, y, 0));
  }
}

}  // namespace stochtex::tiling
