#pragma once
// Colour statistics: the mean of each channel and the covariance of the channels. One definition
// serves the analyses (the mean a model stores, the colour decorrelation of tiling and lrp,
// texton's covariance correction), the runtime (tiling's per-level variances) and the metrics, so
// every model file and measurement sums in the same order. Their principal components are in
// spectral/principal_components.hpp.

#include <span>
#include <vector>

#include "stochtex/image.hpp"

namespace stochtex {

// Mean of each channel: the pixels summed in raster order in double, divided by the pixel count.
std::vector<double> channel_means(ImageView<const float> image);

// Covariance of the channels about `mean` (channels x channels, row-major), summed in raster order
// in double and divided by the pixel count n, not n - 1: the image is the whole texture whose
// second-order statistics the synthesis reproduces, not a sample of it. Each value is centred in
// the precision of `mean`: a float mean (the one a model stores and centres its kernel with)
// centres in float, a double mean in double.
std::vector<double> channel_covariance(ImageView<const float> image, std::span<const double> mean);
std::vector<double> channel_covariance(ImageView<const float> image, std::span<const float> mean);
// Its diagonal alone: the variance of each channel, the same values in fewer operations.
std::vector<double> channel_variances(ImageView<const float> image, std::span<const double> mean);

}  // namespace stochtex
