#include "metrics/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/colour_statistics.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "hwy/contrib/sort/vqsort.h"
#include "spectral/adsn.hpp"
#include "spectral/fft.hpp"

namespace stochtex {

void require_pixels(ImageView<const float> image, const char* function) {
  if (image.width < 1 || image.height < 1 || image.channels < 1 || image.data == nullptr)
    throw std::invalid_argument(std::string(function) + ": the image is empty");
}

namespace {

void require_same_channels(ImageView<const float> a, ImageView<const float> b,
                           const char* function) {
  if (a.channels != b.channels)
    throw std::invalid_argument(std::string(function) + ": the images have " +
                                std::to_string(a.channels) + " and " + std::to_string(b.channels) +
                                " channels");
}

// numerator / denominator with the convention of metrics.hpp for a zero reference.
double relative(double numerator, double denominator) {
  if (denominator > 0.0) return numerator / denominator;
  return numerator > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

// Crop origins 0, crop / 2, crop, ... that fit in `size` (50% overlap, Welch 1967); crop >= 2.
std::vector<int> crop_origins(int size, int crop) {
  std::vector<int> origins;
  for (int origin = 0; origin + crop <= size; origin += crop / 2) origins.push_back(origin);
  return origins;
}

// The periodic Hann window sin^2(pi n / size): its copies shifted by size / 2 sum to a constant,
// so 50%-overlapping crops weight every interior pixel equally, and its DFT has only three
// non-zero bins, so the bias of removing the crop mean stays on the lowest frequencies.
std::vector<double> hann_window(int size) {
  std::vector<double> window(static_cast<std::size_t>(size));
  for (int n = 0; n < size; ++n) {
    const double s = std::sin(std::numbers::pi * n / size);
    window[static_cast<std::size_t>(n)] = s * s;
  }
  return window;
}

// A standard normal value by Box-Muller on two raw mt19937 draws (std::normal_distribution is not
// specified exactly, so its values differ between standard libraries). Each draw is its own
// statement so that the order of the draws does not depend on argument evaluation order.
double standard_normal(std::mt19937& rng) {
  constexpr double two_to_32 = 4294967296.0;
  const double u1 = (static_cast<double>(rng()) + 0.5) / two_to_32;
  const double u2 = (static_cast<double>(rng()) + 0.5) / two_to_32;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// `count` unit vectors of R^channels, uniform on the sphere, the same on every call.
std::vector<std::vector<double>> projection_directions(int channels, int count) {
  if (channels == 1) return {{1.0}};
  constexpr std::uint32_t direction_seed = 0x5EED5EEDu;
  std::mt19937 rng(direction_seed);
  std::vector<std::vector<double>> directions(static_cast<std::size_t>(count));
  for (auto& direction : directions) {
    direction.resize(static_cast<std::size_t>(channels));
    double norm_squared = 0.0;
    for (double& component : direction) {
      component = standard_normal(rng);
      norm_squared += component * component;
    }
    const double norm = std::sqrt(norm_squared);
    for (double& component : direction) component /= norm;
  }
  return directions;
}

// The pixels of `image` projected on `direction`, sorted: the empirical quantile function.
std::vector<double> sorted_projection(ImageView<const float> image,
                                      const std::vector<double>& direction) {
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    const float* row = image.row(y);
    for (int x = 0; x < image.width; ++x) {
      const float* pixel = row + static_cast<std::ptrdiff_t>(x) * image.channels;
      double value = 0.0;
      for (int c = 0; c < image.channels; ++c)
        value += direction[static_cast<std::size_t>(c)] * pixel[c];
      values.push_back(value);
    }
  }
  sort_ascending(values);
  return values;
}

// The empirical quantile F^-1((2 i + 1) / (2 levels)) of n sorted values: the value of index
// floor((2 i + 1) n / (2 levels)), computed in integers so that equal counts give index i exactly.
double quantile(const std::vector<double>& sorted, std::size_t i, std::size_t levels) {
  const std::size_t index = (2 * i + 1) * sorted.size() / (2 * levels);
  return sorted[index];
}

}  // namespace

void sort_ascending(std::vector<double>& values) {
  // Highway's vectorised quicksort (VQSort): the same sorted values as std::sort (a sort's result
  // does not depend on the algorithm when no value is NaN), 5 times as fast on a 1024² render,
  // where std::sort took 96% of a sliced Wasserstein distance (docs/performance.md).
  if (hwy::Sorter::HaveFloat64())
    hwy::Sorter()(values.data(), values.size(), hwy::SortAscending());
  else
    std::sort(values.begin(), values.end());
}

std::vector<double> welch_power_spectrum(ImageView<const float> image, int crop) {
  require_pixels(image, "welch_power_spectrum");
  if (crop < 2 || crop > image.width || crop > image.height)
    throw std::invalid_argument("welch_power_spectrum: the crop side " + std::to_string(crop) +
                                " must be at least 2 and fit in the " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " image");
  const std::vector<double> window = hann_window(crop);
  double window_energy_1d = 0.0;
  for (const double w : window) window_energy_1d += w * w;
  const double window_energy = window_energy_1d * window_energy_1d;

  const Fft2d fft(crop, crop);
  const int spectrum_width = fft.spectrum_width();
  std::vector<float> windowed(fft.image_size());
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  std::vector<double> half_power(fft.spectrum_size(), 0.0);
  const std::vector<int> x_origins = crop_origins(image.width, crop);
  const std::vector<int> y_origins = crop_origins(image.height, crop);
  for (const int y0 : y_origins) {
    for (const int x0 : x_origins) {
      const ImageView<const float> block = image.sub(x0, y0, crop, crop);
      for (int c = 0; c < image.channels; ++c) {
        double sum = 0.0;
        for (int y = 0; y < crop; ++y)
          for (int x = 0; x < crop; ++x) sum += block.at(x, y, c);
        const double mean = sum / (static_cast<double>(crop) * crop);
        for (int y = 0; y < crop; ++y)
          for (int x = 0; x < crop; ++x)
            windowed[static_cast<std::size_t>(y) * crop + x] = static_cast<float>(
                window[static_cast<std::size_t>(x)] * window[static_cast<std::size_t>(y)] *
                (block.at(x, y, c) - mean));
        fft.forward(windowed, spectrum);
        for (std::size_t i = 0; i < spectrum.size(); ++i) half_power[i] += std::norm(spectrum[i]);
      }
    }
  }

  // The input is real, so |X(kx, ky)| = |X(-kx, -ky)|: the columns kx > crop / 2 missing from the
  // half-plane are read at (crop - kx, -ky).
  const double normalisation =
      1.0 / (window_energy * static_cast<double>(x_origins.size() * y_origins.size()));
  std::vector<double> power(static_cast<std::size_t>(crop) * crop);
  for (int ky = 0; ky < crop; ++ky) {
    for (int kx = 0; kx < crop; ++kx) {
      const bool stored = kx < spectrum_width;
      const int qx = stored ? kx : crop - kx;
      const int qy = stored ? ky : (crop - ky) % crop;
      power[static_cast<std::size_t>(ky) * crop + kx] =
          half_power[static_cast<std::size_t>(qy) * spectrum_width + qx] * normalisation;
    }
  }
  return power;
}

int welch_crop_size(ImageView<const float> a, ImageView<const float> b) {
  const int smaller_side = std::min({a.width, a.height, b.width, b.height});
  if (smaller_side < 2)
    throw std::invalid_argument(
        "welch_crop_size: a spectral comparison needs images of at least 2x2 pixels");
  constexpr int min_crop = 8;
  constexpr int max_crop = 128;
  const int limit =
      smaller_side < min_crop ? smaller_side : std::clamp(smaller_side / 2, min_crop, max_crop);
  int crop = 2;
  while (crop * 2 <= limit) crop *= 2;
  return crop;
}

double relative_l1_distance(std::span<const double> a, std::span<const double> reference) {
  if (a.size() != reference.size())
    throw std::invalid_argument("relative_l1_distance: the spectra have different sizes");
  double difference = 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference += std::abs(a[i] - reference[i]);
    total += std::abs(reference[i]);
  }
  return relative(difference, total);
}

double spectral_error(ImageView<const float> image, ImageView<const float> reference, int crop) {
  require_same_channels(image, reference, "spectral_error");
  return relative_l1_distance(welch_power_spectrum(image, crop),
                              welch_power_spectrum(reference, crop));
}

double sliced_wasserstein(ImageView<const float> a, ImageView<const float> b, int directions) {
  require_pixels(a, "sliced_wasserstein");
  require_pixels(b, "sliced_wasserstein");
  require_same_channels(a, b, "sliced_wasserstein");
  if (directions < 1)
    throw std::invalid_argument("sliced_wasserstein: the number of directions must be positive");
  const std::size_t levels = std::min(static_cast<std::size_t>(a.width) * a.height,
                                      static_cast<std::size_t>(b.width) * b.height);
  const std::vector<std::vector<double>> projections =
      projection_directions(a.channels, directions);
  // Directions run in parallel, each into its own slot, and the slots are summed in order: the
  // result does not depend on the thread count.
  std::vector<double> mean_squares(projections.size());
  parallel_for(projections.size(), 0, [&](std::size_t d) {
    const std::vector<double> sorted_a = sorted_projection(a, projections[d]);
    const std::vector<double> sorted_b = sorted_projection(b, projections[d]);
    double squares = 0.0;
    for (std::size_t i = 0; i < levels; ++i) {
      const double difference = quantile(sorted_a, i, levels) - quantile(sorted_b, i, levels);
      squares += difference * difference;
    }
    mean_squares[d] = squares / static_cast<double>(levels);
  });
  double sum = 0.0;
  for (const double mean_square : mean_squares) sum += mean_square;
  return std::sqrt(sum / static_cast<double>(projections.size()));
}

SlicedWassersteinReference::SlicedWassersteinReference(ImageView<const float> reference,
                                                       std::size_t levels, int directions) {
  require_pixels(reference, "SlicedWassersteinReference");
  if (directions < 1)
    throw std::invalid_argument(
        "SlicedWassersteinReference: the number of directions must be positive");
  channels_ = reference.channels;
  pixels_ = static_cast<std::size_t>(reference.width) * reference.height;
  if (levels < 1 || levels > pixels_)
    throw std::invalid_argument("SlicedWassersteinReference: the level count " +
                                std::to_string(levels) + " must be 1 to the reference's " +
                                std::to_string(pixels_) + " pixels");
  levels_ = levels;
  directions_ = projection_directions(reference.channels, directions);
  quantiles_.resize(directions_.size());
  parallel_for(directions_.size(), 0, [&](std::size_t d) {
    const std::vector<double> sorted = sorted_projection(reference, directions_[d]);
    quantiles_[d].resize(levels_);
    for (std::size_t i = 0; i < levels_; ++i) quantiles_[d][i] = quantile(sorted, i, levels_);
  });
}

double SlicedWassersteinReference::distance(ImageView<const float> image) const {
  require_pixels(image, "SlicedWassersteinReference::distance");
  if (image.channels != channels_)
    throw std::invalid_argument("SlicedWassersteinReference::distance: the image has " +
                                std::to_string(image.channels) + " channels, the reference " +
                                std::to_string(channels_));
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  if (std::min(pixels, pixels_) != levels_)
    throw std::invalid_argument(
        "SlicedWassersteinReference::distance: the image's pixel count does not match the "
        "reference's quantile levels");
  // The same sums in the same order as sliced_wasserstein.
  std::vector<double> mean_squares(directions_.size());
  parallel_for(directions_.size(), 0, [&](std::size_t d) {
    const std::vector<double> sorted = sorted_projection(image, directions_[d]);
    double squares = 0.0;
    for (std::size_t i = 0; i < levels_; ++i) {
      const double difference = quantile(sorted, i, levels_) - quantiles_[d][i];
      squares += difference * difference;
    }
    mean_squares[d] = squares / static_cast<double>(levels_);
  });
  double sum = 0.0;
  for (const double mean_square : mean_squares) sum += mean_square;
  return std::sqrt(sum / static_cast<double>(directions_.size()));
}

ColourStatistics colour_statistics(ImageView<const float> image) {
  require_pixels(image, "colour_statistics");
  std::vector<double> mean = channel_means(image);
  std::vector<double> covariance = channel_covariance(image, mean);
  return {std::move(mean), std::move(covariance)};
}

double mean_error(const ColourStatistics& a, const ColourStatistics& b) {
  if (a.mean.size() != b.mean.size())
    throw std::invalid_argument("mean_error: the statistics have different channel counts");
  double sum_of_squares = 0.0;
  for (std::size_t c = 0; c < a.mean.size(); ++c)
    sum_of_squares += (a.mean[c] - b.mean[c]) * (a.mean[c] - b.mean[c]);
  return std::sqrt(sum_of_squares);
}

double covariance_error(const ColourStatistics& a, const ColourStatistics& reference) {
  if (a.covariance.size() != reference.covariance.size())
    throw std::invalid_argument("covariance_error: the statistics have different channel counts");
  double difference = 0.0;
  double norm = 0.0;
  for (std::size_t i = 0; i < a.covariance.size(); ++i) {
    const double delta = a.covariance[i] - reference.covariance[i];
    difference += delta * delta;
    norm += reference.covariance[i] * reference.covariance[i];
  }
  return relative(std::sqrt(difference), std::sqrt(norm));
}

WrapSteps wrap_steps(ImageView<const float> image) {
  if (!image.data || image.width < 2 || image.height < 2 || image.channels < 1)
    throw std::invalid_argument("wrap_steps needs an image of at least 2x2 pixels");
  double inside_x = 0.0, wrap_x = 0.0, inside_y = 0.0, wrap_y = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < image.channels; ++c) {
        const double value = image.at(x, y, c);
        const double right = image.at(x + 1 < image.width ? x + 1 : 0, y, c);
        const double below = image.at(x, y + 1 < image.height ? y + 1 : 0, c);
        (x + 1 < image.width ? inside_x : wrap_x) += std::abs(right - value);
        (y + 1 < image.height ? inside_y : wrap_y) += std::abs(below - value);
      }
  // Means: the wrap has one column (row), the inside width - 1 (height - 1) of them.
  const auto ratio = [](double wrap, double inside, int steps) {
    return inside > 0.0 ? wrap * steps / inside : 1.0;
  };
  return {ratio(wrap_x, inside_x, image.width - 1), ratio(wrap_y, inside_y, image.height - 1)};
}

double variance_nonstationarity(std::span<const ImageView<const float>> renders, int block) {
  if (renders.size() < 2)
    throw std::invalid_argument("variance_nonstationarity: at least 2 renders are needed");
  const ImageView<const float>& first = renders.front();
  for (const auto& render : renders) {
    require_pixels(render, "variance_nonstationarity");
    require_same_channels(render, first, "variance_nonstationarity");
    if (render.width != first.width || render.height != first.height)
      throw std::invalid_argument("variance_nonstationarity: the renders have different sizes");
  }
  if (block < 1 || block > first.width || block > first.height)
    throw std::invalid_argument("variance_nonstationarity: the block side " +
                                std::to_string(block) + " must be at least 1 and fit in the " +
                                std::to_string(first.width) + "x" + std::to_string(first.height) +
                                " renders");
  const int blocks_x = first.width / block;
  const int blocks_y = first.height / block;
  const double count = static_cast<double>(renders.size());
  std::vector<double> block_variance(static_cast<std::size_t>(blocks_x) * blocks_y, 0.0);
  for (int y = 0; y < blocks_y * block; ++y) {
    for (int x = 0; x < blocks_x * block; ++x) {
      double variance = 0.0;
      for (int c = 0; c < first.channels; ++c) {
        double sum = 0.0;
        for (const auto& render : renders) sum += render.at(x, y, c);
        const double mean = sum / count;
        double squares = 0.0;
        for (const auto& render : renders) {
          const double deviation = render.at(x, y, c) - mean;
          squares += deviation * deviation;
        }
        variance += squares / (count - 1.0);
      }
      block_variance[static_cast<std::size_t>(y / block) * blocks_x + x / block] += variance;
    }
  }
  double sum = 0.0;
  for (const double variance : block_variance) sum += variance;
  const double mean = sum / static_cast<double>(block_variance.size());
  double squares = 0.0;
  for (const double variance : block_variance) squares += (variance - mean) * (variance - mean);
  return relative(std::sqrt(squares / static_cast<double>(block_variance.size())), mean);
}

double histogram_error_floor(ImageView<const float> exemplar) {
  require_pixels(exemplar, "histogram_error_floor");
  const int top_height = exemplar.height / 2;
  return sliced_wasserstein(
      exemplar.sub(0, 0, exemplar.width, top_height),
      exemplar.sub(0, top_height, exemplar.width, exemplar.height - top_height));
}

void check_compare_budget(int exemplar_width, int exemplar_height, int width, int height,
                          int channels) {
  const auto pixels = [](int w, int h) {
    return static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  };
  check_memory_budget(
      compare_peak_bytes(pixels(exemplar_width, exemplar_height), pixels(width, height), channels),
      "comparing a " + std::to_string(width) + "x" + std::to_string(height) + " image with a " +
          std::to_string(exemplar_width) + "x" + std::to_string(exemplar_height) + " exemplar",
      "compare crops of them");
}

Comparison::Comparison(ImageView<const float> exemplar, std::uint32_t seed)
    : exemplar_(exemplar), seed_(seed) {
  require_pixels(exemplar, "Comparison");
}

void Comparison::add(ImageView<const float> image) {
  require_pixels(image, "Comparison::add");
  require_same_channels(image, exemplar_, "Comparison::add");
  if (images_ > 0 && (image.width != width_ || image.height != height_))
    throw std::invalid_argument("Comparison::add: the image is " + std::to_string(image.width) +
                                "x" + std::to_string(image.height) + ", the first was " +
                                std::to_string(width_) + "x" + std::to_string(height_) +
                                "; compare renders of one size");
  check_compare_budget(exemplar_.width, exemplar_.height, image.width, image.height,
                       image.channels);
  if (images_ == 0) {
    width_ = image.width;
    height_ = image.height;
    crop_ = welch_crop_size(exemplar_, image);
    exemplar_statistics_ = colour_statistics(exemplar_);
    histogram_error_floor_ = histogram_error_floor(exemplar_);
    exemplar_spectrum_ = welch_power_spectrum(exemplar_, crop_);
    image_spectrum_sum_.assign(exemplar_spectrum_.size(), 0.0);
    adsn_spectrum_sum_.assign(exemplar_spectrum_.size(), 0.0);
  }
  const ImageF gaussian =
      adsn(exemplar_, image.width, image.height, seed_ + static_cast<std::uint32_t>(images_));
  const auto measure = [&](ImageView<const float> synthesis, Quality& sum,
                           std::vector<double>& spectrum_sum) {
    const std::vector<double> spectrum = welch_power_spectrum(synthesis, crop_);
    sum.spectral_error += relative_l1_distance(spectrum, exemplar_spectrum_);
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum_sum[i] += spectrum[i];
    sum.histogram_error += sliced_wasserstein(synthesis, exemplar_);
  };
  measure(image, image_sum_, image_spectrum_sum_);
  measure(gaussian.view(), adsn_sum_, adsn_spectrum_sum_);
  const ColourStatistics image_statistics = colour_statistics(image);
  image_sum_.mean_error += mean_error(image_statistics, exemplar_statistics_);
  image_sum_.covariance_error += covariance_error(image_statistics, exemplar_statistics_);
  ++images_;
}

ComparisonReport Comparison::report() const {
  if (images_ == 0) throw std::logic_error("Comparison::report: no image was added");
  const double count = static_cast<double>(images_);
  const auto mean = [&](const Quality& sum, const std::vector<double>& spectrum_sum) {
    Quality quality;
    quality.spectral_error = sum.spectral_error / count;
    quality.histogram_error = sum.histogram_error / count;
    quality.mean_error = sum.mean_error / count;
    quality.covariance_error = sum.covariance_error / count;
    std::vector<double> averaged(spectrum_sum.size());
    for (std::size_t i = 0; i < averaged.size(); ++i) averaged[i] = spectrum_sum[i] / count;
    quality.averaged_spectral_error = relative_l1_distance(averaged, exemplar_spectrum_);
    return quality;
  };
  ComparisonReport report;
  report.crop = crop_;
  report.images = images_;
  report.image = mean(image_sum_, image_spectrum_sum_);
  report.adsn = mean(adsn_sum_, adsn_spectrum_sum_);
  report.histogram_error_floor = histogram_error_floor_;
  return report;
}

ComparisonReport compare_images(ImageView<const float> exemplar, ImageView<const float> image,
                                std::uint32_t seed) {
  Comparison comparison(exemplar, seed);
  comparison.add(image);
  return comparison.report();
}

}  // namespace stochtex
