// `stochtex methods`: the methods and their parameters, as the registry describes them.

#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "commands.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

nlohmann::ordered_json methods_json() {
  auto list = nlohmann::ordered_json::array();
  for (const auto& method : methods()) {
    auto params = nlohmann::ordered_json::array();
    for (const auto& p : method.params) {
      nlohmann::ordered_json param{{"name", p.name},       {"default", p.default_value},
                                   {"min", p.min_value},   {"max", p.max_value},
                                   {"integer", p.integer}, {"help", p.help}};
      if (!p.allowed.empty())
        param["allowed"] = std::vector<double>(p.allowed.begin(), p.allowed.end());
      params.push_back(param);
    }
    list.push_back({{"name", method.name}, {"summary", method.summary}, {"params", params}});
  }
  return list;
}

}  // namespace

Command add_methods_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* command = app.add_subcommand("methods", "list the methods and their parameters");
  command->add_flag("--json", *json, "print one JSON document");
  return {command, [json] {
            if (*json) {
              fmt::print("{}\n", methods_json().dump(2));
              return 0;
            }
            for (const auto& method : methods()) {
              fmt::print("{}: {}\n", method.name, method.summary);
              for (const auto& p : method.params)
                fmt::print("  -p {:<20} {}\n", fmt::format("{}={}", p.name, p.default_value),
                           p.help);
            }
            return 0;
          }};
}

}  // namespace stochtex::cli
