#pragma once
// Bandwidth-quantised Gabor noise (section 4, eq. 5): for each colour channel of the synthesis
// colour space, a sparse set of Gaussians in frequency, each a symmetric pair with a frequency
// omega, one of the quantised bandwidths a_b and a variance; the colour transform back to the
// exemplar's channels (section 7) and the mean. Evaluation (section 6) runs one Poisson grid per
// (channel, bandwidth) and draws kernel parameters with the alias method.

#include <cstdint>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/cell_count.hpp"
#include "model/model_record.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::gabor {

// Quantised bandwidths a_b = 2^-b sqrt(pi / (2 ln 2)) (section 4.3), b = 0 .. kMaxBands - 1, in
// cycles per exemplar pixel: the spectral Gaussian of band b has a full width at half maximum of
// 2^-b cycles per pixel, i.e. 2^-b M frequency bins of an M-pixel exemplar.
inline constexpr int kMaxBands = 16;
double bandwidth(int band);

// A model holds at most this many Gaussians (a 1024^2 RGBA exemplar fitted at full density):
// loading refuses more, so a file cannot ask for more memory or set-up work than analysis makes.
inline constexpr std::size_t kMaxGaussians = std::size_t{1} << 22;

// Constants of the evaluator (GaborModel::evaluate), shared with its GLSL twin (gl_twin.hpp).
// pi as a float, for the kernel's truncation test: the kernel's support ends where its envelope
// exp(-e) falls to e^-pi (r = 1/a, section 6.1).
inline constexpr double kPi = std::numbers::pi;
inline constexpr auto kPiF = static_cast<float>(kPi);
// The kernel fades out before that cut instead of jumping there by e^-pi of its amplitude (our
// addition; docs/methods/gabor.md, "Kernel taper"): it is multiplied by smoothstep(t) = t^2 (3 -
// 2t) with t = min((pi - e) kTaperScale, 1), which changes only the envelope's last 1 / kTaperScale
// before the cut (values below e^-(pi - 1/8) = 4.9 % of the peak; a wider taper, 1/2, moved the
// fit's spectrum measurably: moss_ground_512's spectral error ratio +0.02). The noise is then
// continuous with a continuous gradient, and a kernel that rounding puts just inside or just
// outside the support (a float position against a double one) changes a sample by float
// rounding, not by a jump.
inline constexpr float kTaperScale = 8.0f;
// A grid whose least attenuated Gaussian is scaled by less than e^-12 (6e-6) by the footprint's
// filter contributes nothing visible and is skipped.
inline constexpr double kNegligibleAttenuation = 12.0;
// Footprints wider than the kernel make it cover more cells; the process is then thinned by 4 per
// level (cells twice as wide, a quarter of the intensity, amplitudes doubled so the variance is
// unchanged) so that the cost per sample stays bounded. At most this many levels; wider
// footprints make the grid vanish.
inline constexpr int kMaxLevels = 40;
// The surface_mni at which surface noise has, at a point, tent weights summing on average to
// the planar noise's impulse count (GaborModel::evaluate_surface): the paper's 60 (texton paper
// section 6) for a planar MNI of 30.
inline constexpr double kSurfaceMniReference = 60.0;
// Variance per axis of a box of one pixel.
inline constexpr double kPixelVariance = 1.0 / 12.0;

// One symmetric pair of Gaussians of eq. (6): frequency +-omega in cycles per pixel, bandwidth
// a_band, variance sigma^2 = K^2 / (4 a^2) of its Gabor noise.
struct GaussianComponent {
  int channel = 0;
  int band = 0;
  float frequency_x = 0;
  float frequency_y = 0;
  float variance = 0;
};

// Values reported by the analysis, kept in the model file so that `stochtex info` shows them.
struct FitReport {
  double sparseness = 0;                  // Gaussians / (channels x pixels) (section 5.1)
  double fit_error = 0;                   // ||S_n(alpha) - S_ex||_2 / ||S_ex||_2 over all channels
  double offdiagonality_independent = 0;  // J(T) of eq. (10) for the three colour spaces
  double offdiagonality_pca = 0;
  double offdiagonality_rgb = 0;
};

class GaborModel {
 public:
  static constexpr std::string_view kMethodName = "gabor";

  // `mixing` (channels x channels, row-major) maps the synthesis channels back to the exemplar's:
  // colour = mean + mixing * noise. Throws std::invalid_argument on inconsistent data.
  GaborModel(int channels, double impulses, int colour_space,
             std::vector<GaussianComponent> gaussians, std::vector<float> mixing,
             std::vector<float> mean, const FitReport& report);

  static GaborModel from_record(const ModelRecord& record, const std::string& source);
  ModelRecord to_record(const ParamValues& params) const;

  int channels() const { return channels_; }
  double impulses() const { return impulses_; }
  int colour_space() const { return colour_space_; }
  const std::vector<GaussianComponent>& gaussians() const { return gaussians_; }
  std::span<const float> mixing() const { return mixing_; }
  std::span<const float> mean() const { return mean_; }
  const FitReport& report() const { return report_; }

  // For inspection (`stochtex info --export` writes it as an image): the fourth root of the
  // fitted power spectrum of each synthesis channel on kPreviewSide^2 frequencies, DC centred,
  // mapped to [-1, 1] (the export maps [-1, 1] to black..white). Derived from the Gaussians; the
  // model file carries it and loading ignores it.
  static constexpr int kPreviewSide = 128;
  std::vector<float> spectrum_preview() const;

  // Bandwidth-quantised Gabor noise (eq. 5) per synthesis channel, mixed back to colour. Each
  // kernel is attenuated analytically by the footprint's Gaussian pixel filter. noexcept, no
  // allocation.
  void evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                std::uint32_t seed, ImageView<float> out) const noexcept;

  // evaluate() for a field of model-space period `period` (core/periodic.hpp): each grid's cells
  // (at each thinning level) of side period / round(period / side) per axis, holding the same
  // intensity. The scalar loop, for periodic renders (docs/render.md). noexcept.
  void evaluate_periodic(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                         std::uint32_t seed, ImageView<float> out, Vec2d period) const noexcept;

  // Surface Gabor noise (section 9.1; docs/surface.md) at each surface point: the impulse
  // process of texton surface noise, surface_mni / kSurfaceMniReference times as dense as the
  // planar one, each kernel in the point's tangent frame and filtered by the footprint projected
  // on the tangent plane. Same mean and variance as evaluate(). noexcept, no allocation.
  void evaluate_surface(std::span<const SurfacePoint> points, double surface_mni,
                        std::uint32_t seed, ImageView<float> out) const noexcept;

  // One Poisson grid of the multi-grid evaluation (section 6.1): the Gaussians of one channel
  // and one bandwidth, with their alias table (section 6.2). Public for tests.
  struct Grid {
    int channel = 0;
    int band = 0;
    float bandwidth = 0;      // a_b
    double radius = 0;        // r_b = 1 / a_b, where the kernel envelope falls to e^-pi
    double cell_size = 0;     // side of the grid cells
    float amplitude = 0;      // kernel amplitude K / sqrt(lambda p) of eq. (5), the same for all
    std::uint32_t first = 0;  // range of the grid's Gaussians in the flat arrays
    std::uint32_t count = 0;
    float min_frequency_squared = 0;
    double impulses = 0;  // N_b, this grid's share of the impulse budget
    CellCount cell_count;
  };
  const std::vector<Grid>& grids() const { return grids_; }
  // The 3-D process of one grid's surface noise at one MNI (evaluate_surface, and its GLSL twin in
  // gl_data.cpp): the side of its cubic cells and their impulse count, at thinning level 0.
  struct SurfaceGrid {
    double cell_size = 0;
    CellCount count;
  };
  static SurfaceGrid surface_grid(const Grid& grid, double surface_mni);
  // The amplitude gain of surface noise at this MNI: the planar noise's variance.
  static double surface_amplitude_gain(double surface_mni);
  // The Gaussians' frequencies in grid order (grid.first + i), for the GLSL twin (gl_data.cpp).
  std::span<const float> frequency_x() const { return frequency_x_; }
  std::span<const float> frequency_y() const { return frequency_y_; }
  std::span<const float> alias_probability() const { return alias_probability_; }
  std::span<const std::uint32_t> alias_index() const { return alias_index_; }

 private:
  // colour = mean + mixing * noise for the first `count` pixels of `out`, in place.
  void mix_to_colour(std::size_t count, ImageView<float> out) const noexcept;

  int channels_;
  double impulses_;
  int colour_space_;
  std::vector<GaussianComponent> gaussians_;
  std::vector<float> mixing_;
  std::vector<float> mean_;
  FitReport report_;

  // Derived at construction: Gaussians sorted by grid, flat for the evaluator.
  std::vector<Grid> grids_;
  std::vector<float> frequency_x_;
  std::vector<float> frequency_y_;
  std::vector<float> alias_probability_;
  std::vector<std::uint32_t> alias_index_;
};

}  // namespace stochtex::gabor
