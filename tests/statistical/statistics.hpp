#pragma once
// Helpers of the statistical tests: summaries of a measurement repeated over seeds, and spectra
// averaged over renders.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "core/colour_statistics.hpp"
#include "metrics/metrics.hpp"
#include "stochtex/image.hpp"
#include "stochtex/io.hpp"
#include "stochtex/material.hpp"

namespace stochtex::test_support {

// The shipped maps `names` of the material set `set` (data/materials/<set>/<name>.png), as
// analyze_material and material_exemplar take them; `maps` views `images`.
struct ShippedMaterial {
  std::vector<ImageF> images;
  std::vector<MaterialMap> maps;
};
inline ShippedMaterial shipped_material(const std::string& set,
                                        const std::vector<std::string>& names) {
  ShippedMaterial material;
  for (const std::string& name : names)
    material.images.push_back(
        read_image(std::string(STOCHTEX_MATERIAL_DIR) + "/" + set + "/" + name + ".png"));
  for (std::size_t i = 0; i < names.size(); ++i)
    material.maps.push_back({names[i], {}, material.images[i].view(), names[i] + ".png"});
  return material;
}

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

// The 1-D Wasserstein-1 distance of channel c's histograms in `a` and `b`: the mean absolute
// difference of their quantiles at the levels (k + 1/2) / n of the smaller image's n pixels.
inline double histogram_distance(const ImageF& a, const ImageF& b, int c) {
  const auto sorted = [c](const ImageF& image) {
    std::vector<double> values;
    for (int j = 0; j < image.height(); ++j)
      for (int i = 0; i < image.width(); ++i) values.push_back(image.at(i, j, c));
    sort_ascending(values);
    return values;
  };
  const std::vector<double> x = sorted(a);
  const std::vector<double> y = sorted(b);
  const std::size_t n = std::min(x.size(), y.size());
  const auto quantile = [n](const std::vector<double>& values, std::size_t k) {
    return values[(2 * k + 1) * values.size() / (2 * n)];
  };
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += std::abs(quantile(x, k) - quantile(y, k));
  return sum / static_cast<double>(n);
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
