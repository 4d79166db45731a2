// The shared fixture of the statistical tier (shared.hpp): every method's default model of every
// photo a Gaussian model is meant for, made once under CTest (FIXTURES_SETUP) for the fidelity,
// quality and surface tests that measure it.

#include "shared.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/image_io.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::shared_test {
namespace {

using ModelCase = std::pair<std::string, std::string>;  // method, exemplar file name

std::vector<ModelCase> model_cases() {
  std::vector<ModelCase> all;
  for (const std::string& method : test_support::method_names())
    for (const std::string& exemplar : test_support::gaussian_model_exemplars())
      all.emplace_back(method, exemplar);
  return all;
}

class SharedModel : public ::testing::TestWithParam<ModelCase> {};

TEST_P(SharedModel, Make) {
  const auto folder = test_support::shared_folder();
  if (!folder) GTEST_SKIP() << "STOCHTEX_TEST_CACHE is not set: the tests analyse their own";
  const auto& [method, name] = GetParam();
  const ImageF exemplar = read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/" + name);
  std::filesystem::create_directories(*folder);
  // save_model writes through a temporary and a rename: a reader never sees half a file.
  save_model(analyze(method, exemplar.view(), {}, 0, name),
             test_support::shared_model_path(*folder, method, name));
}

INSTANTIATE_TEST_SUITE_P(Shared, SharedModel, ::testing::ValuesIn(model_cases()),
                         [](const auto& test_case) {
                           return test_support::test_name(test_case.param.first + "_" +
                                                          test_case.param.second);
                         });

}  // namespace
}  // namespace stochtex::shared_test
