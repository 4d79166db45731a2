// Definition of done for every method: `synth` works on every image of the corpus, structured ones
// included (they may look wrong; they must not fail), with finite values near the exemplar's mean,
// point-sampled and zoomed out (filtered).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "shared.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::corpus_test {
namespace {

// The photos a Gaussian model is meant for take the shared fixture's default models (shared.hpp),
// made once for the fidelity and quality tests; the other exemplars take cheaper-than-default
// settings where the default only costs time (the defaults are exercised by each method's own
// statistical tests).
const std::map<std::string, ParamValues, std::less<>> kFastParams = {
    {"texton", {{"support", 64}}},
    // Coarser fit (homotopy down to kappa = 1/16, 50 FISTA steps) and a small impulse budget:
    // the default fit of a 512² colour exemplar takes about half a minute.
    {"gabor", {{"kappa", 1.0 / 16.0}, {"iterations", 50}, {"impulses", 64}}},
};

// The standard deviation, per channel, of the means of the exemplar's 64 x 64 windows (stride 32):
// how far the mean of a 64 x 64 piece of this texture strays from the global mean by itself.
std::vector<double> window_mean_deviation(const ImageF& image) {
  constexpr int kWindow = 64;
  const int channels = image.channels();
  std::vector<double> sum(static_cast<std::size_t>(channels), 0.0);
  std::vector<double> square(static_cast<std::size_t>(channels), 0.0);
  int windows = 0;
  for (int y0 = 0; y0 + kWindow <= image.height(); y0 += kWindow / 2)
    for (int x0 = 0; x0 + kWindow <= image.width(); x0 += kWindow / 2) {
      for (int c = 0; c < channels; ++c) {
        double mean = 0.0;
        for (int y = y0; y < y0 + kWindow; ++y)
          for (int x = x0; x < x0 + kWindow; ++x) mean += image.at(x, y, c);
        mean /= kWindow * kWindow;
        sum[static_cast<std::size_t>(c)] += mean;
        square[static_cast<std::size_t>(c)] += mean * mean;
      }
      ++windows;
    }
  std::vector<double> deviation(static_cast<std::size_t>(channels));
  for (std::size_t c = 0; c < deviation.size(); ++c) {
    const double mean = sum[c] / windows;
    deviation[c] = std::sqrt(std::max(0.0, square[c] / windows - mean * mean));
  }
  return deviation;
}

class EveryCorpusImage : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryCorpusImage, AnalysesAndRenders) {
  const std::string method = GetParam();
  const auto fast = kFastParams.find(method);
  const ParamValues params = fast == kFastParams.end() ? ParamValues{} : fast->second;
  const std::vector<std::string> shared = test_support::gaussian_model_exemplars();
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(STOCHTEX_TEXTURE_DIR)) {
    if (entry.path().extension() != ".png") continue;
    const std::string name = entry.path().filename().string();
    const ImageF exemplar = read_image(entry.path());
    const Model model = std::find(shared.begin(), shared.end(), name) != shared.end()
                            ? test_support::default_model(method, name, exemplar)
                            : analyze(method, exemplar.view(), params, 0, name);
    const ColourStatistics target = colour_statistics(exemplar.view());
    const std::vector<double> window_deviation = window_mean_deviation(exemplar);
    for (const double scale : {1.0, 4.0}) {
      ImageF noise(64, 64, model.channels());
      render(model, Grid{{0.0, 0.0}, scale, 64, 64}, 1, noise.view());
      for (const float value : noise.pixels()) ASSERT_TRUE(std::isfinite(value)) << name;
      const ColourStatistics stats = colour_statistics(noise.view());
      // The mean of a 64 x 64 render strays like the means of the exemplar's own 64 x 64 windows
      // (a tiling render at scale 1 may sit inside one patch); 4 of their deviations, plus 1/100
      // for exemplars with almost no low frequencies, catch a wrong normalisation or look-up.
      for (std::size_t c = 0; c < stats.mean.size(); ++c)
        EXPECT_NEAR(stats.mean[c], target.mean[c], 4.0 * window_deviation[c] + 0.01)
            << method << " " << name << " scale " << scale << " channel " << c;
    }
    ++count;
  }
  EXPECT_EQ(count, 17);  // the shipped exemplars, data/exemplars/ATTRIBUTION.md
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryCorpusImage,
                         ::testing::ValuesIn(test_support::method_names()),
                         [](const auto& test) { return test.param; });

}  // namespace
}  // namespace stochtex::corpus_test
