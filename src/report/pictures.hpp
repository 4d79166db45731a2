#pragma once
// Small pictures of measurements for `stochtex report`, drawn by simple rasterisation into float
// images (values in [0, 1]) that any image writer can save: a power spectrum on a log scale, a
// colour histogram as a plot, and box-filtered thumbnails. Invalid arguments throw
// std::invalid_argument.

#include <span>
#include <utility>
#include <vector>

#include "stochtex/image.hpp"

namespace stochtex {

// The grey levels of a log-scale spectrum picture: log10 of the power mapped linearly from `low`
// (black) to `high` (white), both in log10 units.
struct SpectrumRange {
  double low = 0.0;
  double high = 1.0;
};
// The range that shows `reference` (a power spectrum) from its 1% quantile to its maximum: used
// for the exemplar and every synthesis of it, so that their pictures share one scale.
SpectrumRange spectrum_range(std::span<const double> reference);

// A side x side grey picture of a power spectrum laid out as welch_power_spectrum returns it (row
// = vertical frequency, DC at (0, 0)), with the DC moved to the centre pixel (side / 2, side / 2).
// Values at or below zero are black.
ImageF spectrum_picture(std::span<const double> spectrum, int side, SpectrumRange range);

// Per-channel histograms of pixel values over [low, high] in `bins` equal bins; values outside
// (and NaN, counted as `low`) land in the end bins. `fractions[c * bins + b]` is the fraction of
// the pixels whose channel c falls in bin b (each channel sums to 1).
struct ColourHistogram {
  int channels = 0;
  int bins = 0;
  double low = 0.0;
  double high = 1.0;
  std::vector<double> fractions;
  double largest() const;  // the largest fraction of any bin of any channel
};
ColourHistogram colour_histogram(ImageView<const float> image, int bins, double low = 0.0,
                                 double high = 1.0);
// A value range that shows the histogram of `image` and of syntheses of it: from its 0.5% to its
// 99.5% quantile over all channels, widened by a quarter of that span on each side and kept within
// [0, 1] (the range of image files) unless the values themselves leave it.
std::pair<double, double> histogram_range(ImageView<const float> image);

// A width x height RGB plot of `histogram` over `reference` (for example a synthesis over its
// exemplar): each channel of the reference is a pale filled area and each channel of `histogram`
// a line, in the channel's colour (grey: black; RGB: red, green, blue; a second or fourth channel,
// alpha: grey). The vertical axis runs from 0 to `top` (fractions above it are clipped), so plots
// drawn with the same `top` compare directly. The histograms must have the same channels, bins and
// range.
ImageF histogram_picture(const ColourHistogram& histogram, const ColourHistogram& reference,
                         int width, int height, double top);

// The image shrunk so that its larger side is at most `max_side`, keeping its aspect ratio, by an
// area-weighted box filter (each output pixel is the exact mean of the input area it covers).
// Images already small enough are copied.
ImageF downscale(ImageView<const float> image, int max_side);

}  // namespace stochtex
