#include "report/measure_all.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <optional>

#include "core/parallel.hpp"
#include "registry.hpp"

namespace stochtex {

int measure_all(std::vector<ExemplarResults>& exemplars, const std::vector<std::string>& methods,
                const ReportSettings& settings, int threads, const MeasureCallbacks& callbacks) {
  // Per exemplar: what every synthesis is measured against, and the Gaussian version.
  std::vector<ExemplarReference> references(exemplars.size());
  parallel_for(exemplars.size(), threads, [&](std::size_t i) {
    ExemplarResults& exemplar = exemplars[i];
    references[i] = make_reference(exemplar.image.view(), settings);
    const ExemplarReference& reference = references[i];
    exemplar.crop = reference.crop;
    exemplar.histogram_error_floor = reference.histogram_error_floor;
    exemplar.choice = choose_method(exemplar.image.view());
    callbacks.pictures(exemplar, {"exemplar", exemplar.image.view(), reference.spectrum_picture,
                                  reference.spectrum_picture, reference.histogram_picture});
    const Synthesis gaussian = measure_gaussian(exemplar.image.view(), reference, settings);
    callbacks.pictures(exemplar, {gaussian.name, gaussian.image.view(), gaussian.spectrum_picture,
                                  gaussian.averaged_spectrum_picture, gaussian.histogram_picture});
    exemplar.outcomes.resize(1 + methods.size());
    exemplar.outcomes[0].name = gaussian.name;
    exemplar.outcomes[0].quality = gaussian.quality;
    callbacks.finished(exemplar, exemplar.outcomes[0]);
  });

  // Every (exemplar, method) pair, the most expensive first so that the last tasks to start are
  // short ones: an analysis grows with the pixel and channel counts, times its registry row's
  // relative cost (gabor's sparse fit dominates).
  struct Task {
    std::size_t exemplar;
    std::size_t method;
    double cost;
  };
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < exemplars.size(); ++i) {
    const double size =
        static_cast<double>(exemplars[i].image.pixel_count()) * exemplars[i].image.channels();
    for (std::size_t m = 0; m < methods.size(); ++m)
      tasks.push_back({i, m, analysis_cost(methods[m]) * size});
  }
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const Task& a, const Task& b) { return a.cost > b.cost; });
  std::atomic<int> failures{0};
  std::vector<std::atomic<std::size_t>> remaining(exemplars.size());
  for (auto& count : remaining) count = methods.size();
  parallel_for(tasks.size(), threads, [&](std::size_t t) {
    ExemplarResults& exemplar = exemplars[tasks[t].exemplar];
    const std::string& method = methods[tasks[t].method];
    Outcome& outcome = exemplar.outcomes[1 + tasks[t].method];
    outcome.name = method;
    std::optional<Synthesis> synthesis;
    try {
      synthesis =
          measure_method(method, exemplar.image.view(), references[tasks[t].exemplar], settings);
      outcome.quality = synthesis->quality;
    } catch (const std::exception& e) {
      outcome.error = e.what();
      ++failures;
    }
    // Outside the try: a method that fails is a row of the report, a picture that cannot be
    // written ends the report.
    if (synthesis)
      callbacks.pictures(exemplar,
                         {method, synthesis->image.view(), synthesis->spectrum_picture,
                          synthesis->averaged_spectrum_picture, synthesis->histogram_picture});
    if (--remaining[tasks[t].exemplar] == 0) references[tasks[t].exemplar].colours.reset();
    callbacks.finished(exemplar, outcome);
  });
  return failures;
}

}  // namespace stochtex
