#include "report/measures.hpp"

#include <array>

namespace stochtex {
namespace {

// The floor is only defined for the colour histogram: the exemplar's two halves have no spectrum
// of the synthesis' size, and their means and covariances are the exemplar's own.
constexpr std::array kMeasures = {
    Measure{"spectral_error", "spectral_error_adsn", "", "spectral error (rel. L1)",
            "spectral error",
            "relative L1 distance of the Welch power spectra (Hann-windowed crops) of the "
            "synthesis and the exemplar; the Gaussian version's value is the level of the ideal "
            "Gaussian texture, which texton, lrp and gabor noise approximate",
            "{:.3f}", &Quality::spectral_error, false, false},
    Measure{"averaged_spectral_error", "averaged_spectral_error_adsn", "",
            "averaged spectral error", "averaged spectral error",
            "relative L1 distance of the Welch power spectrum averaged over the renders of several "
            "seeds and the exemplar's: the bias of the synthesis's expected spectrum, with most of "
            "one render's shot noise averaged away (the difference to the spectral error); the "
            "Gaussian version's value is the exemplar's own estimator noise",
            "{:.3f}", &Quality::averaged_spectral_error, false, true},
    Measure{"histogram_error", "histogram_error_adsn", "histogram_error_floor",
            "colour histogram (SW2)", "colour error (SW2)",
            "sliced Wasserstein-2 distance between the pixel colours of the synthesis and of the "
            "exemplar (64 fixed directions); the floor is the exemplar's top half against its "
            "bottom half",
            "{:.4f}", &Quality::histogram_error, false, false},
    Measure{"mean_error", "", "", "mean error", "mean error",
            "Euclidean distance of the mean colours", "{:.4f}", &Quality::mean_error, false, false},
    Measure{"covariance_error", "", "", "covariance error (rel.)", "covariance error",
            "relative Frobenius distance of the colour covariance matrices", "{:.3f}",
            &Quality::covariance_error, false, false},
    Measure{
        "structure_error", "", "", "", "structure error",
        "mean over the octave bands (differences of Gaussians of 1, 2, 4, ... pixels, up to "
        "a 64th of the synthesis's side) of the relative distance between the kurtosis of the "
        "synthesis's band-pass responses and the exemplar's, on the mean of the channels: a "
        "Gaussian texture's is 3 in every band, so a Gaussian synthesis of an exemplar with "
        "edges, blobs or lines scores 1 - 3 / its kurtosis, which the spectral and colour "
        "errors do not show (a periodic pattern's loss it does not see: plaid's kurtosis is near "
        "3); the Gaussian version's value is that level",
        "{:.3f}", &Quality::structure_error, false, false},
    Measure{"nonstationarity", "", "", "", "non-stationarity",
            "coefficient of variation, over 4x4-sample blocks, of the per-sample variance across "
            "8 seeds of a 64x64 grid of point samples 2 exemplar pixels apart; the Gaussian "
            "version is exactly stationary, so its value is the estimator's noise",
            "{:.3f}", &Quality::nonstationarity, false, false},
    Measure{"analysis_seconds", "", "", "", "analysis (s)",
            "CPU seconds of one thread analysing the exemplar with the default parameters",
            "{:.2f}", &Quality::analysis_seconds, true, false},
    Measure{"ns_per_sample", "", "", "", "ns/sample",
            "CPU nanoseconds per sample of one thread rendering the report's image (scale 1, "
            "filtered)",
            "{:.0f}", &Quality::ns_per_sample, true, false},
};

}  // namespace

std::span<const Measure> measures() {
  return kMeasures;
}

}  // namespace stochtex
