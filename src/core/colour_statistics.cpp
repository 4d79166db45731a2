#include "core/colour_statistics.hpp"

#include <cstddef>

namespace stochtex {
namespace {

double pixel_count(ImageView<const float> image) {
  return static_cast<double>(image.width) * image.height;
}

// Entry (i, j) of the covariance about `mean`, for all (i, j) or the diagonal alone. `Mean` is
// float or double: the centred values take its precision (see the header).
template <typename Mean>
std::vector<double> covariance_about(ImageView<const float> image, std::span<const Mean> mean,
                                     bool diagonal) {
  const auto channels = static_cast<std::size_t>(image.channels);
  std::vector<double> covariance(diagonal ? channels : channels * channels, 0.0);
  std::vector<Mean> centred(channels);
  // Around the mean, not from raw second moments: summing raw squares would cancel
  // catastrophically for images with a large mean and a small variance.
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      for (std::size_t c = 0; c < channels; ++c)
        centred[c] = image.at(x, y, static_cast<int>(c)) - mean[c];
      if (diagonal) {
        for (std::size_t c = 0; c < channels; ++c)
          covariance[c] += static_cast<double>(centred[c]) * centred[c];
      } else {
        for (std::size_t i = 0; i < channels; ++i)
          for (std::size_t j = 0; j < channels; ++j)
            covariance[i * channels + j] += static_cast<double>(centred[i]) * centred[j];
      }
    }
  const double n = pixel_count(image);
  for (double& value : covariance) value /= n;
  return covariance;
}

}  // namespace

std::vector<double> channel_means(ImageView<const float> image) {
  std::vector<double> mean(static_cast<std::size_t>(image.channels), 0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < image.channels; ++c)
        mean[static_cast<std::size_t>(c)] += image.at(x, y, c);
  const double n = pixel_count(image);
  for (double& value : mean) value /= n;
  return mean;
}

std::vector<double> channel_covariance(ImageView<const float> image, std::span<const double> mean) {
  return covariance_about(image, mean, false);
}

std::vector<double> channel_covariance(ImageView<const float> image, std::span<const float> mean) {
  return covariance_about(image, mean, false);
}

std::vector<double> channel_variances(ImageView<const float> image, std::span<const double> mean) {
  return covariance_about(image, mean, true);
}

}  // namespace stochtex
