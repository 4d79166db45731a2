#include "methods/texton_mix/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "methods/texton/evaluate.hpp"
#include "methods/texton/simd.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"

namespace stochtex::texton_mix {

MixField::MixField(double start, double end, double direction_x, double direction_y)
    : start_(start) {
  const double length = std::hypot(direction_x, direction_y);
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("texton_mix: the ramp direction must be a nonzero vector");
  if (!(end != start) || !std::isfinite(end - start))
    throw std::invalid_argument("texton_mix: ramp_end must differ from ramp_start");
  inverse_length_ = 1.0 / (end - start);
  unit_x_ = direction_x / length;
  unit_y_ = direction_y / length;
}

MixField::MixField(std::vector<float> mask, int width, int height, double scale)
    : mask_(std::move(mask)),
      mask_width_(width),
      mask_height_(height),
      inverse_scale_(1.0 / scale) {
  if (width < 1 || height < 1 || mask_.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("texton_mix: the mask array has the wrong size");
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw std::invalid_argument("texton_mix: mask_scale must be a positive number");
  if (std::any_of(mask_.begin(), mask_.end(), [](float v) { return !(v >= 0.0f && v <= 1.0f); }))
    throw std::invalid_argument("texton_mix: mask values must lie in [0, 1]");
}

double MixField::rho(double x, double y) const noexcept {
  if (!is_mask())
    return std::clamp((x * unit_x_ + y * unit_y_ - start_) * inverse_length_, 0.0, 1.0);
  // Bilinear between pixel centres, clamped to the edge pixels.
  const double u = std::clamp(x * inverse_scale_ - 0.5, 0.0, mask_width_ - 1.0);
  const double v = std::clamp(y * inverse_scale_ - 0.5, 0.0, mask_height_ - 1.0);
  const int i = std::min(static_cast<int>(u), mask_width_ - 1);
  const int j = std::min(static_cast<int>(v), mask_height_ - 1);
  const int i1 = std::min(i + 1, mask_width_ - 1);
  const int j1 = std::min(j + 1, mask_height_ - 1);
  const double s = u - i;
  const double t = v - j;
  const auto at = [&](int a, int b) {
    return static_cast<double>(mask_[static_cast<std::size_t>(b) * mask_width_ + a]);
  };
  return (1.0 - t) * ((1.0 - s) * at(i, j) + s * at(i1, j)) +
         t * ((1.0 - s) * at(i, j1) + s * at(i1, j1));
}

TextonMixModel::TextonMixModel(const Params& params, int channels, int support,
                               std::vector<float> textons, std::vector<float> mean_a,
                               std::vector<float> mean_b, MixField field)
    : params_(params),
      channels_(channels),
      support_(support),
      textons_(std::move(textons)),
      mean_a_(std::move(mean_a)),
      mean_b_(std::move(mean_b)),
      field_(std::move(field)) {
  if (params_.steps < 2) throw std::invalid_argument("texton_mix: steps must be at least 2");
  const std::size_t texton_size = static_cast<std::size_t>(support) * support * channels;
  if (channels < 1 || channels > 4 || support < 1 ||
      textons_.size() != texton_size * static_cast<std::size_t>(params_.steps) ||
      mean_a_.size() != static_cast<std::size_t>(channels) || mean_b_.size() != mean_a_.size())
    throw std::invalid_argument("texton_mix: a texton or mean array has the wrong size");
  // Each step as a texton noise model of zero mean: its pyramid (section 5) and its shot-noise
  // constants, which depend on support, order and MNI only and so are the same for every step.
  // The mixing keeps the paper's Poisson process (its impulses carry their own signs).
  shapes_.reserve(static_cast<std::size_t>(params_.steps));
  for (int step = 0; step < params_.steps; ++step) {
    const auto first = textons_.begin() + static_cast<std::ptrdiff_t>(texton_size * step);
    shapes_.emplace_back(
        channels, support, params_.texton.order, params_.texton.mni, texton::kPoissonPoints,
        std::vector<float>(first, first + static_cast<std::ptrdiff_t>(texton_size)),
        std::vector<float>(static_cast<std::size_t>(channels), 0.0f));
  }
}

TextonMixModel TextonMixModel::from_record(const ModelRecord& record, const std::string& source) {
  Params params;
  for (const auto& field : kFields)
    field.set(params, record.param_scalar(field.info.name, kParams, source));
  const int channels = static_cast<int>(record.scalar_in("channels", 1, 4, true, source));
  const int support =
      static_cast<int>(record.scalar_in("support", 1, params.texton.support, true, source));
  const bool mask = record.scalar_in("mask", 0, 1, true, source) != 0.0;
  const NamedArray& textons =
      record.array("textons", {params.steps, support, support, channels}, source);
  const NamedArray& mean_a = record.array("mean_a", {channels}, source);
  const NamedArray& mean_b = record.array("mean_b", {channels}, source);
  if (!within_model_range(textons.values) || !within_model_range(mean_a.values) ||
      !within_model_range(mean_b.values))
    throw Error(ErrorCode::format, "'" + source +
                                       "' holds texton values that are not finite or beyond "
                                       "+-1e12; re-run `stochtex mix`");
  try {
    MixField field = [&] {
      if (!mask)
        return MixField(params.ramp_start, params.ramp_end, params.direction_x, params.direction_y);
      const auto width = static_cast<int>(record.scalar_in("mask_width", 1, 1 << 14, true, source));
      const auto height =
          static_cast<int>(record.scalar_in("mask_height", 1, 1 << 14, true, source));
      return MixField(record.array("mask", {height, width}, source).values, width, height,
                      params.mask_scale);
    }();
    return TextonMixModel(params, channels, support, textons.values, mean_a.values, mean_b.values,
                          std::move(field));
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid texton_mix model (" + e.what() +
                                       "); re-run `stochtex mix`");
  }
}

ModelRecord TextonMixModel::to_record(const ParamValues& params) const {
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  record.scalars = param_values(kFields, params_);
  record.scalars["channels"] = channels_;
  record.scalars["support"] = support_;
  record.scalars["mask"] = field_.is_mask() ? 1 : 0;
  record.arrays.push_back({"textons", {params_.steps, support_, support_, channels_}, textons_});
  record.arrays.push_back({"mean_a", {channels_}, mean_a_});
  record.arrays.push_back({"mean_b", {channels_}, mean_b_});
  if (field_.is_mask()) {
    record.scalars["mask_width"] = field_.mask_width();
    record.scalars["mask_height"] = field_.mask_height();
    record.arrays.push_back({"mask",
                             {field_.mask_height(), field_.mask_width()},
                             std::vector<float>(field_.mask().begin(), field_.mask().end())});
  }
  return record;
}

void TextonMixModel::evaluate(std::span<const Vec2d> positions,
                              std::span<const Footprint> footprints, std::uint32_t seed,
                              ImageView<float> out) const noexcept {
  // Texton noise mixing takes 1 to 4 channels (its registry row's default): no wider loops.
  texton::with_order_and_channels<4>(
      params_.texton.order, channels_, [&]<int Order, int Channels>() {
        evaluate_typed<Order, Channels>(positions, footprints, seed, out);
      });
}

template <int Order, int Channels>
void TextonMixModel::evaluate_typed(std::span<const Vec2d> positions,
                                    std::span<const Footprint> footprints, std::uint32_t seed,
                                    ImageView<float> out) const noexcept {
  const texton::TextonModel& shape = shapes_.front();
  const double cell_size = shape.cell_size();
  const double last_step = params_.steps - 1;
  texton::CellCache cells(seed, shape.cell_count());
  // Section 7: impulse x_j uses the texton of the region its centre falls in (rho(x_j) rounded to
  // the nearest of the R steps) with a random sign eps_j in {-1, +1}, drawn from the cell's own
  // stream so that the points are texton noise's, whatever the field.
  const auto region_texton = [&](std::int64_t cell_x, std::int64_t cell_y, std::uint32_t index,
                                 float u, float v) {
    const double centre_x = (static_cast<double>(cell_x) + u) * cell_size;
    const double centre_y = (static_cast<double>(cell_y) + v) * cell_size;
    const auto step =
        static_cast<std::size_t>(std::lround(field_.rho(centre_x, centre_y) * last_step));
    return texton::Impulse{shapes_[step].pyramid().data(),
                           texton::impulse_sign(cell_x, cell_y, index, seed)};
  };
  texton::shot_noise<Order, Channels>(
      positions, footprints, shape.pyramid(), cell_size, cells, region_texton,
      [&](std::size_t index, const texton::FilteredTexton<Order, Channels>& texton,
          const float(&acc)[Channels]) {
        const Vec2d p = positions[index];
        // The mean interpolated with the field at the evaluation point (section 7).
        const auto rho = static_cast<float>(field_.rho(p.x, p.y));
        const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
        const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
        for (int c = 0; c < Channels; ++c)
          out.at(x, y, c) = (1.0f - rho) * mean_a_[c] + rho * mean_b_[c] +
                            texton.fade() * acc[c] * shape.inverse_sqrt_intensity();
      });
}

}  // namespace stochtex::texton_mix
