#pragma once
// Quality measures of docs/design.md §8, used by `stochtex compare`, the statistical tests and
// the docs. Every function takes views and returns plain numbers. Sums are accumulated in double.
// Invalid arguments (empty images, a crop that does not fit, channel counts that differ) throw
// std::invalid_argument. A relative error against a reference that is zero is 0 when the other
// term is zero too, +infinity otherwise.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

// Throws std::invalid_argument ("FUNCTION: the image is empty") unless `image` has pixels.
void require_pixels(ImageView<const float> image, const char* function);

// Welch power spectrum: mean of |FFT|^2 of Hann-windowed, mean-removed square crops of side
// `crop` with 50% overlap, summed over channels. Returned as crop x crop values, row-major with
// the vertical frequency as the row, DC at (0, 0) (both half-planes: the spectrum is symmetric).
// Crops start at 0, crop / 2, crop, ... while they fit inside the image, in both axes. The window
// is the periodic Hann window sin^2(pi n / crop) in each axis; each |FFT|^2 is divided by the sum
// of the squared window weights, so the result is a power spectral density whose mean over the
// crop^2 frequencies is the window-weighted variance: white noise of variance s^2 per channel gives
// a flat spectrum at channels * s^2 (less the one degree of freedom the mean removal takes, which
// lands on the 3 x 3 lowest frequencies). Requires 2 <= crop <= min(width, height).
std::vector<double> welch_power_spectrum(ImageView<const float> image, int crop);
// The crop size used by compare for a pair of images: the largest power of two <= half the smaller
// side of both, capped at 128 and at least 8. Images whose smaller side is below 8 pixels get the
// largest power of two <= that side (a single crop per axis); a side below 2 throws.
int welch_crop_size(ImageView<const float> a, ImageView<const float> b);
// Relative L1 distance sum|Sa - Sb| / sum|Sb| of the Welch spectra of a and of the reference b.
// Relative L1 distance sum|a - r| / sum|r| of two spectra of the same layout (the measure of
// spectral_error, for spectra averaged over several renders).
double relative_l1_distance(std::span<const double> a, std::span<const double> reference);

double spectral_error(ImageView<const float> image, ImageView<const float> reference, int crop);

inline constexpr int default_sliced_directions = 64;
// Sorts `values` ascending, to the same values as std::sort (none may be NaN), with Highway's
// vectorised quicksort: the empirical quantile functions of the measures below.
void sort_ascending(std::vector<double>& values);

// Sliced Wasserstein-2 distance between the pixel colour distributions: sqrt of the mean over
// directions of W2^2 between the 1-D projections. The directions are fixed (the same on every call
// and platform), so the distance is deterministic and symmetric; a 1-channel image has the single
// direction 1 whatever `directions` says. The two images may have different pixel counts: W2^2 =
// int_0^1 |Fa^-1(t) - Fb^-1(t)|^2 dt is evaluated by the midpoint rule at min(count_a, count_b)
// quantile levels of the empirical distributions (exact when the counts are equal).
double sliced_wasserstein(ImageView<const float> a, ImageView<const float> b,
                          int directions = default_sliced_directions);

// The reference side of sliced_wasserstein computed once, for many distances to one reference
// (the exemplar against each synthesis): its sorted projections kept at `levels` quantile levels.
// distance(image) equals sliced_wasserstein(image, reference, directions) bit for bit when
// min(image pixels, reference pixels) == levels, and throws std::invalid_argument otherwise.
// Holds levels x directions doubles.
class SlicedWassersteinReference {
 public:
  SlicedWassersteinReference(ImageView<const float> reference, std::size_t levels,
                             int directions = default_sliced_directions);
  double distance(ImageView<const float> image) const;

 private:
  int channels_ = 0;
  std::size_t pixels_ = 0;
  std::size_t levels_ = 0;
  std::vector<std::vector<double>> directions_;
  std::vector<std::vector<double>> quantiles_;  // per direction, at the levels
};

// channel_means and channel_covariance (core/colour_statistics.hpp) of the image.
struct ColourStatistics {
  std::vector<double> mean;        // per channel
  std::vector<double> covariance;  // channels x channels, row-major, divided by the pixel count
};
ColourStatistics colour_statistics(ImageView<const float> image);
// |mean_a - mean_b| (Euclidean) and ||cov_a - cov_b||_F / ||cov_b||_F.
double mean_error(const ColourStatistics& a, const ColourStatistics& b);
double covariance_error(const ColourStatistics& a, const ColourStatistics& reference);

// Stationarity (docs/design.md §8): `renders` are the same grid rendered with different seeds.
// The per-pixel variance across the renders, summed over channels, is averaged over block x block
// pixel blocks; the result is the coefficient of variation (standard deviation / mean) of those
// block variances. A stationary field gives only the estimator's noise (compare with the same
// measure of an exactly stationary field such as ADSN); a method whose variance follows its
// lattice gives more. Needs at least 2 renders of the same size and channel count, each at least
// block x block pixels; pixels beyond the last whole block are ignored.
double variance_nonstationarity(std::span<const ImageView<const float>> renders, int block);

// How far an image is from tiling seamlessly (WrapSteps, stochtex/model.hpp). A tileable image
// gives about 1 (0.85 to 1.25 on the shipped tileable exemplars: the wrap is one column's sample);
// a photo cut from a larger scene more (water_caustics_256 4.6, wood_planks_256 5.6 and 7.1,
// docs/inputs.md). Needs at least 2x2 pixels and an image that is not constant along the axis
// (else that axis gives 1).
WrapSteps wrap_steps(ImageView<const float> image);

// The measured numbers of one synthesis against its exemplar, as the rows of the measure table
// (report/measures.hpp) read them. Each caller fills the measures it takes: compare_images the
// first four, `stochtex report` all of them (the times for methods only, not for ADSN).
struct Quality {
  double spectral_error = 0.0;  // relative L1 distance of Welch spectra
  // The relative L1 distance of the Welch spectrum averaged over several renders (seeds): the
  // bias of the expected spectrum, with the shot noise of one render averaged away.
  double averaged_spectral_error = 0.0;
  double histogram_error = 0.0;   // sliced Wasserstein-2 distance of pixel colours
  double mean_error = 0.0;        // |mean - exemplar mean|
  double covariance_error = 0.0;  // relative Frobenius distance of colour covariances
  double nonstationarity = 0.0;   // variance_nonstationarity over renders with several seeds
  // The mean, over the octave bands, of |band kurtosis - the exemplar's| / the exemplar's
  // (metrics/structure.hpp): the edges, blobs and lines a Gaussian synthesis loses, which the
  // spectral and colour errors do not see (`stochtex report` only).
  double structure_error = 0.0;
  double analysis_seconds = 0.0;  // CPU seconds of analyze() with default parameters
  double ns_per_sample = 0.0;     // CPU nanoseconds per sample of a one-thread render
};

// The sliced W2 distance between the exemplar's top half and its bottom half: two disjoint
// samples of the same texture, so the distance a perfect synthesis could not beat.
double histogram_error_floor(ImageView<const float> exemplar);

struct ComparisonReport {
  int crop = 0;
  int images = 0;  // the syntheses measured; image holds the means of their measures
  Quality image;   // image vs exemplar: spectral, histogram, mean and covariance errors
  Quality adsn;    // ADSN samples of the exemplar (same size, as many) vs exemplar
  double histogram_error_floor = 0;  // exemplar top half vs bottom half
};

// `stochtex compare`: one or several syntheses of one model (renders of one size with different
// seeds) against the exemplar. Each image is measured on add(), and only running sums are kept,
// so memory stays at one image and one ADSN sample whatever the count. The report gives the mean
// of each measure over the images, and the averaged spectral error: the error of their mean
// Welch spectrum, which keeps the bias of the synthesis's expected spectrum and loses most of its
// shot noise (that falls as 1 / sqrt(images)). Image k (from 0) is set beside an ADSN sample
// adsn(exemplar, image size, seed + k), measured the same way. Throws std::invalid_argument on an
// empty image, another channel count or size than the first image's, and, before any work, when
// compare_peak_bytes exceeds the memory budget.
class Comparison {
 public:
  explicit Comparison(ImageView<const float> exemplar, std::uint32_t seed = 1);
  void add(ImageView<const float> image);
  // Throws std::logic_error before the first add().
  ComparisonReport report() const;
  int images() const { return images_; }
  int width() const { return width_; }  // the first image's size (0 before it)
  int height() const { return height_; }

 private:
  ImageView<const float> exemplar_;
  std::uint32_t seed_ = 1;
  ColourStatistics exemplar_statistics_;
  double histogram_error_floor_ = 0.0;
  int width_ = 0;
  int height_ = 0;
  int crop_ = 0;
  int images_ = 0;
  std::vector<double> exemplar_spectrum_;
  Quality image_sum_;
  Quality adsn_sum_;
  std::vector<double> image_spectrum_sum_;
  std::vector<double> adsn_spectrum_sum_;
};

// Throws std::invalid_argument, one sentence, when comparing a width x height image of `channels`
// channels with an exemplar_width x exemplar_height exemplar exceeds the memory budget
// (compare_peak_bytes): Comparison::add checks each image with it, and a caller may before it
// holds either (the Python module, before copying arrays).
void check_compare_budget(int exemplar_width, int exemplar_height, int width, int height,
                          int channels);

// One image: Comparison(exemplar, seed) with the image added.
ComparisonReport compare_images(ImageView<const float> exemplar, ImageView<const float> image,
                                std::uint32_t seed = 1);

}  // namespace stochtex
