// `--method auto`: the method chosen from measured properties of the exemplar (docs/comparison.md
// "Which method?", where the thresholds below are measured on every shipped exemplar).

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include "metrics/metrics.hpp"
#include "metrics/structure.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

// Above this band-pass kurtosis an exemplar is not Gaussian. ADSN versions of the 17 shipped
// exemplars (8 seeds each) measure at most 3.26, the Gaussian-looking exemplars at most 3.34
// (wool_knit_blue_256, which is periodic instead); the least non-Gaussian of the others measure
// 4.40 (cobblestone_512) and 4.42 (wood_planks_256).
constexpr double kGaussianBandKurtosis = 4.0;

[[gnu::format(printf, 1, 2)]] std::string choice_text(const char* format, ...) {
  std::vector<char> text(512);
  va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(text.data(), text.size(), format, arguments);
  va_end(arguments);
  return text.data();
}

}  // namespace

MethodChoice choose_method(ImageView<const float> exemplar) {
  require_pixels(exemplar, "choose_method");
  MethodChoice choice;
  const std::vector<double> kurtosis =
      band_kurtosis(exemplar, kurtosis_bands(exemplar.width, exemplar.height));
  const auto largest = std::max_element(kurtosis.begin(), kurtosis.end());
  choice.band_kurtosis = *largest;
  choice.band_scale = 1 << static_cast<int>(largest - kurtosis.begin());
  choice.peak_fraction = spectral_peak_fraction(exemplar);
  choice.wrap_step = wrap_steps(exemplar).largest();
  const bool structured = choice.band_kurtosis > kGaussianBandKurtosis;
  const bool periodic = choice.peak_fraction > kPeriodicPeakFraction;
  const std::string kurtosis_text =
      choice_text("band-pass kurtosis %.1f at %d px, a Gaussian texture's is 3",
                  choice.band_kurtosis, choice.band_scale);
  const std::string peaks_text =
      choice_text("%.0f%% of its power in spectral peaks", 100.0 * choice.peak_fraction);
  if (structured || periodic) {
    choice.method = "tiling";
    choice.reason = structured
                        ? choice_text(
                              "tiling: far from Gaussian (%s; auto's line %.0f): only tiling "
                              "keeps its edges, shapes and histogram, the Gaussian methods "
                              "blur them",
                              kurtosis_text.c_str(), kGaussianBandKurtosis)
                        : choice_text(
                              "tiling: periodic (%s; auto's line %.0f%%): only tiling keeps "
                              "its pattern, the Gaussian methods scramble it",
                              peaks_text.c_str(), 100.0 * kPeriodicPeakFraction);
  } else {
    choice.method = "texton";
    choice.reason = choice_text(
        "texton: close to Gaussian (%s; %s; auto's lines %.0f and %.0f%%): a Gaussian method "
        "reproduces it, and texton renders 15 to 60 times as fast as lrp and gabor",
        kurtosis_text.c_str(), peaks_text.c_str(), kGaussianBandKurtosis,
        100.0 * kPeriodicPeakFraction);
  }
  return choice;
}

}  // namespace stochtex
