#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "report/measure_all.hpp"
#include "report/measures.hpp"

namespace stochtex::report_test {
namespace {

// One row per measure: scripts and the CLI find a measure by its keys, so none may repeat.
TEST(Measures, KeysAreUniqueAndEveryValueIsItsOwn) {
  std::set<std::string_view> keys;
  std::vector<double Quality::*> values;
  for (const Measure& measure : measures()) {
    for (const std::string_view key : {measure.key, measure.adsn_key, measure.floor_key}) {
      if (!key.empty()) {
        EXPECT_TRUE(keys.insert(key).second) << key;
      }
    }
    EXPECT_EQ(std::find(values.begin(), values.end(), measure.value), values.end()) << measure.key;
    values.push_back(measure.value);
    EXPECT_FALSE(measure.title.empty()) << measure.key;
    EXPECT_FALSE(measure.help.empty()) << measure.key;
    // compare shows the ADSN and floor columns only for its own rows.
    if (measure.compare_label.empty()) {
      EXPECT_TRUE(measure.adsn_key.empty()) << measure.key;
    }
    if (!measure.floor_key.empty()) {
      EXPECT_FALSE(measure.adsn_key.empty()) << measure.key;
    }
  }
}

ImageF noisy_exemplar() {
  std::mt19937 rng(5);
  ImageF image(48, 48, 3);
  for (float& value : image.pixels())
    value = static_cast<float>(0.2 + 0.6 * (static_cast<double>(rng()) / 4294967296.0));
  return image;
}

ReportSettings small_settings() {
  ReportSettings settings;
  settings.width = 32;
  settings.height = 32;
  settings.stationarity_side = 8;
  settings.stationarity_seeds = 2;
  return settings;
}

struct Seen {
  std::mutex mutex;
  std::vector<std::string> pictures;
  std::vector<std::string> finished;
};

MeasureCallbacks recording(Seen& seen, const std::string& failing_kind) {
  MeasureCallbacks callbacks;
  callbacks.pictures = [&seen, failing_kind](const ExemplarResults&, const Pictures& pictures) {
    if (pictures.kind == failing_kind) throw std::runtime_error("disk full");
    const std::lock_guard lock(seen.mutex);
    seen.pictures.emplace_back(pictures.kind);
  };
  callbacks.finished = [&seen](const ExemplarResults&, const Outcome& outcome) {
    const std::lock_guard lock(seen.mutex);
    seen.finished.push_back(outcome.name);
  };
  return callbacks;
}

TEST(MeasureAll, MeasuresTheGaussianVersionAndEveryMethod) {
  std::vector<ExemplarResults> exemplars(1);
  exemplars[0].image = noisy_exemplar();
  Seen seen;
  const int failures = measure_all(exemplars, {"tiling"}, small_settings(), 2, recording(seen, ""));
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(seen.pictures, (std::vector<std::string>{"exemplar", "gaussian", "tiling"}));
  EXPECT_EQ(seen.finished, (std::vector<std::string>{"gaussian", "tiling"}));
  const ExemplarResults& exemplar = exemplars[0];
  EXPECT_GT(exemplar.crop, 0);
  EXPECT_GT(exemplar.histogram_error_floor, 0.0);
  ASSERT_EQ(exemplar.outcomes.size(), 2u);
  EXPECT_EQ(exemplar.outcomes[0].name, "gaussian");
  EXPECT_GT(exemplar.outcomes[0].quality.spectral_error, 0.0);
  EXPECT_EQ(exemplar.outcomes[0].quality.analysis_seconds, 0.0);
  EXPECT_FALSE(exemplar.outcomes[1].error);
  EXPECT_GT(exemplar.outcomes[1].quality.spectral_error, 0.0);
  EXPECT_GT(exemplar.outcomes[1].quality.ns_per_sample, 0.0);
}

// A picture that cannot be written (a full disk) ends the report: it is one output, written
// whole or not at all (an AtomicFileSet in the CLI), so it does not go on without the file.
TEST(MeasureAll, APictureThatCannotBeWrittenEndsTheReport) {
  std::vector<ExemplarResults> exemplars(1);
  exemplars[0].image = noisy_exemplar();
  Seen seen;
  EXPECT_THROW(measure_all(exemplars, {"tiling"}, small_settings(), 1, recording(seen, "tiling")),
               std::runtime_error);
}

}  // namespace
}  // namespace stochtex::report_test
