#include "methods/gabor/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <span>
#include <thread>
#include <vector>

#include "core/colour_statistics.hpp"
#include "core/parallel.hpp"
#include "methods/gabor/colour_space.hpp"
#include "methods/gabor/dictionary.hpp"
#include "methods/gabor/eigen_matrix.hpp"
#include "methods/gabor/fit.hpp"
#include "methods/gabor/params.hpp"
#include "spectral/periodic.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gabor {
namespace {

// Lags |xi|_inf <= 4 of the lagged correlation matrices (section 7): 81 matrices. Longer lags of a
// 128^2 exemplar carry mostly estimation noise.
constexpr int kMaxLag = 4;
// The channels' fits run in parallel, each with its own dictionary and iterates (~370 bytes a
// pixel at 256², measured): at most this many at once, so that the analysis memory row
// (registry_row) bounds a material of up to kMaxChannels channels on any core count (9 channels
// at 256², 4 fits in flight: 1852 bytes a pixel against the row's 2540; 9 in flight: 3325).
// Exemplars of 1 to 4 channels fit every channel at once where the cores allow, as before.
constexpr int kMaxFitsInFlight = 4;
// narrowest = 0 (automatic): the first fit's dictionary stops at bands of this FWHM in bins. The
// l2 fit of a feature narrower than the dictionary's Gaussians spreads it and inflates its mass
// (a one-bin peak fitted by one Gaussian of any width gets twice its mass): when the first fit's
// variance exceeds the periodogram's by more than kAutoVarianceExcess, it is redone down to one
// bin (measured: wood_planks_256 1.31, the 512² colour exemplars 1.00-1.08 on the decimated plane
// below, paving_height_grey_512 1.13, the diffuse 256² exemplars 0.99-1.03).
// The coarse fit costs about kAutoCoarseShare of the full one (its bands are all sub-sampled).
constexpr int kAutoNarrowest = 4;
constexpr double kAutoVarianceExcess = 1.15;
constexpr double kAutoCoarseShare = 0.25;
// The coarse fit's bands are at least kAutoNarrowest bins wide, smooth at the exemplar's bin: on
// an exemplar larger than kCoarsePlane bins a side, it runs on the periodogram decimated by a
// power of two `factor` <= kAutoNarrowest (decimate_spectrum) that leaves at least kCoarsePlane
// bins a side, its narrowest band kAutoNarrowest / factor bins there: the same Gaussians, at the
// same frequencies, fitted on factor^2 fewer bins.
constexpr int kCoarsePlane = 256;

int coarse_fit_factor(int width, int height) {
  int factor = 1;
  while (2 * factor <= kAutoNarrowest && width % (2 * factor) == 0 && height % (2 * factor) == 0 &&
         std::min(width, height) / (2 * factor) >= kCoarsePlane)
    factor *= 2;
  return factor;
}

}  // namespace

GaborModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t /*seed*/,
                   const std::function<void(double)>& progress) {
  const int width = exemplar.width;
  const int height = exemplar.height;
  const int channels = exemplar.channels;
  const auto colour_space = static_cast<int>(params.colour_space);
  FitOptions options;
  options.kappa = params.kappa;
  options.max_iterations = params.iterations;

  // The periodic component (section 3.2, [Moisan 2011]): no cross artefact in its spectrum.
  const ImageF periodic = periodic_component(exemplar);
  const std::size_t pixels = periodic.pixel_count();
  std::vector<float> mean;
  for (const double value : channel_means(periodic.view()))
    mean.push_back(static_cast<float>(value));
  std::vector<std::vector<float>> centred(static_cast<std::size_t>(channels),
                                          std::vector<float>(pixels));
  for (int c = 0; c < channels; ++c) {
    for (std::size_t i = 0; i < pixels; ++i)
      centred[c][i] = periodic.pixels()[i * channels + c] - mean[c];
  }

  // Colour space (section 7): T maps centred colours to the synthesis channels.
  FitReport report;
  Matrix transform(static_cast<std::size_t>(channels) * channels, 0.0);
  for (int c = 0; c < channels; ++c) transform[static_cast<std::size_t>(c) * channels + c] = 1.0;
  if (channels > 1) {
    const std::vector<Matrix> correlations =
        lagged_correlations(centred, width, height, std::min({kMaxLag, width / 2, height / 2}));
    const Matrix independent = joint_diagonalizer(correlations, channels);
    const Matrix pca = principal_axes(correlations.front(), channels);
    report.offdiagonality_independent = off_diagonality(independent, correlations, channels);
    report.offdiagonality_pca = off_diagonality(pca, correlations, channels);
    report.offdiagonality_rgb = off_diagonality(transform, correlations, channels);
    if (colour_space == static_cast<int>(ColourSpace::independent)) transform = independent;
    if (colour_space == static_cast<int>(ColourSpace::pca)) transform = pca;
  }
  const Eigen::MatrixXd forward = to_eigen(transform, channels);
  const Eigen::MatrixXd backward = forward.inverse();
  std::vector<float> mixing(static_cast<std::size_t>(channels) * channels);
  for (int i = 0; i < channels; ++i)
    for (int j = 0; j < channels; ++j)
      mixing[static_cast<std::size_t>(i) * channels + j] = static_cast<float>(backward(i, j));
  if (!std::all_of(mixing.begin(), mixing.end(), [](float v) { return std::isfinite(v); }))
    throw Error(ErrorCode::numerical, "gabor: the colour transform is singular");

  // Each synthesis channel's spectrum is fitted on its own (independent channel synthesis), the
  // channels in parallel, each with its own dictionary (the operators keep work buffers). Each fit
  // is the same whatever the thread count.
  std::vector<std::vector<float>> targets(static_cast<std::size_t>(channels));
  for (int k = 0; k < channels; ++k) {
    std::vector<float> plane(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      double value = 0.0;
      for (int c = 0; c < channels; ++c)
        value += forward(k, c) * static_cast<double>(centred[c][i]);
      plane[i] = static_cast<float>(value);
    }
    targets[static_cast<std::size_t>(k)] = periodogram(plane, width, height);
  }
  // Per channel: its Gaussians and the unweighted residual and target norms of its fit.
  struct ChannelFit {
    std::vector<GaussianComponent> gaussians;
    double residual_norm = 0.0;
    double target_norm = 0.0;
  };
  std::vector<ChannelFit> fits(static_cast<std::size_t>(channels));
  // Progress: every fit records its fraction; the calling thread reports their mean. What the hook
  // throws is kept, and the other fits stop at their next iteration.
  std::vector<std::atomic<double>> fit_fraction(fits.size());
  std::atomic<bool> cancelled{false};
  std::exception_ptr cancellation;
  const auto caller = std::this_thread::get_id();
  // Fit k's progress, its fraction mapped onto [from, to].
  const auto fit_progress = [&](std::size_t k, double from,
                                double to) -> std::function<void(double)> {
    if (!progress) return {};
    return [&, k, from, to](double fraction) {
      fit_fraction[k] = from + (to - from) * fraction;
      if (std::this_thread::get_id() != caller) {
        if (cancelled) throw Error(ErrorCode::numerical, "gabor: the analysis was cancelled");
        return;
      }
      double sum = 0.0;
      for (const auto& f : fit_fraction) sum += f;
      try {
        progress(sum / static_cast<double>(fit_fraction.size()));
      } catch (...) {
        cancellation = std::current_exception();
        cancelled = true;
        throw;
      }
    };
  };
  // Fits channel k on a plane of width x height bins (the exemplar's, or a decimated one) with a
  // dictionary whose narrowest band spans `narrowest` bins; the weighted problem: operator
  // diag(w) S_n, target w S_ex.
  const auto fit_channel = [&](std::size_t k, int plane_width, int plane_height, int narrowest,
                               std::span<const float> weights, std::span<const float> target,
                               double from, double to) {
    GaussianDictionary dictionary(plane_width, plane_height, narrowest);
    dictionary.set_weights(std::vector<float>(weights.begin(), weights.end()));
    const SpectrumFit fit = fit_spectrum(dictionary, target, options, fit_progress(k, from, to));
    ChannelFit result;
    result.residual_norm = fit.residual_norm;
    result.target_norm = fit.target_norm;
    // Every non-zero coefficient is a Gaussian (section 5.1). The fit runs on the full plane with
    // a symmetric target, so its iterates are symmetric: the Gaussians at m and -m form one pair
    // of eq. (6) with variance alpha(m) + alpha(-m) (half-plane, section 5.3).
    for (int b = 0; b < dictionary.band_count(); ++b) {
      const std::vector<float>& alpha = fit.alpha[static_cast<std::size_t>(b)];
      for (int y = 0; y < plane_height; ++y)
        for (int x = 0; x < plane_width; ++x) {
          const std::size_t index = static_cast<std::size_t>(y) * plane_width + x;
          const std::size_t mirror =
              static_cast<std::size_t>((plane_height - y) % plane_height) * plane_width +
              (plane_width - x) % plane_width;
          if (mirror < index) continue;
          const auto variance = static_cast<float>(
              dictionary.mass(b) * (mirror == index ? alpha[index] : alpha[index] + alpha[mirror]));
          if (!(variance > 0.0f)) continue;
          const int signed_x = x < (plane_width + 1) / 2 ? x : x - plane_width;
          const int signed_y = y < (plane_height + 1) / 2 ? y : y - plane_height;
          result.gaussians.push_back(
              {static_cast<int>(k), dictionary.band(b),
               static_cast<float>(static_cast<double>(signed_x) / plane_width),
               static_cast<float>(static_cast<double>(signed_y) / plane_height), variance});
        }
    }
    return result;
  };
  try {
    parallel_for(
        fits.size(), std::min(resolve_thread_count(0), kMaxFitsInFlight), [&](std::size_t k) {
          double target_variance = 0.0;
          for (const float v : targets[k]) target_variance += v;
          // The fit on a plane of width / factor x height / factor bins.
          const auto weighted_fit = [&](int factor, int narrowest, double from, double to) {
            const int plane_width = width / factor;
            const int plane_height = height / factor;
            std::vector<float> target =
                factor == 1 ? targets[k] : decimate_spectrum(targets[k], width, height, factor);
            const std::vector<float> weights =
                spectrum_weights(target, plane_width, plane_height, params.weighting);
            for (std::size_t i = 0; i < weights.size(); ++i) target[i] *= weights[i];
            return fit_channel(k, plane_width, plane_height, narrowest, weights, target, from, to);
          };
          const auto fitted_variance = [&] {
            double variance = 0.0;
            for (const GaussianComponent& g : fits[k].gaussians) variance += g.variance;
            return variance;
          };
          if (params.narrowest > 0) {
            fits[k] = weighted_fit(1, params.narrowest, 0.0, 1.0);
          } else {
            // Automatic: the dictionary down to kAutoNarrowest bins first, on the coarsest plane
            // that still resolves its narrowest band; the full one (one bin, on the exemplar's
            // plane) when that fit inflates the variance (features narrower than its Gaussians).
            const int factor = coarse_fit_factor(width, height);
            fits[k] = weighted_fit(factor, kAutoNarrowest / factor, 0.0, kAutoCoarseShare);
            if (fitted_variance() > kAutoVarianceExcess * target_variance)
              fits[k] = weighted_fit(1, 1, kAutoCoarseShare, 1.0);
          }
          // The channel's noise gets its periodogram's variance (the periodic component's, as
          // ADSN's); the fit error reports the fit itself.
          const double variance = fitted_variance();
          if (params.renormalise && variance > 0.0)
            for (GaussianComponent& g : fits[k].gaussians)
              g.variance = static_cast<float>(g.variance * (target_variance / variance));
        });
  } catch (...) {
    if (cancellation) std::rethrow_exception(cancellation);
    throw;
  }
  std::vector<GaussianComponent> gaussians;
  double residual_squared = 0.0;
  double target_squared = 0.0;
  for (ChannelFit& fit : fits) {
    residual_squared += fit.residual_norm * fit.residual_norm;
    target_squared += fit.target_norm * fit.target_norm;
    gaussians.insert(gaussians.end(), fit.gaussians.begin(), fit.gaussians.end());
    fit.gaussians = {};
  }
  report.sparseness =
      static_cast<double>(gaussians.size()) / (static_cast<double>(pixels) * channels);
  report.fit_error = target_squared > 0.0 ? std::sqrt(residual_squared / target_squared) : 0.0;
  if (gaussians.size() > kMaxGaussians)
    throw Error(ErrorCode::invalid_input,
                "gabor: the fit has more Gaussians than a model may hold; raise kappa");
  return GaborModel(channels, params.impulses, colour_space, std::move(gaussians),
                    std::move(mixing), std::move(mean), report);
}

}  // namespace stochtex::gabor
