#pragma once
// stochtex: procedural texture synthesis by example.
//
// Conventions, obeyed by every function:
//  - Model space: one unit = one exemplar pixel. Images are float32, interleaved, 1 to 4 channels.
//  - Inputs are views, outputs are owned values. The seed is always an argument, never state.
//  - Analysis and I/O throw stochtex::Error (bad data, files) or std::invalid_argument (bad
//    parameters) with one sentence a user can act on; evaluation never throws and never allocates.
//  - Results are bit-identical for the same inputs, whatever the thread count or tiling.
//
// Linking: stochtex::runtime gives model.hpp and render.hpp (load, evaluate, render);
// stochtex::analysis adds the functions below (FFTW, Eigen).

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "stochtex/error.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"

namespace stochtex {

// The methods and their described parameters.
std::span<const MethodInfo> methods();
// Throws std::invalid_argument naming the known methods when `name` is not one.
const MethodInfo& method_info(std::string_view name);

// Completes `given` with defaults and checks every value (known name, number, integer, range,
// choices); throws std::invalid_argument with one sentence naming the parameter.
ParamValues resolve_params(std::string_view method, const ParamValues& given);
// The same from text values (the CLI's -p key=value): a number, or for a parameter with choices
// (an enumeration such as tiling's blend, or an off/on switch) the choice's name or number.
ParamValues resolve_params(std::string_view method,
                           const std::map<std::string, std::string, std::less<>>& given);
// A parameter value as a user writes it: the choice's name where the parameter has one for
// `value`, else the number (`stochtex info`).
std::string format_param(std::string_view method, std::string_view name, double value);

// `stochtex methods`: every method with its parameters, defaults and help, as text lines or as
// one JSON document (the ParamInfo fields, plus `allowed` and `choices` for enumerations).
std::string methods_text();
std::string methods_json();

// The largest magnitude of an exemplar value (docs/design.md §9). Analysis squares values and sums
// them over up to 2^26 pixels in float (power spectra, covariances): (1e6 * 2^26)^2 = 4.5e27 keeps
// a margin of 1e10 below float's 3.4e38, and HDR exemplars in scene units (the sun near 1e5) fit;
// larger values are refused rather than rendered as NaN.
inline constexpr float kMaxExemplarValue = 1e6f;

// Checks an exemplar: at least 2x2 pixels, 1 to `max_channels` channels, finite values within
// +-kMaxExemplarValue, not constant. Throws Error(invalid_input) with a sentence naming
// `source_name`.
void validate_exemplar(ImageView<const float> exemplar, const std::string& source_name,
                       int max_channels = kMaxImageChannels);

// About the peak memory, in bytes, of analysing a width x height exemplar of `channels` channels
// with `method` (docs/design.md §9; the method's registry row, measured).
std::uint64_t analysis_peak_bytes(std::string_view method, int width, int height, int channels);

// Builds a model of the exemplar with the named method. `params` may be partial (defaults fill it).
// Throws std::invalid_argument, before any work, when analysis_peak_bytes exceeds the memory
// budget of 2 GiB. `progress`, when given, is called from the calling thread with the fraction
// done (non-decreasing, 1 at the end): during the iterations of texton's and gabor's analyses,
// at the end for the others. An exception it throws stops the analysis at the next iteration
// and propagates out of analyze() (how a caller cancels it).
// `colour_space` says what the exemplar's values are (stochtex/colour.hpp): srgb for an ordinary
// photo read with its colour (read_image's ImageColour), whose model renders linear light; data
// (the default) keeps the values as they are, as every model before colour spaces did.
Model analyze(std::string_view method, ImageView<const float> exemplar,
              const ParamValues& params = {}, std::uint32_t seed = 0,
              const std::string& source_name = "exemplar",
              const std::function<void(double)>& progress = {},
              ColourSpace colour_space = ColourSpace::data);

// Texton noise mixing (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017, section 7): a model
// whose texture goes from exemplar a's texton noise (rho = 0) to b's (rho = 1) along a ramp, or as
// a grey mask (1 channel, values in [0, 1]) says. params: method texton_mix's (steps, the ramp,
// mask_scale, and texton's support, order, iterations, mni). a and b must have the same channel
// count; the larger is centre-cropped to the smaller's size. Throws Error(invalid_input) with a
// sentence naming the file, std::invalid_argument for a bad parameter.
struct MixInputs {
  ImageView<const float> a;
  ImageView<const float> b;
  std::string a_name = "A";
  std::string b_name = "B";
  std::optional<ImageView<const float>> mask;
  std::string mask_name = "mask";
};
Model mix(const MixInputs& inputs, const ParamValues& params = {}, std::uint32_t seed = 0);

// `--method auto` (docs/comparison.md "Which method?"): a registered method chosen from measured
// properties of the exemplar, with one line saying why. Tiling where the exemplar is far from
// Gaussian (its band-pass kurtosis, metrics/structure.hpp, above 4) or periodic (more than 10% of
// its power in spectral peaks): the Gaussian methods would blur its edges, shapes or pattern;
// else texton, the Gaussian method that renders fastest. The thresholds are measured on the
// shipped exemplars; the measures are taken on the mean of the channels, as stored, so data
// exemplars are measured alike. Deterministic; about 0.1 s for 512^2 pixels. Throws
// std::invalid_argument for an empty image.
inline constexpr std::string_view kAutoMethod = "auto";
struct MethodChoice {
  std::string method;          // the chosen method's name
  std::string reason;          // "tiling: far from Gaussian (...): ...", one line
  double band_kurtosis = 3.0;  // the largest band-pass kurtosis
  int band_scale = 1;          // the band's scale s, in pixels, where it is largest
  double peak_fraction = 0.0;  // the share of the power in spectral peaks
  double wrap_step = 1.0;      // wrap_steps(exemplar).largest() (metrics/metrics.hpp)
};
MethodChoice choose_method(ImageView<const float> exemplar);

// The Gaussian version of the exemplar (ADSN), at any size: the ideal Gaussian texture that
// texton, lrp and gabor noise approximate.
ImageF gaussian_version(ImageView<const float> exemplar, int width, int height, std::uint32_t seed);

}  // namespace stochtex
