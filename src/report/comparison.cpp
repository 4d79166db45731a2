#include "report/comparison.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "metrics/structure.hpp"
#include "spectral/adsn.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

// CPU seconds used by the calling thread: the analyses and one-thread renders run on it, and
// unlike the wall clock this barely moves when other threads or processes share the cores.
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

void check_settings(const ReportSettings& settings) {
  if (settings.width < 2 || settings.height < 2)
    throw std::invalid_argument("the report's images must be at least 2x2 pixels");
  if (settings.averaged_seeds < 1)
    throw std::invalid_argument("the report's averaged spectrum needs at least one seed");
  if (settings.stationarity_seeds < 2 || settings.stationarity_block < 1 ||
      settings.stationarity_side < settings.stationarity_block || settings.stationarity_step < 1)
    throw std::invalid_argument("the report's stationarity grid is inconsistent");
}

// The quality of `image` against the exemplar, except stationarity (which needs several renders).
Quality measure_quality(ImageView<const float> image, const ExemplarReference& reference) {
  Quality quality;
  quality.spectral_error =
      relative_l1_distance(welch_power_spectrum(image, reference.crop), reference.spectrum);
  quality.histogram_error = reference.colours->distance(image);
  const ColourStatistics statistics = colour_statistics(image);
  quality.mean_error = mean_error(statistics, reference.statistics);
  quality.covariance_error = covariance_error(statistics, reference.statistics);
  const std::vector<double> kurtosis =
      band_kurtosis(image, static_cast<int>(reference.band_kurtosis.size()));
  for (std::size_t k = 0; k < kurtosis.size(); ++k)
    quality.structure_error +=
        std::abs(kurtosis[k] - reference.band_kurtosis[k]) / reference.band_kurtosis[k];
  quality.structure_error /= static_cast<double>(kurtosis.size());
  return quality;
}

void draw_pictures(Synthesis& synthesis, const ExemplarReference& reference,
                   const ReportSettings& settings) {
  synthesis.spectrum_picture =
      spectrum_picture(welch_power_spectrum(synthesis.image.view(), reference.crop), reference.crop,
                       reference.spectrum_range);
  const ColourHistogram histogram =
      colour_histogram(synthesis.image.view(), settings.histogram_bins, reference.histogram.low,
                       reference.histogram.high);
  synthesis.histogram_picture =
      histogram_picture(histogram, reference.histogram, settings.histogram_width,
                        settings.histogram_height, reference.histogram_top);
}

// The averaged spectral error and its picture: the Welch spectra of the synthesis's image and of
// `others` (the same synthesis with the next seeds) averaged.
void average_spectra(Synthesis& synthesis, const std::vector<ImageF>& others,
                     const ExemplarReference& reference) {
  std::vector<double> mean = welch_power_spectrum(synthesis.image.view(), reference.crop);
  for (const ImageF& other : others) {
    const std::vector<double> spectrum = welch_power_spectrum(other.view(), reference.crop);
    for (std::size_t i = 0; i < mean.size(); ++i) mean[i] += spectrum[i];
  }
  const double count = static_cast<double>(others.size() + 1);
  for (double& power : mean) power /= count;
  synthesis.quality.averaged_spectral_error = relative_l1_distance(mean, reference.spectrum);
  synthesis.averaged_spectrum_picture =
      spectrum_picture(mean, reference.crop, reference.spectrum_range);
}

double nonstationarity(const std::vector<ImageF>& renders, const ReportSettings& settings) {
  std::vector<ImageView<const float>> views;
  for (const ImageF& render : renders) views.push_back(render.view());
  return variance_nonstationarity(views, settings.stationarity_block);
}

}  // namespace

ExemplarReference make_reference(ImageView<const float> exemplar, const ReportSettings& settings) {
  check_settings(settings);
  validate_exemplar(exemplar, "exemplar");
  ExemplarReference reference;
  // The crop compare uses for an image of the report's size against this exemplar.
  const ImageF report_sized(settings.width, settings.height, exemplar.channels);
  reference.crop = welch_crop_size(exemplar, report_sized.view());
  reference.spectrum = welch_power_spectrum(exemplar, reference.crop);
  reference.spectrum_range = spectrum_range(reference.spectrum);
  reference.statistics = colour_statistics(exemplar);
  const auto [low, high] = histogram_range(exemplar);
  reference.histogram = colour_histogram(exemplar, settings.histogram_bins, low, high);
  reference.histogram_top = 1.25 * reference.histogram.largest();
  reference.histogram_error_floor = histogram_error_floor(exemplar);
  reference.band_kurtosis =
      band_kurtosis(exemplar, std::min(kurtosis_bands(exemplar.width, exemplar.height),
                                       kurtosis_bands(settings.width, settings.height)));
  reference.colours.emplace(exemplar,
                            std::min(static_cast<std::size_t>(exemplar.width) * exemplar.height,
                                     static_cast<std::size_t>(settings.width) * settings.height));
  reference.spectrum_picture =
      spectrum_picture(reference.spectrum, reference.crop, reference.spectrum_range);
  reference.histogram_picture =
      histogram_picture(reference.histogram, reference.histogram, settings.histogram_width,
                        settings.histogram_height, reference.histogram_top);
  return reference;
}

Synthesis measure_gaussian(ImageView<const float> exemplar, const ExemplarReference& reference,
                           const ReportSettings& settings) {
  check_settings(settings);
  Synthesis synthesis;
  synthesis.name = "gaussian";
  synthesis.image = adsn(exemplar, settings.width, settings.height, settings.seed);
  synthesis.quality = measure_quality(synthesis.image.view(), reference);
  std::vector<ImageF> others;
  for (int k = 1; k < settings.averaged_seeds; ++k)
    others.push_back(adsn(exemplar, settings.width, settings.height,
                          settings.seed + static_cast<std::uint32_t>(k)));
  average_spectra(synthesis, others, reference);
  // ADSN on the stationarity grid: samples of a larger ADSN image, step pixels apart.
  const int step = settings.stationarity_step;
  const int side = settings.stationarity_side;
  std::vector<ImageF> renders;
  for (int k = 0; k < settings.stationarity_seeds; ++k) {
    const ImageF dense =
        adsn(exemplar, side * step, side * step, settings.seed + 1 + static_cast<std::uint32_t>(k));
    ImageF sparse(side, side, dense.channels());
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x)
        for (int c = 0; c < dense.channels(); ++c)
          sparse.at(x, y, c) = dense.at(x * step, y * step, c);
    renders.push_back(std::move(sparse));
  }
  synthesis.quality.nonstationarity = nonstationarity(renders, settings);
  draw_pictures(synthesis, reference, settings);
  return synthesis;
}

Synthesis measure_method(std::string_view method, ImageView<const float> exemplar,
                         const ExemplarReference& reference, const ReportSettings& settings) {
  check_settings(settings);
  Synthesis synthesis;
  synthesis.name = std::string(method);
  const double analysis_start = thread_cpu_seconds();
  const Model model = analyze(method, exemplar);
  const double analysis_seconds = thread_cpu_seconds() - analysis_start;

  RenderOptions one_thread;
  one_thread.threads = 1;
  synthesis.image = ImageF(settings.width, settings.height, model.channels());
  const double render_start = thread_cpu_seconds();
  render(model, Grid{{0.0, 0.0}, 1.0, settings.width, settings.height}, settings.seed,
         synthesis.image.view(), one_thread);
  const double ns_per_sample = (thread_cpu_seconds() - render_start) * 1e9 /
                               (static_cast<double>(settings.width) * settings.height);
  synthesis.quality = measure_quality(synthesis.image.view(), reference);
  synthesis.quality.analysis_seconds = analysis_seconds;
  synthesis.quality.ns_per_sample = ns_per_sample;
  std::vector<ImageF> others;
  for (int k = 1; k < settings.averaged_seeds; ++k) {
    ImageF other(settings.width, settings.height, model.channels());
    render(model, Grid{{0.0, 0.0}, 1.0, settings.width, settings.height},
           settings.seed + static_cast<std::uint32_t>(k), other.view(), one_thread);
    others.push_back(std::move(other));
  }
  average_spectra(synthesis, others, reference);

  // Point samples, so that the variance measured is the method's own and not its filtering's.
  one_thread.filter = false;
  const Grid stationarity_grid{{0.0, 0.0},
                               static_cast<double>(settings.stationarity_step),
                               settings.stationarity_side,
                               settings.stationarity_side};
  std::vector<ImageF> renders;
  for (int k = 0; k < settings.stationarity_seeds; ++k) {
    ImageF render_k(settings.stationarity_side, settings.stationarity_side, model.channels());
    render(model, stationarity_grid, settings.seed + 1 + static_cast<std::uint32_t>(k),
           render_k.view(), one_thread);
    renders.push_back(std::move(render_k));
  }
  synthesis.quality.nonstationarity = nonstationarity(renders, settings);
  draw_pictures(synthesis, reference, settings);
  return synthesis;
}

}  // namespace stochtex
