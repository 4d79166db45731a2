// The method registry and its described parameters.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

TEST(Registry, ListsTextonWithDescribedParameters) {
  const MethodInfo& info = method_info("texton");
  EXPECT_EQ(info.name, "texton");
  for (const auto& param : info.params) {
    EXPECT_FALSE(param.help.empty()) << param.name;
    EXPECT_GE(param.default_value, param.min_value) << param.name;
    EXPECT_LE(param.default_value, param.max_value) << param.name;
  }
  const ParamValues defaults = resolve_params("texton", ParamValues{});
  EXPECT_EQ(defaults.at("support"), 128);
  EXPECT_EQ(defaults.at("order"), 1);
  EXPECT_EQ(defaults.at("iterations"), 50);
  EXPECT_EQ(defaults.at("mni"), 30);
}

TEST(Registry, RejectsBadNamesAndValues) {
  EXPECT_THROW(method_info("voronoi"), std::invalid_argument);
  EXPECT_THROW(resolve_params("texton", ParamValues{{"colour", 1}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("texton", ParamValues{{"mni", 0}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("texton", ParamValues{{"order", 2}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("texton", ParamValues{{"support", 16.5}}), std::invalid_argument);
  using Text = std::map<std::string, std::string, std::less<>>;
  EXPECT_THROW(resolve_params("texton", Text{{"mni", "thirty"}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("texton", Text{{"mni", "nan"}}), std::invalid_argument);
  EXPECT_EQ(resolve_params("texton", Text{{"mni", "12.5"}}).at("mni"), 12.5);
}

TEST(Registry, ExemplarValidationNamesTheProblem) {
  ImageF tiny(1, 1, 3, 0.5f);
  EXPECT_THROW(analyze("texton", tiny.view()), Error);
  ImageF constant(16, 16, 1, 0.25f);
  EXPECT_THROW(analyze("texton", constant.view()), Error);
  ImageF with_nan(16, 16, 1, 0.25f);
  with_nan.at(3, 4, 0) = std::nanf("");
  try {
    analyze("texton", with_nan.view(), {}, 0, "bad.pfm");
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).find("'bad.pfm'"), 0u);
  }
}

}  // namespace
}  // namespace stochtex
