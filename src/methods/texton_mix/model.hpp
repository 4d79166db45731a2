#pragma once
// Texton noise mixing model (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017, section 7): R
// textons of the optimal-transport barycentres between the Gaussian models of two exemplars A and
// B, their two means, and the mixing field rho(x) in [0, 1] that chooses, at each impulse centre,
// the texton of its region. Data are flat arrays (docs/design.md §4).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "methods/texton/model.hpp"
#include "methods/texton_mix/params.hpp"
#include "model/model_record.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::texton_mix {

// rho(x): a linear ramp along a unit direction (figure 5), or a grey mask over model space.
class MixField {
 public:
  // The ramp: rho = clamp((<x, d> - start) / (end - start), 0, 1), d = direction / |direction|.
  MixField(double start, double end, double direction_x, double direction_y);
  // The mask: values in [0, 1], width x height, row-major; mask pixel (i, j) is centred on model
  // position ((i + 0.5) s, (j + 0.5) s); bilinear, clamped to the edge pixels beyond.
  MixField(std::vector<float> mask, int width, int height, double scale);

  bool is_mask() const { return mask_width_ > 0; }
  std::span<const float> mask() const { return mask_; }
  int mask_width() const { return mask_width_; }
  int mask_height() const { return mask_height_; }
  // The ramp's and the mask's mapping, for the GLSL twin (texton_mix/gl_data.cpp).
  double ramp_start() const { return start_; }
  double inverse_length() const { return inverse_length_; }
  double unit_x() const { return unit_x_; }
  double unit_y() const { return unit_y_; }
  double inverse_scale() const { return inverse_scale_; }

  double rho(double x, double y) const noexcept;

 private:
  double start_ = 0;
  double inverse_length_ = 0;
  double unit_x_ = 1;
  double unit_y_ = 0;
  std::vector<float> mask_;
  int mask_width_ = 0;
  int mask_height_ = 0;
  double inverse_scale_ = 1;
};

class TextonMixModel {
 public:
  static constexpr std::string_view kMethodName = "texton_mix";

  // `textons` is steps x support x support x channels (texton k for rho = k / (steps - 1));
  // `mean_a`, `mean_b` have `channels` values.
  TextonMixModel(const Params& params, int channels, int support, std::vector<float> textons,
                 std::vector<float> mean_a, std::vector<float> mean_b, MixField field);

  static TextonMixModel from_record(const ModelRecord& record, const std::string& source);
  ModelRecord to_record(const ParamValues& params) const;

  int channels() const { return channels_; }
  int support() const { return support_; }
  int steps() const { return params_.steps; }
  std::span<const float> textons() const { return textons_; }
  const texton::TextonModel& texton(int step) const {
    return shapes_[static_cast<std::size_t>(step)];
  }
  const MixField& field() const { return field_; }
  std::span<const float> mean_a() const { return mean_a_; }
  std::span<const float> mean_b() const { return mean_b_; }

  // The mixed texton noise f / sqrt(lambda) + (1 - rho(x)) mean_a + rho(x) mean_b at each
  // position, filtered by the footprint as texton noise is. noexcept, no allocation.
  void evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                std::uint32_t seed, ImageView<float> out) const noexcept;

 private:
  template <int Order, int Channels>
  void evaluate_typed(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                      std::uint32_t seed, ImageView<float> out) const noexcept;

  Params params_;
  int channels_;
  int support_;
  std::vector<float> textons_;
  std::vector<float> mean_a_;
  std::vector<float> mean_b_;
  MixField field_;
  // One texton noise model per step (zero mean): its pyramid and shot-noise constants.
  std::vector<texton::TextonModel> shapes_;
};

}  // namespace stochtex::texton_mix
