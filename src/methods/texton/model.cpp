#include "methods/texton/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/surface_process.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/params.hpp"
#include "methods/texton/simd.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"

namespace stochtex::texton {
namespace {

// Cell size a = 0.6 r of the grid that simulates the Poisson process (section 8).
constexpr double kCellSizeFactor = 0.6;

// Level l+1 averages 2x2 texels of level l (zero beyond the border), so sum(alpha_l) * 4^l stays
// sum(alpha): the filtered noise keeps the exemplar mean, and h_l approximates h convolved with a
// box of width 2^l (section 5: filtering the noise = filtering the texton, by linearity). Texels
// hold texton_lanes(channels) values, zero beyond `channels`.
std::vector<PyramidLevel> build_pyramid(std::span<const float> coefficients, int support,
                                        int channels, int order) {
  const int lanes = texton_lanes(channels);
  std::vector<PyramidLevel> levels;
  std::vector<float> current(coefficients.begin(), coefficients.end());
  int size = support;
  const float centre = 0.5f * static_cast<float>(support - 1);
  for (int level = 0;; ++level) {
    PyramidLevel out;
    out.size = size;
    out.stride = size + 2 * kPadding;
    out.spacing = std::ldexp(1.0f, level);
    out.first_texel = 0.5f * (out.spacing - 1.0f) - centre;
    const float last_texel = out.first_texel + static_cast<float>(size - 1) * out.spacing;
    out.half_width = std::max(std::abs(out.first_texel), std::abs(last_texel)) +
                     0.5f * out.spacing * static_cast<float>(order + 1);
    out.coefficients.assign(static_cast<std::size_t>(out.stride) * out.stride * lanes, 0.0f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < channels; ++c)
          out.coefficients[(static_cast<std::size_t>(y + kPadding) * out.stride + x + kPadding) *
                               lanes +
                           c] = current[(static_cast<std::size_t>(y) * size + x) * channels + c];
    const std::size_t plane = static_cast<std::size_t>(out.stride) * out.stride;
    out.planes.resize(plane * lanes);
    for (std::size_t texel = 0; texel < plane; ++texel)
      for (std::size_t c = 0; c < static_cast<std::size_t>(lanes); ++c)
        out.planes[c * plane + texel] = out.coefficients[texel * lanes + c];
    levels.push_back(std::move(out));
    if (size == 1) break;
    const int next_size = (size + 1) / 2;
    std::vector<float> next(static_cast<std::size_t>(next_size) * next_size * channels, 0.0f);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < channels; ++c)
          next[(static_cast<std::size_t>(y / 2) * next_size + x / 2) * channels + c] +=
              0.25f * current[(static_cast<std::size_t>(y) * size + x) * channels + c];
    current = std::move(next);
    size = next_size;
  }
  return levels;
}

}  // namespace

TextonModel::TextonModel(int channels, int support, int order, double mean_impacts, int points,
                         std::vector<float> coefficients, std::vector<float> mean)
    : channels_(channels),
      support_(support),
      order_(order),
      mean_impacts_(mean_impacts),
      points_(points),
      coefficients_(std::move(coefficients)),
      mean_(std::move(mean)) {
  if (channels_ < 1 || channels_ > kMaxChannels)
    throw std::invalid_argument("texton: channels must be 1 to " + std::to_string(kMaxChannels));
  if (support_ < 1) throw std::invalid_argument("texton: support must be positive");
  if (std::none_of(kOrders.begin(), kOrders.end(),
                   [&](const ParamChoice& choice) { return choice.value == order_; }))
    throw std::invalid_argument("texton: order must be 0, 1, 3 or 5");
  if (!(mean_impacts_ > 0.0) || !std::isfinite(mean_impacts_))
    throw std::invalid_argument("texton: mni must be a positive number");
  if (std::none_of(kPointProcesses.begin(), kPointProcesses.end(),
                   [&](const ParamChoice& choice) { return choice.value == points_; }))
    throw std::invalid_argument("texton: points must be poisson (0) or balanced (1)");
  if (coefficients_.size() != static_cast<std::size_t>(support_) * support_ * channels_ ||
      mean_.size() != static_cast<std::size_t>(channels_))
    throw std::invalid_argument("texton: coefficient or mean array has the wrong size");

  pyramid_ = build_pyramid(coefficients_, support_, channels_, order_);
  // h = sum alpha(k) psi(y - k) has a square support of side r = S + k (section 3.3: MNI =
  // lambda r^2), so lambda = MNI / r^2.
  const double side = 2.0 * pyramid_.front().half_width;
  intensity_ = mean_impacts_ / (side * side);
  cell_size_ = kCellSizeFactor * side;
  if (balanced_points()) {
    // Cells a little larger than 0.6 r, so that each holds a whole number of points: then no
    // cell's count varies, and the impacts of a region vary with nothing but where they fall.
    const double whole = CellCount::whole_mean(intensity_ * cell_size_ * cell_size_);
    cell_size_ = std::sqrt(whole / intensity_);
    cell_count_ = CellCount::balanced(whole);
  } else {
    cell_count_ = CellCount::poisson(intensity_ * cell_size_ * cell_size_);
  }
  inverse_sqrt_intensity_ = static_cast<float>(1.0 / std::sqrt(intensity_));
  // E f = lambda * integral(h) = lambda * sum(alpha) since psi integrates to 1 (Proposition 1);
  // with signed impacts E f = 0 (section 7).
  constant_term_.resize(static_cast<std::size_t>(channels_));
  coefficient_sum_.resize(static_cast<std::size_t>(channels_));
  for (int c = 0; c < channels_; ++c) {
    double sum = 0.0;
    for (std::size_t i = static_cast<std::size_t>(c); i < coefficients_.size();
         i += static_cast<std::size_t>(channels_))
      sum += coefficients_[i];
    coefficient_sum_[c] = sum;
    const double expectation = balanced_points() ? 0.0 : intensity_ * sum;
    constant_term_[c] = static_cast<float>(mean_[c] - expectation / std::sqrt(intensity_));
  }
}

TextonModel TextonModel::from_record(const ModelRecord& record, const std::string& source) {
  // Scalars are checked against the analysis parameters' ranges (params.hpp).
  const auto read = [&](const char* name, double low, double high, bool integer) {
    return record.scalar_in(name, low, high, integer, source);
  };
  const auto read_param = [&](std::string_view name) {
    return record.param_scalar(name, kParams, source);
  };
  const int channels = static_cast<int>(read("channels", 1, kMaxChannels, true));
  const int support = static_cast<int>(read_param("support"));
  const int order = static_cast<int>(read_param("order"));
  const double mean_impacts = read_param("mni");
  // Files written before the choice existed were rendered with the paper's Poisson process.
  const int points = record.scalars.contains("points") ? static_cast<int>(read_param("points"))
                                                       : static_cast<int>(kPoissonPoints);
  const NamedArray& coefficients = record.array("texton", {support, support, channels}, source);
  const NamedArray& mean = record.array("mean", {channels}, source);
  if (!within_model_range(coefficients.values) || !within_model_range(mean.values))
    throw Error(ErrorCode::format, "'" + source +
                                       "' holds texton values that are not finite or beyond "
                                       "+-1e12; re-run `stochtex analyze`");
  try {
    return TextonModel(channels, support, order, mean_impacts, points, coefficients.values,
                       mean.values);
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid texton model (" + e.what() +
                                       "); re-run `stochtex analyze`");
  }
}

ModelRecord TextonModel::to_record(const ParamValues& params) const {
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  // The side used, also when the exemplar chose it (support = 0): `stochtex info` shows it.
  record.params["support"] = support_;
  record.scalars = {{"channels", channels_},
                    {"support", support_},
                    {"order", order_},
                    {"mni", mean_impacts_},
                    {"points", points_}};
  record.arrays.push_back({"texton", {support_, support_, channels_}, coefficients_});
  record.arrays.push_back({"mean", {channels_}, mean_});
  return record;
}

void TextonModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                           std::uint32_t seed, ImageView<float> out) const noexcept {
  with_order_and_channels(order_, channels_, [&]<int Order, int Channels>() {
    evaluate_typed<Order, Channels>(positions, footprints, seed, out);
  });
}

void TextonModel::evaluate_periodic(std::span<const Vec2d> positions,
                                    std::span<const Footprint> footprints, std::uint32_t seed,
                                    ImageView<float> out, Vec2d period) const noexcept {
  with_order_and_channels(order_, channels_, [&]<int Order, int Channels>() {
    evaluate_periodic_typed<Order, Channels>(positions, footprints, seed, out, period);
  });
}

template <int Order, int Channels>
void TextonModel::evaluate_periodic_typed(std::span<const Vec2d> positions,
                                          std::span<const Footprint> footprints, std::uint32_t seed,
                                          ImageView<float> out, Vec2d period) const noexcept {
  const PeriodicAxis x = periodic_axis(period.x, cell_size_);
  const PeriodicAxis y = periodic_axis(period.y, cell_size_);
  // The same intensity lambda in cells of another area: Poisson counts stay exact (the process
  // does not depend on how the plane is cut into cells); balanced counts of a mean that is no
  // longer whole vary by at most one point per chunk (core/cell_count.hpp).
  const double mean = intensity_ * x.size * y.size;
  const CellCount count = balanced_points() ? CellCount::balanced(mean) : CellCount::poisson(mean);
  CellCache cells(seed, count, balanced_points());
  const int top_level = static_cast<int>(pyramid_.size()) - 1;
  for (std::size_t index = 0; index < positions.size(); ++index) {
    const FilterSetup filter =
        footprints.empty() ? FilterSetup{} : filter_setup(footprints[index], top_level);
    const FilteredTexton<Order, Channels> texton(pyramid_, filter);
    float acc[Channels] = {};
    sum_impulses_periodic<Order, Channels>(reduce_position(positions[index], period), texton, x, y,
                                           cells, pyramid_.data(), acc);
    const auto px = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto py = static_cast<int>(index / static_cast<std::size_t>(out.width));
    for (int c = 0; c < channels_; ++c)
      out.at(px, py, c) =
          texton.output(acc[c], inverse_sqrt_intensity_, constant_term_[c], mean_[c]);
  }
}

void TextonModel::evaluate_surface(std::span<const SurfacePoint> points, double surface_mni,
                                   std::uint32_t seed, ImageView<float> out) const noexcept {
  with_order_and_channels(order_, channels_, [&]<int Order, int Channels>() {
    evaluate_surface_typed<Order, Channels>(points, surface_mni, seed, out);
  });
}

template <int Order, int Channels>
void TextonModel::evaluate_typed(std::span<const Vec2d> positions,
                                 std::span<const Footprint> footprints, std::uint32_t seed,
                                 ImageView<float> out) const noexcept {
  CellCache cells(seed, cell_count_, balanced_points());
  shot_noise<Order, Channels>(
      positions, footprints, pyramid_, cell_size_, cells, OneTexton{pyramid_.data()},
      [&](std::size_t index, const FilteredTexton<Order, Channels>& texton,
          const float(&acc)[Channels]) {
        const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
        const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
        // (f - E f) / sqrt(lambda) + mean, eq. (2). Channels is the lane count
        // (texton_lanes): the channels beyond the model's are zero padding.
        for (int c = 0; c < channels_; ++c)
          out.at(x, y, c) =
              texton.output(acc[c], inverse_sqrt_intensity_, constant_term_[c], mean_[c]);
      });
}

SurfaceConstants TextonModel::surface_constants(double surface_mni) const {
  // Surface noise (section 6): a 3-D Poisson process of intensity lambda = MNI / r^3, impulses
  // within r/2 of the tangent plane weighted by (1 - 2 |t| / r)+ and carrying the texton in the
  // frame (u1, u2). Proposition 3: mean lambda r/2 sum(alpha), variance lambda r/3 integral(h^2),
  // so g = (f - lambda r/2 sum(alpha)) / sqrt(lambda r/3) has the mean and variance of the planar
  // normalised noise (eq. 2) whatever the MNI. Cells of side 0.6 r as in 2-D (section 8).
  const double side = 2.0 * pyramid_.front().half_width;
  const double intensity = surface_mni / (side * side * side);
  SurfaceConstants constants;
  constants.cell_size = kCellSizeFactor * side;
  constants.count = CellCount::poisson(intensity * constants.cell_size * constants.cell_size *
                                       constants.cell_size);
  const double scale = 1.0 / std::sqrt(intensity * side / 3.0);
  constants.scale = static_cast<float>(scale);
  for (int c = 0; c < channels_; ++c)
    constants.constant[c] =
        static_cast<float>(mean_[c] - intensity * 0.5 * side * coefficient_sum_[c] * scale);
  constants.depth = static_cast<float>(0.5 * side);
  constants.inverse_depth = 1.0f / constants.depth;
  return constants;
}

template <int Order, int Channels>
void TextonModel::evaluate_surface_typed(std::span<const SurfacePoint> points, double surface_mni,
                                         std::uint32_t seed, ImageView<float> out) const noexcept {
  const SurfaceConstants constants = surface_constants(surface_mni);
  const int top_level = static_cast<int>(pyramid_.size()) - 1;
  for (std::size_t index = 0; index < points.size(); ++index) {
    const SurfacePoint& p = points[index];
    const SurfaceFrame frame = surface_frame(p);
    const FilteredTexton<Order, Channels> texton(
        pyramid_, filter_setup(tangent_footprint(p, frame), top_level));
    float acc[Channels] = {};
    for_each_surface_impulse(p, frame, texton.reach(), constants.depth, constants.cell_size,
                             constants.count, seed, [&](CounterRng&, float t, float z1, float z2) {
                               const float weight = 1.0f - std::abs(t) * constants.inverse_depth;
                               if (weight > 0.0f) texton.add(pyramid_.data(), z1, z2, weight, acc);
                             });
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    for (int c = 0; c < channels_; ++c)
      out.at(x, y, c) = texton.output(acc[c], constants.scale, constants.constant[c], mean_[c]);
  }
}

}  // namespace stochtex::texton
