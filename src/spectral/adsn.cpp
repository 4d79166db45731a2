#include "spectral/adsn.hpp"

#include <complex>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "core/colour_statistics.hpp"
#include "core/hash.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"
#include "spectral/white_noise.hpp"

namespace stochtex {
namespace {

// The smallest n' >= n whose only prime factors are 2, 3, 5 and 7: FFTW is fastest on those.
int smooth_size(int n) {
  for (int candidate = n;; ++candidate) {
    int rest = candidate;
    for (const int factor : {2, 3, 5, 7})
      while (rest % factor == 0) rest /= factor;
    if (rest == 1) return candidate;
  }
}

}  // namespace

ImageF adsn(ImageView<const float> exemplar, int width, int height, std::uint32_t seed) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("adsn: the output size must be positive");
  const int kernel_width = exemplar.width;
  const int kernel_height = exemplar.height;
  const int channels = exemplar.channels;
  const ImageF periodic = periodic_component(exemplar);
  const std::size_t kernel_pixels = periodic.pixel_count();

  // out(x) = sum_k t(k) W(x - k) on a circular domain of at least (width + M) x (height + N):
  // the outputs at x in [M, M + width) x [N, N + height) never read a wrapped noise value, so the
  // result is an exact sample of the ADSN on Z^2, restricted to the requested window.
  const int domain_width = smooth_size(width + kernel_width);
  const int domain_height = smooth_size(height + kernel_height);
  const Fft2d fft(domain_width, domain_height);
  const std::vector<float> noise =
      gaussian_white_noise(fft.image_size(), cell_key(0, 0, seed, Stream::analysis));
  std::vector<std::complex<float>> noise_spectrum(fft.spectrum_size());
  fft.forward(noise, noise_spectrum);

  ImageF result(width, height, channels);
  std::vector<float> plane(fft.image_size());
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  const double normalisation = 1.0 / std::sqrt(static_cast<double>(kernel_pixels));
  const std::vector<double> means = channel_means(periodic.view());
  for (int c = 0; c < channels; ++c) {
    const double mean = means[static_cast<std::size_t>(c)];
    // t = (p - mean(p)) / sqrt(|Omega|), zero-padded (texton paper section 3.1).
    std::fill(plane.begin(), plane.end(), 0.0f);
    for (int y = 0; y < kernel_height; ++y)
      for (int x = 0; x < kernel_width; ++x)
        plane[static_cast<std::size_t>(y) * domain_width + x] =
            static_cast<float>((periodic.at(x, y, c) - mean) * normalisation);
    fft.forward(plane, spectrum);
    // One white noise for every channel keeps the exemplar's colour correlations.
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= noise_spectrum[i];
    fft.inverse(spectrum, plane);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        result.at(x, y, c) = static_cast<float>(
            mean +
            plane[static_cast<std::size_t>(y + kernel_height) * domain_width + x + kernel_width]);
  }
  return result;
}

}  // namespace stochtex
