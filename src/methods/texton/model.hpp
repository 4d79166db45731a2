#pragma once
// Texton noise model: the texton interpolation coefficients alpha (eq. 3), their prefiltered
// pyramid (section 5), the exemplar mean and the shot-noise constants (sections 3.3, 8).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/cell_count.hpp"
#include "methods/texton/params.hpp"
#include "model/model_record.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::texton {

// The constants of texton surface noise at one MNI (section 6, Proposition 3), shared by the CPU
// evaluator (evaluate_surface) and its GLSL twin (gl_data.cpp): the 3-D process's cell side,
// impulse count per cell and tent half-depth r/2, and the normalisation
// (f - lambda r/2 sum(alpha)) / sqrt(lambda r/3) + mean = f * scale + constant.
struct SurfaceConstants {
  double cell_size = 0;
  CellCount count;
  float depth = 0;
  float inverse_depth = 0;
  float scale = 0;
  std::array<float, kMaxChannels> constant = {};  // per channel, zero beyond the model's
};

// The evaluator's accumulator width for `channels` channels: the count itself up to 4, then the
// next multiple of 4 (8, 12, 16), so that 1 to kMaxChannels channels take 7 unrolled loops. The
// pyramid stores this many values per texel, zero beyond the model's channels.
constexpr int texton_lanes(int channels) {
  return channels <= 4 ? channels : (channels + 3) / 4 * 4;
}

// Texels of zero around each pyramid level: order k reads up to k + 1 texels outside a level near
// the support border (k <= 5); with 8 the evaluator never tests bounds, even after float rounding.
inline constexpr int kPadding = 8;

struct PyramidLevel {
  int size = 0;           // texels per side
  int stride = 0;         // size + 2 * kPadding, texels per padded row
  float spacing = 1.0f;   // 2^level: distance between texels in exemplar pixels
  float first_texel = 0;  // position of texel 0 relative to the texton centre, exemplar pixels
  float half_width = 0;   // the kernel h_level vanishes where |y|_inf >= half_width
  std::vector<float> coefficients;  // padded, (stride x stride x texton_lanes(channels))
  std::vector<float> planes;  // the same texels channel by channel: lanes planes of stride x stride
};

class TextonModel {
 public:
  static constexpr std::string_view kMethodName = "texton";

  // `coefficients` is support x support x channels, row-major (the output of Algorithm 1 after the
  // colour covariance correction); `mean` has `channels` values; `points` a PointProcess
  // (params.hpp).
  TextonModel(int channels, int support, int order, double mean_impacts, int points,
              std::vector<float> coefficients, std::vector<float> mean);

  static TextonModel from_record(const ModelRecord& record, const std::string& source);
  ModelRecord to_record(const ParamValues& params) const;

  int channels() const { return channels_; }
  // Values per texel of the pyramid: texton_lanes(channels()).
  int lanes() const { return texton_lanes(channels_); }
  int support() const { return support_; }
  int order() const { return order_; }
  double mean_impacts() const { return mean_impacts_; }
  int points() const { return points_; }
  // Whether the points are balanced (params.hpp): balanced counts on a shifted lattice, each
  // impact with a random sign (section 7's marks).
  bool balanced_points() const { return points_ == kBalancedPoints; }
  std::span<const float> coefficients() const { return coefficients_; }
  std::span<const float> mean() const { return mean_; }
  const std::vector<PyramidLevel>& pyramid() const { return pyramid_; }
  double intensity() const { return intensity_; }
  // Shot-noise constants, for the GLSL twin of the evaluator (gl_data.cpp).
  double cell_size() const { return cell_size_; }
  const CellCount& cell_count() const { return cell_count_; }
  float inverse_sqrt_intensity() const { return inverse_sqrt_intensity_; }
  std::span<const float> constant_term() const { return constant_term_; }

  // Normalised texton noise (f - E f) / sqrt(lambda) + mean (eq. 2; E f = lambda sum(alpha) for
  // the Poisson process, 0 with signed impacts) at each position, filtered by the footprint when it
  // is wider than a texel. noexcept, no allocation.
  void evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                std::uint32_t seed, ImageView<float> out) const noexcept;

  // evaluate() for a field of model-space period `period` (core/periodic.hpp): cells of side
  // period / round(period / cell_size()) per axis holding the same intensity. The scalar loop, for
  // periodic renders (docs/render.md). noexcept, no allocation.
  void evaluate_periodic(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                         std::uint32_t seed, ImageView<float> out, Vec2d period) const noexcept;

  // Normalised surface noise g^s (section 6, Proposition 3) + mean at each surface point
  // (docs/surface.md): a 3-D Poisson process of surface_mni impulses per r^3 cube, the texton in
  // each point's tangent frame, filtered by the footprint projected on the tangent plane.
  // noexcept, no allocation.
  void evaluate_surface(std::span<const SurfacePoint> points, double surface_mni,
                        std::uint32_t seed, ImageView<float> out) const noexcept;
  // The constants evaluate_surface uses at this MNI (its GLSL twin's too).
  SurfaceConstants surface_constants(double surface_mni) const;

 private:
  template <int Order, int Channels>
  void evaluate_periodic_typed(std::span<const Vec2d> positions,
                               std::span<const Footprint> footprints, std::uint32_t seed,
                               ImageView<float> out, Vec2d period) const noexcept;
  template <int Order, int Channels>
  void evaluate_typed(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                      std::uint32_t seed, ImageView<float> out) const noexcept;
  template <int Order, int Channels>
  void evaluate_surface_typed(std::span<const SurfacePoint> points, double surface_mni,
                              std::uint32_t seed, ImageView<float> out) const noexcept;

  int channels_;
  int support_;
  int order_;
  double mean_impacts_;
  int points_;
  std::vector<float> coefficients_;
  std::vector<float> mean_;

  // Derived at construction.
  std::vector<PyramidLevel> pyramid_;
  double intensity_ = 0;  // lambda = MNI / r^2, r the side of h's support (section 3.3)
  double cell_size_ = 0;  // a = 0.6 r (section 8); a little more for balanced points
  CellCount cell_count_;
  float inverse_sqrt_intensity_ = 0;
  std::vector<float> constant_term_;     // mean - E f / sqrt(lambda), per channel
  std::vector<double> coefficient_sum_;  // sum(alpha), per channel
};

}  // namespace stochtex::texton
