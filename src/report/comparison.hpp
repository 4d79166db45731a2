#pragma once
// The measurements behind `stochtex report`: every method run on one exemplar with its default
// parameters, at the same size and seed as the exemplar's Gaussian version (ADSN), measured with
// the quality measures of docs/design.md §8 and timed. Each measurement is one call, so a caller
// can spread (exemplar, method) pairs over threads; every call is single-threaded apart from the
// sliced Wasserstein distance, and deterministic.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "metrics/metrics.hpp"
#include "report/pictures.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

struct ReportSettings {
  int width = 256;  // the size of every synthesis
  int height = 256;
  std::uint32_t seed = 1;  // the render seed (analysis uses seed 0, the CLI's default)
  // The averaged spectral error: the Welch spectrum averaged over renders (ADSN samples) of the
  // seeds seed, seed + 1, ..., seed + averaged_seeds - 1.
  int averaged_seeds = 4;
  // Stationarity: `stationarity_seeds` point-sampled renders of `stationarity_side`^2 samples
  // spaced `stationarity_step` exemplar pixels apart, their per-pixel variance averaged over
  // blocks of `stationarity_block`^2 samples (variance_nonstationarity).
  int stationarity_side = 64;
  int stationarity_step = 2;
  int stationarity_seeds = 8;
  int stationarity_block = 4;
  int histogram_bins = 64;
  int histogram_width = 192;  // histogram plot size in pixels
  int histogram_height = 96;
};

// What every synthesis of one exemplar is measured against, computed once per exemplar.
struct ExemplarReference {
  int crop = 0;                        // Welch crop side of the spectral error
  std::vector<double> spectrum;        // the exemplar's Welch spectrum, crop x crop
  SpectrumRange spectrum_range;        // shared by all spectrum pictures of the exemplar
  ColourStatistics statistics;         // the exemplar's mean and covariance
  ColourHistogram histogram;           // drawn under every histogram plot
  double histogram_top = 0.0;          // vertical range of every histogram plot
  double histogram_error_floor = 0.0;  // sliced W2 of the exemplar's top half vs bottom half
  // The exemplar's band_kurtosis (metrics/structure.hpp) in the bands both it and a synthesis of
  // the report's size measure: the reference of the structure error.
  std::vector<double> band_kurtosis;
  // The exemplar's side of the sliced W2 distance to every synthesis (levels x 64 doubles, 32 MB
  // for a 512^2 exemplar and 256^2 renders: release it once the exemplar's syntheses are done).
  std::optional<SlicedWassersteinReference> colours;
  ImageF spectrum_picture;  // the exemplar's own pictures
  ImageF histogram_picture;
};
ExemplarReference make_reference(ImageView<const float> exemplar, const ReportSettings& settings);

// One synthesis (a method's render or the ADSN sample) with its measures and pictures. Times are
// CPU seconds of the calling thread, so other work running beside it changes them little.
struct Synthesis {
  std::string name;  // the method, or "gaussian" for ADSN
  ImageF image;      // settings.width x settings.height
  Quality quality;   // all measures; the analysis and render times are 0 for ADSN
  ImageF spectrum_picture;
  ImageF averaged_spectrum_picture;  // of the spectrum averaged over settings.averaged_seeds
  ImageF histogram_picture;
};

// ADSN samples of the exemplar at the report's size and seed (and, for stationarity, at the
// stationarity grid's spacing), measured like a method.
Synthesis measure_gaussian(ImageView<const float> exemplar, const ExemplarReference& reference,
                           const ReportSettings& settings);
// `method` analysed with its default parameters and rendered on one thread.
Synthesis measure_method(std::string_view method, ImageView<const float> exemplar,
                         const ExemplarReference& reference, const ReportSettings& settings);

}  // namespace stochtex
