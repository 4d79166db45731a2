#include "metrics/structure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "metrics/metrics.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"

namespace stochtex {
namespace {

// The mean of the channels, one channel.
ImageF channel_mean_image(ImageView<const float> image) {
  ImageF mean(image.width, image.height, 1);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      double sum = 0.0;
      for (int c = 0; c < image.channels; ++c) sum += image.at(x, y, c);
      mean.at(x, y, 0) = static_cast<float>(sum / image.channels);
    }
  return mean;
}

// E[(v - mean)^4] / E[(v - mean)^2]^2, 3 where the values do not vary.
double sample_kurtosis(const std::vector<float>& values) {
  double mean = 0.0;
  for (const float v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double second = 0.0;
  double fourth = 0.0;
  for (const float v : values) {
    const double d = v - mean;
    second += d * d;
    fourth += d * d * d * d;
  }
  second /= static_cast<double>(values.size());
  fourth /= static_cast<double>(values.size());
  return second > 0.0 ? fourth / (second * second) : 3.0;
}

// The signed frequency of DFT index k of n, in cycles per pixel.
double signed_frequency(int k, int n) {
  return static_cast<double>(k <= n / 2 ? k : k - n) / n;
}

}  // namespace

int kurtosis_bands(int width, int height) {
  int bands = 1;
  for (int scale = 2; scale <= std::min(width, height) / 64; scale *= 2) ++bands;
  return bands;
}

std::vector<double> band_kurtosis(ImageView<const float> image, int bands) {
  require_pixels(image, "band_kurtosis");
  if (bands < 1) throw std::invalid_argument("band_kurtosis: needs at least one band");
  const ImageF mean = channel_mean_image(image);
  const ImageF periodic = periodic_component(mean.view());
  Fft2d fft(image.width, image.height);
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  fft.forward(periodic.pixels(), spectrum);
  std::vector<std::complex<float>> band(spectrum.size());
  std::vector<float> response(fft.image_size());
  std::vector<double> kurtosis;
  for (int k = 0; k < bands; ++k) {
    // The transfer function of G(sigma) is exp(-2 pi^2 sigma^2 |f|^2).
    const double sigma = static_cast<double>(1 << k);
    const double fine = -2.0 * std::numbers::pi * std::numbers::pi * sigma * sigma / 4.0;
    const double coarse = -2.0 * std::numbers::pi * std::numbers::pi * sigma * sigma;
    for (int y = 0; y < image.height; ++y) {
      const double fy = signed_frequency(y, image.height);
      for (int x = 0; x < fft.spectrum_width(); ++x) {
        const double fx = static_cast<double>(x) / image.width;
        const double f2 = fx * fx + fy * fy;
        const std::size_t i = static_cast<std::size_t>(y) * fft.spectrum_width() + x;
        band[i] = spectrum[i] * static_cast<float>(std::exp(fine * f2) - std::exp(coarse * f2));
      }
    }
    fft.inverse(band, response);
    kurtosis.push_back(sample_kurtosis(response));
  }
  return kurtosis;
}

double spectral_peak_fraction(ImageView<const float> image) {
  require_pixels(image, "spectral_peak_fraction");
  const int w = image.width;
  const int h = image.height;
  const ImageF mean = channel_mean_image(image);
  double average = 0.0;
  for (const float v : mean.pixels()) average += v;
  average /= static_cast<double>(w) * h;
  // The periodic Hann window sin^2(pi n / size) of welch_power_spectrum, over the whole image.
  const auto hann = [](int n, int size) {
    const double s = std::sin(std::numbers::pi * n / size);
    return s * s;
  };
  Fft2d fft(w, h);
  std::vector<float> windowed(fft.image_size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      windowed[static_cast<std::size_t>(y) * w + x] =
          static_cast<float>((mean.at(x, y, 0) - average) * hann(x, w) * hann(y, h));
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  fft.forward(windowed, spectrum);
  // The whole plane from the half plane: |X(x, y)| = |X(-x, -y)| for a real input.
  std::vector<double> power(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool stored = x < fft.spectrum_width();
      const int sx = stored ? x : w - x;
      const int sy = stored ? y : (h - y) % h;
      power[static_cast<std::size_t>(y) * w + x] =
          std::norm(spectrum[static_cast<std::size_t>(sy) * fft.spectrum_width() + sx]);
    }
  constexpr int kRadius = 4;         // the neighbourhood is (2 kRadius + 1)^2 bins
  constexpr double kPeakRatio = 16;  // times the neighbourhood's median
  constexpr double kDcRadius = 4;    // bins nearer DC than this are not counted
  std::array<double, (2 * kRadius + 1) * (2 * kRadius + 1)> neighbourhood{};
  double total = 0.0;
  double peaks = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = std::min(x, w - x);
      const double dy = std::min(y, h - y);
      if (std::hypot(dx, dy) < kDcRadius) continue;
      const double p = power[static_cast<std::size_t>(y) * w + x];
      total += p;
      std::size_t n = 0;
      for (int j = -kRadius; j <= kRadius; ++j)
        for (int i = -kRadius; i <= kRadius; ++i)
          neighbourhood[n++] =
              power[static_cast<std::size_t>(((y + j) % h + h) % h) * w + ((x + i) % w + w) % w];
      const auto middle = neighbourhood.begin() + static_cast<std::ptrdiff_t>(n / 2);
      std::nth_element(neighbourhood.begin(), middle, neighbourhood.end());
      if (p > kPeakRatio * *middle) peaks += p;
    }
  return total > 0.0 ? peaks / total : 0.0;
}

}  // namespace stochtex
