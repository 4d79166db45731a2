#pragma once
// Helpers of the statistical tests: summaries of a measurement repeated over seeds, and spectra
// averaged over renders.

#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/colour_statistics.hpp"
#include "metrics/metrics.hpp"
#include "stochtex/image.hpp"

namespace stochtex::test_support {

struct Sample {
  double mean = 0;
  double deviation = 0;  // sample standard deviation of one measurement
};

inline Sample summarise(const std::vector<double>& values) {
  const double n = static_cast<double>(values.size());
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double square = 0.0;
  for (const double v : values) square += (v - mean) * (v - mean);
  return {mean, std::sqrt(square / (n - 1.0))};
}

// The pooled standard deviation of two measurements' samples (equal counts).
inline double pooled(const Sample& a, const Sample& b) {
  return std::sqrt(0.5 * (a.deviation * a.deviation + b.deviation * b.deviation));
}

// Correlation matrix (channels x channels, row-major) of an image's values.
inline std::vector<double> correlation_matrix(const ImageF& image) {
  const ColourStatistics statistics = colour_statistics(image.view());
  const auto n = static_cast<std::size_t>(image.channels());
  std::vector<double> result(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      result[i * n + j] =
          statistics.covariance[i * n + j] /
          std::sqrt(statistics.covariance[i * n + i] * statistics.covariance[j * n + j]);
  return result;
}

// Welch spectrum averaged over the images make(1) ... make(seeds): an estimate of the expected
// spectrum of what `make` renders.
template <typename Make>
std::vector<double> mean_spectrum(Make&& make, int seeds, int crop) {
  std::vector<double> mean;
  for (std::uint32_t seed = 1; seed <= static_cast<std::uint32_t>(seeds); ++seed) {
    const ImageF image = make(seed);
    const std::vector<double> spectrum = welch_power_spectrum(image.view(), crop);
    mean.resize(spectrum.size(), 0.0);
    for (std::size_t i = 0; i < spectrum.size(); ++i) mean[i] += spectrum[i] / seeds;
  }
  return mean;
}

}  // namespace stochtex::test_support
