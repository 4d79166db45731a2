// The `stochtex` command (docs/design.md §6): the subcommands (commands.hpp, one file
// each), parsed, run, and their failures mapped to exit codes and one-sentence messages on
// stderr; --json output is one document on stdout.

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <new>
#include <stdexcept>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "progress.hpp"
#include "stochtex/error.hpp"

namespace {

using namespace stochtex;

int run(int argc, char** argv) {
  remove_temporaries_on_signals();  // an interrupted write leaves no temporary (§6)
  CLI::App app{"stochtex: infinite, seedable, filterable textures from a small exemplar photo"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stochtex 0.1.0");
  bool progress_lines = false;
  app.add_flag("--progress", progress_lines,
               "show progress as a line every 2 seconds also when stderr is not a terminal (a "
               "log, CI); on a terminal a bar is always shown");
  // --progress may follow the subcommand, as users type it.
  app.fallthrough();
  const std::vector<cli::Command> commands{
      cli::add_analyze_command(app),       cli::add_mix_command(app),
      cli::add_render_command(app),        cli::add_render_mesh_command(app),
      cli::add_synth_command(app),         cli::add_gaussian_command(app),
      cli::add_compare_command(app),       cli::add_info_command(app),
      cli::add_export_shader_command(app), cli::add_edit_command(app),
      cli::add_report_command(app),        cli::add_methods_command(app),
      cli::add_languages_command(app),     cli::add_export_web_command(app),
      cli::add_studio_command(app)};

  // CLI11's own usage errors follow the one-sentence rule too.
  app.failure_message([](const CLI::App*, const CLI::Error& error) {
    return fmt::format("stochtex: error: {}; see --help\n", error.what());
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : cli::kExitUsage;
  }

  cli::set_progress_lines(progress_lines);
  try {
    for (const cli::Command& command : commands)
      if (*command.subcommand) {
        cli::check_no_empty_values(*command.subcommand);
        if (command.protects_inputs) protect_inputs();
        return command.run();
      }
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return cli::kExitUsage;
  } catch (const Error& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return cli::kExitRuntime;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "stochtex: error: out of memory; use a smaller --size or exemplar\n");
    return cli::kExitRuntime;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return cli::kExitRuntime;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return run(argc, argv);
}
