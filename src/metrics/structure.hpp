#pragma once
// How far an image is from a Gaussian texture, in the two measures `--method auto` chooses by
// (docs/comparison.md "Which method?", docs/design.md §8) and the report's structure error: the
// kurtosis of its band-pass responses, and the share of its power in spectral peaks. Both are
// taken on the mean of the channels (its luminance for a colour image), as stored: structure shows
// there, and a channel of small variance (wood's blue) would give its quantisation's kurtosis.

#include <vector>

#include "stochtex/image.hpp"

namespace stochtex {

// The kurtosis E[b^4] / E[b^2]^2 of the band-pass responses b of the image's periodic component
// (Moisan 2011, so that a non-tileable image's wrap is no edge): difference-of-Gaussians octaves
// G(s / 2) - G(s) for s = 1, 2, 4, ... pixels, `bands` of them, the first at s = 1. Any linear
// filter of a Gaussian texture is Gaussian, of kurtosis 3 (ADSN versions of the shipped exemplars
// measure 2.9 to 3.3); the edges, blobs and lines of a structured texture concentrate its band
// energy and raise it (water_caustics_256: 19.7 at s = 1). A band with no variance counts 3.
// Throws std::invalid_argument for an empty image or bands < 1.
std::vector<double> band_kurtosis(ImageView<const float> image, int bands);
// The bands band_kurtosis measures well on a width x height image: s up to the smaller side / 64
// (at least 64 wavelengths of the band across it; ADSN samples' estimator spread stays within
// 3 +- 0.3 there), at least one.
int kurtosis_bands(int width, int height);

// The share of the image's power in spectral peaks: the Hann-windowed, mean-removed periodogram,
// bins at least 4 bins from DC; a bin is a peak when its power exceeds 16 times the median of its
// 9 x 9 neighbourhood. A smooth spectrum (a Gaussian texture's) has a bin's power exponentially
// distributed about the median / ln 2, so a bin passes 16 medians with probability 2^-16 and the
// share stays near 0 (shipped gaussian exemplars: 0.000 to 0.041); a periodic pattern puts its
// power in a few peaks (plaid_fabric_256: 0.78). Needs at least 2 x 2 pixels; 0 for a constant
// image.
double spectral_peak_fraction(ImageView<const float> image);
// Above this share of its power in spectral peaks an image is periodic. The non-periodic shipped
// exemplars measure at most 0.041 (brushed_aluminium_grey_256, whose streaks make a ridge); the
// periodic ones 0.12 (bricks_stone_wall_512's courses) to 0.78 (plaid_fabric_256).
inline constexpr double kPeriodicPeakFraction = 0.1;

}  // namespace stochtex
