#pragma once
// What several statistical tests share and is costly to make: each method's default model of the
// shipped photos (a gabor analysis of a 512² colour exemplar takes about a minute) and the
// fidelity test's Gaussian references. CTest makes each once, in the fixture tests of
// shared_test.cpp (FIXTURES_SETUP, tests/CMakeLists.txt), into the folder $STOCHTEX_TEST_CACHE,
// which only CTest sets; the tests load from it. Run by hand, without that variable, a test makes
// what it needs itself, so a stale folder can never be read.

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::test_support {

// The `gaussian` and `stochastic` exemplars of the corpus table (data/exemplars/ATTRIBUTION.md),
// in its order: the photos a Gaussian model is meant for.
inline std::vector<std::string> gaussian_model_exemplars() {
  std::ifstream table(std::string(STOCHTEX_TEXTURE_DIR) + "/ATTRIBUTION.md");
  const std::regex row(R"(^\| `([^`]+\.png)` \| [^|]+ \| (gaussian|stochastic) \|)");
  std::vector<std::string> names;
  std::smatch match;
  for (std::string line; std::getline(table, line);)
    if (std::regex_search(line, match, row)) names.push_back(match[1]);
  return names;
}

// The methods analysed from one exemplar, from the registry.
inline std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto& method : methods()) names.emplace_back(method.name);
  return names;
}

// `text` as a GoogleTest parameter name: every character but letters and digits made '_'.
inline std::string test_name(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

inline std::filesystem::path shared_model_path(const std::filesystem::path& folder,
                                               const std::string& method,
                                               const std::string& exemplar_name) {
  return folder / (method + "_" + exemplar_name + ".stx");
}

// The model `method` makes of the shipped exemplar `exemplar_name` (`exemplar`, read from it) at
// its default parameters and analysis seed 0: the shared fixture's file when there is one (every
// method on every gaussian_model_exemplars()), else analysed here. A model file holds the model
// exactly (the round-trip tests of each method), so both render the same bytes.
inline Model default_model(const std::string& method, const std::string& exemplar_name,
                           const ImageF& exemplar) {
  if (const auto folder = shared_folder()) {
    const std::filesystem::path path = shared_model_path(*folder, method, exemplar_name);
    if (std::filesystem::exists(path)) return load_model(path);
  }
  return analyze(method, exemplar.view(), {}, 0, exemplar_name);
}

}  // namespace stochtex::test_support
