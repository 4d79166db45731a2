// `stochtex methods`: the methods and their parameters, as the registry describes them.

#include <fmt/core.h>

#include <memory>

#include "commands.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

Command add_methods_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* command = app.add_subcommand("methods", "list the methods and their parameters");
  command->add_flag("--json", *json, "print one JSON document");
  return {command, [json] {
            fmt::print("{}", *json ? methods_json() + "\n" : methods_text());
            return 0;
          }};
}

}  // namespace stochtex::cli
