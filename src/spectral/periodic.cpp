#include "spectral/periodic.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <vector>

#include "spectral/fft.hpp"

namespace stochtex {

ImageF periodic_component(ImageView<const float> image) {
  const int w = image.width;
  const int h = image.height;
  ImageF result(w, h, image.channels);
  Fft2d fft(w, h);
  std::vector<float> boundary(fft.image_size());
  std::vector<float> smooth(fft.image_size());
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  // Denominator of the discrete Poisson problem: 2cos(2pi q/w) + 2cos(2pi r/h) - 4.
  std::vector<double> cos_x(static_cast<std::size_t>(fft.spectrum_width()));
  std::vector<double> cos_y(static_cast<std::size_t>(h));
  for (int q = 0; q < fft.spectrum_width(); ++q)
    cos_x[q] = 2.0 * std::cos(2.0 * std::numbers::pi * q / w);
  for (int r = 0; r < h; ++r) cos_y[r] = 2.0 * std::cos(2.0 * std::numbers::pi * r / h);

  for (int c = 0; c < image.channels; ++c) {
    // The boundary image v: the jumps across the image border, as in Moisan's eq. (13).
    std::fill(boundary.begin(), boundary.end(), 0.0f);
    auto b = [&](int x, int y) -> float& { return boundary[static_cast<std::size_t>(y) * w + x]; };
    for (int y = 0; y < h; ++y) {
      const float jump = image.at(w - 1, y, c) - image.at(0, y, c);
      b(0, y) += jump;
      b(w - 1, y) -= jump;
    }
    for (int x = 0; x < w; ++x) {
      const float jump = image.at(x, h - 1, c) - image.at(x, 0, c);
      b(x, 0) += jump;
      b(x, h - 1) -= jump;
    }
    fft.forward(boundary, spectrum);
    for (int r = 0; r < h; ++r) {
      for (int q = 0; q < fft.spectrum_width(); ++q) {
        const std::size_t i = static_cast<std::size_t>(r) * fft.spectrum_width() + q;
        const double denominator = cos_x[q] + cos_y[r] - 4.0;
        spectrum[i] = (q == 0 && r == 0) ? std::complex<float>(0.0f)
                                         : spectrum[i] / static_cast<float>(denominator);
      }
    }
    fft.inverse(spectrum, smooth);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        result.at(x, y, c) = image.at(x, y, c) - smooth[static_cast<std::size_t>(y) * w + x];
  }
  return result;
}

ImageF periodic_keeping_histogram(ImageView<const float> image) {
  ImageF result = periodic_component(image);
  const int width = image.width;
  const std::size_t pixels = static_cast<std::size_t>(width) * image.height;
  std::vector<std::size_t> order(pixels);
  std::vector<float> values(pixels);
  std::vector<float> periodic(pixels);
  for (int c = 0; c < image.channels; ++c) {
    // Each channel's values copied out once, so that the sort compares floats in one array.
    for (std::size_t i = 0; i < pixels; ++i) {
      const int x = static_cast<int>(i % width);
      const int y = static_cast<int>(i / width);
      order[i] = i;
      values[i] = image.at(x, y, c);
      periodic[i] = result.at(x, y, c);
    }
    std::sort(values.begin(), values.end());
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return periodic[a] < periodic[b]; });
    for (std::size_t k = 0; k < pixels; ++k)
      result.at(static_cast<int>(order[k] % width), static_cast<int>(order[k] / width), c) =
          values[k];
  }
  return result;
}

}  // namespace stochtex
