// The method registry and its described parameters: the typed records, parsing by name and by
// number, and the docs' parameter tables against the records.

#include "methods/gabor/params.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "methods/lrp/params.hpp"
#include "methods/texton/params.hpp"
#include "methods/texton_mix/params.hpp"
#include "methods/tiling/params.hpp"
#include "registry.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::params_test {
namespace {

TEST(Registry, ListsTextonWithDescribedParameters) {
  const MethodInfo& info = method_info("texton");
  EXPECT_EQ(info.name, "texton");
  for (const auto& param : info.params) {
    EXPECT_FALSE(param.help.empty()) << param.name;
    // A default of 0 is the analysis' choice where the field takes it (support).
    if (!(param.zero_chooses && param.default_value == 0.0)) {
      EXPECT_GE(param.default_value, param.min_value) << param.name;
    }
    EXPECT_LE(param.default_value, param.max_value) << param.name;
  }
  const ParamValues defaults = resolve_params("texton", ParamValues{});
  EXPECT_EQ(defaults.at("support"), 0);  // chosen from the exemplar: texton::texton_support
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

TEST(Registry, ChannelsBeyondAMethodsLimitAreRefusedByName) {
  for (const auto& method : methods()) {
    EXPECT_GE(method.max_channels, kMaxImageChannels) << method.name;
    EXPECT_LE(method.max_channels, kMaxChannels) << method.name;
    ImageF too_many(16, 16, method.max_channels + 1, 0.25f);
    too_many.at(1, 2, 0) = 0.5f;
    try {
      analyze(method.name, too_many.view(), {}, 0, "material");
      ADD_FAILURE() << method.name << " took " << too_many.channels() << " channels";
    } catch (const Error& error) {
      const std::string what = error.what();
      EXPECT_EQ(error.code(), ErrorCode::invalid_input);
      EXPECT_NE(what.find("method " + std::string(method.name) + " analyses 1 to " +
                          std::to_string(method.max_channels) + " channels"),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("'material' has " + std::to_string(too_many.channels())),
                std::string::npos)
          << what;
    }
  }
}

using Text = std::map<std::string, std::string, std::less<>>;

// The one-sentence message of a rejected parameter, or "" when it was accepted.
std::string refusal(std::string_view method, const Text& given) {
  try {
    resolve_params(method, given);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// The rows' optional capabilities (methods/capabilities.hpp), which the front ends drive by them.
TEST(Registry, CapabilitiesAreFoundThroughTheRows) {
  EXPECT_NE(target_capability("lrp"), nullptr);
  EXPECT_EQ(target_capability("texton"), nullptr);
  EXPECT_THROW(target_capability("nosuch"), std::invalid_argument);
  EXPECT_NE(edit_capability("gabor"), nullptr);
  EXPECT_EQ(edit_capability("tiling"), nullptr);
  EXPECT_EQ(edit_capability("texton_mix"), nullptr);  // a model's method without a row
  EXPECT_EQ(methods_with(CapabilityKind::target), "lrp");
  EXPECT_EQ(methods_with(CapabilityKind::edit), "gabor");
  EXPECT_GT(analysis_cost("gabor"), analysis_cost("tiling"));
  const auto listed = nlohmann::json::parse(methods_json());
  for (const auto& method : listed) {
    const std::string name = method["name"];
    EXPECT_EQ(method.contains("target"), target_capability(name) != nullptr) << name;
    EXPECT_EQ(method.contains("edit"), edit_capability(name) != nullptr) << name;
  }
}

// The studio's editor builds its sliders from the fields' records: each slider's range holds the
// field's default (its position: the default, or its log2 for a factor moved in octaves).
TEST(Registry, EditSlidersStartAtTheFieldsDefaults) {
  for (const auto& method : nlohmann::json::parse(methods_json())) {
    if (!method.contains("edit")) continue;
    for (const auto& field : method["edit"]["fields"]) {
      const auto& slider = field.at("slider");
      const double step = slider.at("step");
      const double low = slider.at("min");
      const double high = slider.at("max");
      const double value = field.at("default");
      const double start = slider.at("octaves").get<bool>() ? std::log2(value) : value;
      EXPECT_GT(step, 0.0) << field;
      EXPECT_LE(low, start) << field;
      EXPECT_GE(high, start) << field;
      EXPECT_LT(low, high) << field;
    }
  }
}

// An edit sent as JSON is read against the capability's fields: known keys, numbers, pairs.
TEST(Registry, EditJsonFollowsTheFieldRecords) {
  const EditCapability& edit = *edit_capability("gabor");
  const EditValues values = edit_values_from_json(
      edit, nlohmann::ordered_json::parse(R"({"group": "periodic", "rotate": 30,
                                              "translate": [0.1, -0.2]})"));
  EXPECT_EQ(values.group, "periodic");
  EXPECT_EQ(values.numbers.at("rotate"), std::vector<double>{30.0});
  EXPECT_EQ(values.numbers.at("translate"), (std::vector<double>{0.1, -0.2}));
  EXPECT_FALSE(values.numbers.contains("scale"));  // not given: the default
  EXPECT_EQ(edit_values_from_json(edit, nlohmann::ordered_json::object()).group, "all");
  for (const char* bad : {R"({"spin": 1})", R"({"rotate": "10"})", R"({"translate": 0.1})",
                          R"({"translate": [0.1]})", R"({"group": 3})", "[1, 2]"}) {
    EXPECT_THROW(edit_values_from_json(edit, nlohmann::ordered_json::parse(bad)),
                 std::invalid_argument)
        << bad;
  }
}

TEST(Params, EnumerationsAndSwitchesTakeNames) {
  const ParamValues tiling = resolve_params(
      "tiling", Text{{"transport", "pca"}, {"blend", "linear"}, {"stationarity", "on"}});
  EXPECT_EQ(tiling.at("transport"), 1);
  EXPECT_EQ(tiling.at("blend"), 2);
  EXPECT_EQ(tiling.at("stationarity"), 1);
  EXPECT_EQ(resolve_params("tiling", Text{{"blend", "variance"}}).at("blend"), 1);
  EXPECT_EQ(resolve_params("gabor", Text{{"colour_space", "rgb"}}).at("colour_space"), 2);
  EXPECT_EQ(resolve_params("texton", Text{{"order", "cubic"}}).at("order"), 3);
  const ParamValues lrp =
      resolve_params("lrp", Text{{"envelope", "off"}, {"amplitudes", "off"}, {"placement", "off"}});
  EXPECT_EQ(lrp.at("envelope"), 0);
  EXPECT_EQ(lrp.at("amplitudes"), 0);
  EXPECT_EQ(lrp.at("placement"), 0);
}

TEST(Params, NumbersStayAccepted) {
  EXPECT_EQ(resolve_params("tiling", Text{{"blend", "2"}, {"transport", "1"}}).at("blend"), 2);
  EXPECT_EQ(resolve_params("gabor", Text{{"colour_space", "1"}}).at("colour_space"), 1);
  EXPECT_EQ(resolve_params("lrp", Text{{"envelope", "0"}}).at("envelope"), 0);
  EXPECT_EQ(resolve_params("texton", Text{{"order", "5"}}).at("order"), 5);
  EXPECT_EQ(resolve_params("tiling", ParamValues{{"stationarity", 1}}).at("stationarity"), 1);
}

TEST(Params, BadChoicesAreRefusedWithTheNames) {
  EXPECT_EQ(refusal("tiling", Text{{"blend", "foo"}}),
            "parameter blend of method tiling must be one of histogram, variance, linear (or 0, 1, "
            "2), not 'foo'");
  EXPECT_EQ(refusal("tiling", Text{{"blend", "3"}}),
            "parameter blend of method tiling must be one of histogram, variance, linear (or 0, 1, "
            "2), not 3");
  EXPECT_EQ(refusal("lrp", Text{{"envelope", "yes"}}),
            "parameter envelope of method lrp must be one of off, on (or 0, 1), not 'yes'");
  EXPECT_EQ(refusal("texton", Text{{"order", "2"}}),
            "parameter order of method texton must be one of nearest, bilinear, cubic, quintic "
            "(or 0, 1, 3, 5), not 2");
  // Names are case-sensitive and belong to their own parameter only.
  EXPECT_NE(refusal("gabor", Text{{"colour_space", "RGB"}}), "");
  EXPECT_NE(refusal("tiling", Text{{"transport", "variance"}}), "");
  EXPECT_EQ(refusal("texton", Text{{"mni", "on"}}),
            "parameter mni of method texton must be a number, not 'on'");
  EXPECT_NE(refusal("tiling", Text{{"blend", "nan"}}), "");
}

TEST(Params, ValuesAreWrittenByName) {
  EXPECT_EQ(format_param("tiling", "blend", 1), "variance");
  EXPECT_EQ(format_param("lrp", "placement", 1), "on");
  EXPECT_EQ(format_param("texton", "mni", 12.5), "12.5");
  EXPECT_EQ(format_param("gabor", "kappa", 1.0 / 256.0), "0.00390625");
  const std::string text = methods_text();
  EXPECT_NE(text.find("-p blend=histogram "), std::string::npos);
  EXPECT_NE(text.find("-p colour_space=pca "), std::string::npos);
  EXPECT_NE(text.find("-p mni=30 "), std::string::npos);
  const auto json = nlohmann::json::parse(methods_json());
  for (const auto& method : json)
    for (const auto& param : method["params"])
      if (param["name"] == "blend") {
        EXPECT_EQ(param["allowed"], nlohmann::json::array({0, 1, 2}));
        EXPECT_EQ(param["choices"][2], nlohmann::json({{"name", "linear"}, {"value", 2}}));
      }
}

// Whether `text` holds `word` between non-letters.
bool has_word(std::string_view text, std::string_view word) {
  const auto letter = [&](std::size_t i) {
    return i < text.size() && std::isalpha(static_cast<unsigned char>(text[i])) != 0;
  };
  for (auto at = text.find(word); at != std::string_view::npos; at = text.find(word, at + 1))
    if ((at == 0 || !letter(at - 1)) && !letter(at + word.size())) return true;
  return false;
}

TEST(Params, EveryChoiceIsNamedInItsHelp) {
  for (const auto& method : methods())
    for (const auto& param : method.params)
      for (const auto& choice : param.choices)
        EXPECT_TRUE(has_word(param.help, choice.name))
            << method.name << " " << param.name << " " << choice.name;
}

// A record's struct and the numbers of the model file convert both ways without loss: the
// defaults are those resolve_params fills in, and a struct of other values comes back equal.
template <class P, std::size_t N>
void expect_round_trip(std::string_view method, const std::array<ParamField<P>, N>& fields,
                       const P& changed) {
  EXPECT_EQ(param_values(fields, P{}), resolve_params(method, ParamValues{}));
  const ParamValues values = param_values(fields, changed);
  EXPECT_EQ(resolve_params(method, values), values);
  EXPECT_EQ(params_from_values(fields, values), changed);
  EXPECT_FALSE(changed == P{});
  EXPECT_EQ(params_from_values(fields, ParamValues{}), P{});
}

TEST(Params, TypedRecordsRoundTripThroughValues) {
  expect_round_trip("texton", texton::kFields, texton::Params{64, 3, 10, 12.5});
  expect_round_trip("tiling", tiling::kFields,
                    tiling::Params{0.75, tiling::Transport::per_channel, 8, 16, 256,
                                   tiling::Blend::linear, true, tiling::MakeTileable::on});
  expect_round_trip("lrp", lrp::kFields,
                    lrp::Params{20, 2, false, false, false, 3, 12, 0.3, 4.5, false});
  expect_round_trip("gabor", gabor::kFields,
                    gabor::Params{1.0 / 64.0, 256, gabor::ColourSpace::rgb, 50, 0.5, 2, false});
  expect_round_trip("texton_mix", texton_mix::kFields,
                    texton_mix::Params{{64, 3, 10, 12.5}, 9, -5, 300, 0.5, -2, 4});
}

// The rows of the first table headed "| name | default | range | meaning |" of a docs page.
std::vector<std::vector<std::string>> parameter_table(const std::string& path) {
  std::ifstream file(path);
  EXPECT_TRUE(file) << path;
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line) && line != "| name | default | range | meaning |") {
  }
  std::getline(file, line);  // the |---| separator
  while (std::getline(file, line) && line.starts_with("|")) {
    std::vector<std::string> cells;
    std::size_t start = 1;
    for (std::size_t bar = line.find('|', start); bar != std::string::npos && cells.size() < 3;
         start = bar + 1, bar = line.find('|', start)) {
      std::string cell = line.substr(start, bar - start);
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      cells.push_back(cell);
    }
    rows.push_back(cells);
  }
  return rows;
}

TEST(Params, DocsTablesFollowTheRecords) {
  // The methods analysed from one exemplar, and texton_mix (`stochtex mix`).
  std::vector<MethodInfo> records(methods().begin(), methods().end());
  records.push_back({"texton_mix", "", texton_mix::kParams});
  for (const auto& method : records) {
    const std::string page =
        std::string(STOCHTEX_SOURCE_DIR) + "/docs/methods/" + std::string(method.name) + ".md";
    const auto rows = parameter_table(page);
    ASSERT_EQ(rows.size(), method.params.size()) << page;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const ParamInfo& param = method.params[i];
      ASSERT_EQ(rows[i].size(), 3u) << page << " row " << i;
      const std::string_view name = rows[i][0];
      EXPECT_TRUE(name.starts_with('`') && name.ends_with('`')) << page << " " << name;
      EXPECT_EQ(name.substr(1, name.size() - 2), param.name) << page;
      EXPECT_EQ(rows[i][1], format_param(method.name, param.name, param.default_value))
          << page << " " << param.name;
      if (param.choices.empty()) continue;
      std::string names;
      for (const auto& choice : param.choices)
        names += (names.empty() ? "" : ", ") + std::string(choice.name);
      EXPECT_EQ(rows[i][2], names) << page << " " << param.name;
    }
  }
}

}  // namespace
}  // namespace stochtex::params_test
