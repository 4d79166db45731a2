#pragma once
// Every method on every exemplar, beside each exemplar's Gaussian version, measured in parallel:
// the work of `stochtex report`. The images are handed to the caller as soon as they are drawn and
// not kept, so memory stays at a few images per thread whatever the corpus size.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "metrics/metrics.hpp"
#include "report/comparison.hpp"
#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {

// One synthesis's numbers.
struct Outcome {
  std::string name;                  // the method, or "gaussian" for ADSN
  std::optional<std::string> error;  // set when the method failed on this exemplar
  Quality quality;
};

struct ExemplarResults {
  std::string path;  // as given
  std::string name;  // unique among the exemplars of a report
  ImageF image;
  int crop = 0;                        // Welch crop of the spectral error
  double histogram_error_floor = 0.0;  // the exemplar's halves against each other
  MethodChoice choice;                 // --method auto's, with its reason
  std::vector<Outcome> outcomes;       // the Gaussian version first, then the methods in order
};

// One kind of picture set of an exemplar: "exemplar", "gaussian" or a method's name.
struct Pictures {
  std::string_view kind;
  ImageView<const float> image;
  const ImageF& spectrum;
  const ImageF& averaged_spectrum;  // the exemplar's own spectrum for "exemplar"
  const ImageF& histogram;
};

// Both are called from the worker threads, several at once.
struct MeasureCallbacks {
  // Each picture set as soon as it is drawn. An exception thrown here (a file that cannot be
  // written) ends measure_all; a method that fails to analyse or render is an outcome instead.
  std::function<void(const ExemplarResults&, const Pictures&)> pictures;
  // Each outcome once it is final (measured or failed).
  std::function<void(const ExemplarResults&, const Outcome&)> finished;
};

// Fills crop, histogram_error_floor, choice and outcomes of every exemplar (path, name and image
// given): the Gaussian version and then every method of `methods`, with its default parameters, on
// `threads` threads. A method that fails on an exemplar is recorded in its outcome's error, not
// thrown. Returns the number of such failures.
int measure_all(std::vector<ExemplarResults>& exemplars, const std::vector<std::string>& methods,
                const ReportSettings& settings, int threads, const MeasureCallbacks& callbacks);

}  // namespace stochtex
