// Issue 20, fidelity on the shipped photos: every method at its default parameters against the
// exemplar's Gaussian version (ADSN), on every `gaussian` and `stochastic` exemplar of
// data/exemplars/ATTRIBUTION.md. The measure is the one the issue states its aims in: the spectral
// error of `stochtex compare` (Welch spectra, docs/design.md §8) of a 1024² render divided by the
// error of compare's ADSN sample (seed 1, same size), averaged over the render seeds 1 and 2.
//
// The tolerance is measured here, per exemplar: the same ratio for ADSN samples of 8 other seeds
// spreads by sigma (the exemplar's own Welch estimate has 9 crops for a 256² exemplar, so an ideal
// Gaussian method's ratio strays from 1 by itself: 0.78 to 1.31 measured on wood and rock). The
// mean of two renders may exceed the aim by 2 sigma / sqrt(2). The colour covariance error, mean
// of the two renders, may exceed the ADSN samples' mean by 2 of their deviations / sqrt(2), plus
// 0.005 for exemplars whose ADSN covariance barely varies. Tiling's colour histogram error (sliced
// W2, mean of the two renders) must stay at most that of compare's ADSN sample.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "shared.hpp"
#include "spectral/adsn.hpp"
#include "statistics.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::fidelity_test {
namespace {

constexpr int kSide = 1024;
constexpr std::uint32_t kCompareSeed = 1;  // compare's ADSN sample
constexpr int kNoiseSeeds = 8;             // ADSN samples measuring the ratio's own spread

// The aims of issue 20 at the defaults: spectral error / ADSN's, and for the Gaussian-model
// methods the colour covariance at ADSN's level. Tiling copies the exemplar's own pixels: it has no
// spectral aim in the issue (1.5 holds it near the others) and must keep the colour histogram (its
// sliced W2 distance to the exemplar at most ADSN's) instead of a Gaussian covariance.
struct Aim {
  double spectral;
  bool gaussian_model;
};
const std::map<std::string, Aim, std::less<>> kAims = {{"texton", {1.2, true}},
                                                       {"lrp", {1.5, true}},
                                                       {"gabor", {1.25, true}},
                                                       {"tiling", {1.5, false}}};

// Where a method does not reach an aim: the measured level it must keep instead (0: the aim
// holds for that measure), and why. The method pages' "Fidelity on the shipped exemplars
// (issue 20)" sections give the measurements.
struct Shortfall {
  double spectral = 0.0;
  double covariance = 0.0;
  const char* why = "";
};
const std::map<std::pair<std::string, std::string>, Shortfall> kShortfalls = {
    {{"tiling", "wood_planks_256.png"},
     {2.8, 0.0,
      "measured 2.61 and 2.49 (averaged 2.55; 2.75 and 2.72 with the sliced transport, the "
      "default before issue 39; 2.62 and 3.31 before make_tileable): the exemplar "
      "is not tileable (the steps across its borders are 5.6 and 7.1 times the step between "
      "neighbouring pixels); made tileable, its renders lose the straight seams, but the smooth "
      "ramps that replace them and the planks' dark bands, longer than a tile, keep the excess "
      "power in the lowest Welch band (docs/methods/tiling.md)"}}};

struct Case {
  std::string method;
  std::string exemplar;  // file name in data/exemplars
};
void PrintTo(const Case& test, std::ostream* out) {
  *out << test.method << " on " << test.exemplar;
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const std::string& method : test_support::method_names())
    for (const std::string& exemplar : test_support::gaussian_model_exemplars())
      all.push_back({method, exemplar});
  return all;
}

// What the cases of one exemplar compare with, from ADSN samples alone: the spectral error of
// compare's sample, the spread of the ratio and of the covariance error over kNoiseSeeds other
// samples, and the sample's colour histogram error (sliced W2).
struct GaussianReference {
  double adsn_error = 0.0;
  test_support::Sample ratio_noise;
  test_support::Sample covariance_noise;
  double adsn_histogram = 0.0;
};

GaussianReference make_reference(const ImageF& exemplar) {
  const ImageF compared = adsn(exemplar.view(), kSide, kSide, kCompareSeed);
  const int crop = welch_crop_size(exemplar.view(), compared.view());
  const std::vector<double> target = welch_power_spectrum(exemplar.view(), crop);
  const ColourStatistics target_statistics = colour_statistics(exemplar.view());
  GaussianReference reference;
  reference.adsn_error = relative_l1_distance(welch_power_spectrum(compared.view(), crop), target);
  std::vector<double> noise_ratios;
  std::vector<double> noise_covariances;
  for (int k = 0; k < kNoiseSeeds; ++k) {
    const ImageF sample = adsn(exemplar.view(), kSide, kSide, 100u + static_cast<std::uint32_t>(k));
    noise_ratios.push_back(relative_l1_distance(welch_power_spectrum(sample.view(), crop), target) /
                           reference.adsn_error);
    noise_covariances.push_back(
        covariance_error(colour_statistics(sample.view()), target_statistics));
  }
  reference.ratio_noise = test_support::summarise(noise_ratios);
  reference.covariance_noise = test_support::summarise(noise_covariances);
  reference.adsn_histogram = sliced_wasserstein(compared.view(), exemplar.view());
  return reference;
}

std::filesystem::path reference_path(const std::filesystem::path& folder,
                                     const std::string& exemplar_name) {
  return folder / ("fidelity_reference_" + exemplar_name + ".json");
}
// JSON keeps a double exactly (nlohmann_json writes the shortest digits that read back the same).
nlohmann::json reference_json(const GaussianReference& r) {
  return {{"adsn_error", r.adsn_error},
          {"ratio_noise", {r.ratio_noise.mean, r.ratio_noise.deviation}},
          {"covariance_noise", {r.covariance_noise.mean, r.covariance_noise.deviation}},
          {"adsn_histogram", r.adsn_histogram}};
}
GaussianReference reference_from_json(const nlohmann::json& j) {
  return {
      j.at("adsn_error").get<double>(),
      {j.at("ratio_noise").at(0).get<double>(), j.at("ratio_noise").at(1).get<double>()},
      {j.at("covariance_noise").at(0).get<double>(), j.at("covariance_noise").at(1).get<double>()},
      j.at("adsn_histogram").get<double>()};
}

// The shared fixture's reference of `exemplar_name` when CTest made it, else made here.
GaussianReference gaussian_reference(const std::string& exemplar_name, const ImageF& exemplar) {
  if (const auto folder = test_support::shared_folder()) {
    std::ifstream file(reference_path(*folder, exemplar_name));
    if (file) return reference_from_json(nlohmann::json::parse(file));
  }
  return make_reference(exemplar);
}

// The fixture (FIXTURES_SETUP under CTest): each exemplar's reference, made once for the cases of
// every method.
class SharedFidelityReference : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedFidelityReference, Make) {
  const auto folder = test_support::shared_folder();
  if (!folder) GTEST_SKIP() << "STOCHTEX_TEST_CACHE is not set: the cases make their own";
  const std::string& name = GetParam();
  const ImageF exemplar = read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/" + name);
  std::filesystem::create_directories(*folder);
  write_file_atomically(reference_path(*folder, name),
                        reference_json(make_reference(exemplar)).dump());
}

INSTANTIATE_TEST_SUITE_P(Shared, SharedFidelityReference,
                         ::testing::ValuesIn(test_support::gaussian_model_exemplars()),
                         [](const auto& test_case) {
                           return test_support::test_name(test_case.param);
                         });

class Fidelity : public ::testing::TestWithParam<Case> {};

TEST_P(Fidelity, SpectrumAndCovarianceAtTheGaussianLevel) {
  const Case& test = GetParam();
  const auto found_aim = kAims.find(test.method);
  ASSERT_NE(found_aim, kAims.end()) << test.method << " has no aim: add its aim to kAims";
  const Aim& aim = found_aim->second;
  const ImageF exemplar = read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/" + test.exemplar);
  const int crop = welch_crop_size(exemplar.view(), exemplar.view());
  const std::vector<double> target = welch_power_spectrum(exemplar.view(), crop);
  const ColourStatistics target_statistics = colour_statistics(exemplar.view());
  const GaussianReference reference = gaussian_reference(test.exemplar, exemplar);
  const double adsn_error = reference.adsn_error;
  const test_support::Sample& ratio_noise = reference.ratio_noise;
  const test_support::Sample& covariance_noise = reference.covariance_noise;

  const Model model = test_support::default_model(test.method, test.exemplar, exemplar);
  std::vector<double> ratios;
  std::vector<double> covariances;
  std::vector<double> histograms;  // sliced W2 to the exemplar, for tiling
  std::vector<double> mean_spectrum(target.size(), 0.0);
  for (const std::uint32_t seed : {1u, 2u}) {
    ImageF render_image(kSide, kSide, model.channels());
    render(model, Grid{{0.0, 0.0}, 1.0, kSide, kSide}, seed, render_image.view());
    const std::vector<double> spectrum = welch_power_spectrum(render_image.view(), crop);
    for (std::size_t i = 0; i < spectrum.size(); ++i) mean_spectrum[i] += 0.5 * spectrum[i];
    ratios.push_back(relative_l1_distance(spectrum, target) / adsn_error);
    covariances.push_back(
        covariance_error(colour_statistics(render_image.view()), target_statistics));
    if (!aim.gaussian_model)
      histograms.push_back(sliced_wasserstein(render_image.view(), exemplar.view()));
  }
  const double ratio = 0.5 * (ratios[0] + ratios[1]);
  const double covariance = 0.5 * (covariances[0] + covariances[1]);

  const auto found = kShortfalls.find({test.method, test.exemplar});
  const Shortfall shortfall = found == kShortfalls.end() ? Shortfall{} : found->second;
  const double ratio_level = shortfall.spectral > 0.0 ? shortfall.spectral : aim.spectral;
  const double ratio_bound = ratio_level + 2.0 * ratio_noise.deviation / std::sqrt(2.0);
  const double covariance_bound =
      shortfall.covariance > 0.0
          ? shortfall.covariance
          : covariance_noise.mean + 2.0 * covariance_noise.deviation / std::sqrt(2.0) + 0.005;
  // One line per case for scripts/fidelity.sh, which writes docs/fidelity.md from them.
  nlohmann::ordered_json line{
      {"method", test.method},
      {"exemplar", test.exemplar},
      {"ratios", ratios},
      {"averaged_ratio", relative_l1_distance(mean_spectrum, target) / adsn_error},
      {"aim", aim.spectral},
      {"ratio_bound", ratio_bound},
      {"adsn_ratio_mean", ratio_noise.mean},
      {"adsn_ratio_deviation", ratio_noise.deviation},
      {"covariances", covariances},
      {"adsn_covariance_mean", covariance_noise.mean},
      {"adsn_covariance_deviation", covariance_noise.deviation},
      {"shortfall", shortfall.why}};
  EXPECT_LE(ratio, ratio_bound) << test.method << " on " << test.exemplar;
  if (aim.gaussian_model) {
    line["covariance_bound"] = covariance_bound;
    EXPECT_LE(covariance, covariance_bound) << test.method << " on " << test.exemplar;
  } else {
    const double histogram = 0.5 * (histograms[0] + histograms[1]);
    line["histograms"] = histograms;
    line["adsn_histogram"] = reference.adsn_histogram;
    EXPECT_LE(histogram, reference.adsn_histogram) << test.method << " on " << test.exemplar;
  }
  std::printf("fidelity %s\n", line.dump().c_str());
}

INSTANTIATE_TEST_SUITE_P(Shipped, Fidelity, ::testing::ValuesIn(cases()),
                         [](const auto& test_case) {
                           return test_support::test_name(test_case.param.method + "_" +
                                                          test_case.param.exemplar);
                         });

}  // namespace
}  // namespace stochtex::fidelity_test
