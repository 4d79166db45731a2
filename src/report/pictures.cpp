#include "report/pictures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/metrics.hpp"

namespace stochtex {
namespace {

using Rgb = std::array<float, 3>;

// The plotting colour of channel c of an image with `channels` channels.
Rgb channel_colour(int channels, int c) {
  constexpr Rgb black{0.0f, 0.0f, 0.0f};
  constexpr Rgb grey{0.55f, 0.55f, 0.55f};
  constexpr std::array<Rgb, 3> rgb{{{0.85f, 0.1f, 0.1f}, {0.1f, 0.6f, 0.1f}, {0.1f, 0.25f, 0.9f}}};
  if (channels <= 2) return c == 0 ? black : grey;
  return c < 3 ? rgb[static_cast<std::size_t>(c)] : grey;
}

// The plot row of a fraction: 0 at the bottom row, `top` (and above) at the top row.
int plot_row(double fraction, double top, int height) {
  const double level = std::clamp(fraction / top, 0.0, 1.0);
  return (height - 1) - static_cast<int>(std::lround(level * (height - 1)));
}

// Area weights of a box filter from `source` samples to `target` < source samples along one axis:
// output i covers the input interval [i s, (i + 1) s) with s = source / target.
struct AxisWeights {
  std::vector<int> first;  // first input index of each output
  std::vector<std::vector<double>> weights;
};

AxisWeights box_weights(int source, int target) {
  AxisWeights axis;
  const double step = static_cast<double>(source) / target;
  for (int i = 0; i < target; ++i) {
    const double begin = i * step;
    const double end = (i + 1) * step;
    const int first = static_cast<int>(std::floor(begin));
    const int last = std::min(source - 1, static_cast<int>(std::ceil(end)) - 1);
    std::vector<double> weights;
    for (int j = first; j <= last; ++j)
      weights.push_back((std::min<double>(end, j + 1) - std::max<double>(begin, j)) / step);
    axis.first.push_back(first);
    axis.weights.push_back(std::move(weights));
  }
  return axis;
}

}  // namespace

SpectrumRange spectrum_range(std::span<const double> reference) {
  std::vector<double> positive;
  for (const double value : reference)
    if (value > 0.0) positive.push_back(value);
  if (positive.empty())
    throw std::invalid_argument("spectrum_range: the reference spectrum has no positive value");
  std::sort(positive.begin(), positive.end());
  const double low = positive[positive.size() / 100];
  const double high = positive.back();
  // A flat spectrum still gets a range one decade wide, so the picture is not a division by zero.
  const double log_high = std::log10(high);
  const double log_low = std::min(std::log10(low), log_high - 1.0);
  return {log_low, log_high};
}

ImageF spectrum_picture(std::span<const double> spectrum, int side, SpectrumRange range) {
  if (side < 1 || spectrum.size() != static_cast<std::size_t>(side) * side)
    throw std::invalid_argument("spectrum_picture: the spectrum must have side x side values");
  if (!(range.high > range.low))
    throw std::invalid_argument("spectrum_picture: the range's high end must exceed its low end");
  ImageF picture(side, side, 1);
  const int half = side / 2;
  for (int ky = 0; ky < side; ++ky) {
    for (int kx = 0; kx < side; ++kx) {
      const double power = spectrum[static_cast<std::size_t>(ky) * side + kx];
      const double level =
          power > 0.0 ? (std::log10(power) - range.low) / (range.high - range.low) : 0.0;
      picture.at((kx + half) % side, (ky + half) % side, 0) =
          static_cast<float>(std::clamp(level, 0.0, 1.0));
    }
  }
  return picture;
}

std::pair<double, double> histogram_range(ImageView<const float> image) {
  require_pixels(image, "histogram_range");
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(image.width) * image.height * image.channels);
  for (int y = 0; y < image.height; ++y)
    values.insert(values.end(), image.row(y),
                  image.row(y) + static_cast<std::ptrdiff_t>(image.width) * image.channels);
  const auto quantile = [&values](double level) {
    const auto index = static_cast<std::size_t>(level * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                     values.end());
    return static_cast<double>(values[index]);
  };
  const double lowest = quantile(0.005);
  const double highest = quantile(0.995);
  const double margin = std::max(0.25 * (highest - lowest), 1e-3);
  const double low = lowest >= 0.0 ? std::max(0.0, lowest - margin) : lowest - margin;
  const double high = highest <= 1.0 ? std::min(1.0, highest + margin) : highest + margin;
  return {low, high};
}

double ColourHistogram::largest() const {
  return fractions.empty() ? 0.0 : *std::max_element(fractions.begin(), fractions.end());
}

ColourHistogram colour_histogram(ImageView<const float> image, int bins, double low, double high) {
  require_pixels(image, "colour_histogram");
  if (bins < 1) throw std::invalid_argument("colour_histogram: the bin count must be positive");
  if (!(high > low))
    throw std::invalid_argument("colour_histogram: the range's high end must exceed its low end");
  ColourHistogram histogram{image.channels, bins, low, high,
                            std::vector<double>(static_cast<std::size_t>(image.channels) * bins)};
  const double weight = 1.0 / (static_cast<double>(image.width) * image.height);
  const double bins_per_unit = bins / (high - low);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < image.channels; ++c) {
        const double value = image.at(x, y, c);
        const double position = std::isnan(value) ? 0.0 : (value - low) * bins_per_unit;
        const int bin = static_cast<int>(std::clamp(position, 0.0, bins - 1.0));
        histogram.fractions[static_cast<std::size_t>(c) * bins + bin] += weight;
      }
    }
  }
  return histogram;
}

ImageF histogram_picture(const ColourHistogram& histogram, const ColourHistogram& reference,
                         int width, int height, double top) {
  if (width < 1 || height < 2)
    throw std::invalid_argument("histogram_picture: the plot must be at least 1x2 pixels");
  if (!(top > 0.0)) throw std::invalid_argument("histogram_picture: the top must be positive");
  if (histogram.channels != reference.channels || histogram.bins != reference.bins ||
      histogram.fractions.size() != reference.fractions.size() ||
      histogram.fractions.size() != static_cast<std::size_t>(histogram.channels) * histogram.bins)
    throw std::invalid_argument(
        "histogram_picture: the histogram and its reference have different channels or bins");
  if (histogram.low != reference.low || histogram.high != reference.high)
    throw std::invalid_argument(
        "histogram_picture: the histogram and its reference cover different value ranges");
  ImageF picture(width, height, 3, 1.0f);
  const int bins = histogram.bins;
  const auto fraction = [bins](const ColourHistogram& h, int c, int x, int width_) {
    const int bin = static_cast<int>(static_cast<long long>(x) * bins / width_);
    return h.fractions[static_cast<std::size_t>(c) * bins + bin];
  };
  // The reference as pale areas: each channel tints the pixels under its curve by a quarter.
  constexpr float tint = 0.25f;
  for (int c = 0; c < reference.channels; ++c) {
    const Rgb colour = channel_colour(reference.channels, c);
    for (int x = 0; x < width; ++x) {
      for (int y = plot_row(fraction(reference, c, x, width), top, height); y < height; ++y)
        for (int k = 0; k < 3; ++k)
          picture.at(x, y, k) += tint * (colour[static_cast<std::size_t>(k)] - picture.at(x, y, k));
    }
  }
  // The histogram as a step line: in each column, the vertical span from the previous column's
  // row to this one's, so the line stays connected across steps.
  for (int c = 0; c < histogram.channels; ++c) {
    const Rgb colour = channel_colour(histogram.channels, c);
    int previous = plot_row(fraction(histogram, c, 0, width), top, height);
    for (int x = 0; x < width; ++x) {
      const int row = plot_row(fraction(histogram, c, x, width), top, height);
      for (int y = std::min(row, previous); y <= std::max(row, previous); ++y)
        for (int k = 0; k < 3; ++k) picture.at(x, y, k) = colour[static_cast<std::size_t>(k)];
      previous = row;
    }
  }
  return picture;
}

ImageF downscale(ImageView<const float> image, int max_side) {
  require_pixels(image, "downscale");
  if (max_side < 1)
    throw std::invalid_argument("downscale: the largest side must be positive, not " +
                                std::to_string(max_side));
  const int larger = std::max(image.width, image.height);
  const int width = larger <= max_side
                        ? image.width
                        : std::max(1, static_cast<int>(std::lround(
                                          static_cast<double>(image.width) * max_side / larger)));
  const int height = larger <= max_side
                         ? image.height
                         : std::max(1, static_cast<int>(std::lround(
                                           static_cast<double>(image.height) * max_side / larger)));
  const AxisWeights columns = box_weights(image.width, width);
  const AxisWeights rows = box_weights(image.height, height);
  ImageF result(width, height, image.channels);
  std::vector<double> sums(static_cast<std::size_t>(image.channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::fill(sums.begin(), sums.end(), 0.0);
      const auto& row_weights = rows.weights[static_cast<std::size_t>(y)];
      const auto& column_weights = columns.weights[static_cast<std::size_t>(x)];
      for (std::size_t j = 0; j < row_weights.size(); ++j) {
        for (std::size_t i = 0; i < column_weights.size(); ++i) {
          const double weight = row_weights[j] * column_weights[i];
          const int source_x = columns.first[static_cast<std::size_t>(x)] + static_cast<int>(i);
          const int source_y = rows.first[static_cast<std::size_t>(y)] + static_cast<int>(j);
          for (int c = 0; c < image.channels; ++c)
            sums[static_cast<std::size_t>(c)] += weight * image.at(source_x, source_y, c);
        }
      }
      for (int c = 0; c < image.channels; ++c)
        result.at(x, y, c) = static_cast<float>(sums[static_cast<std::size_t>(c)]);
    }
  }
  return result;
}

}  // namespace stochtex
