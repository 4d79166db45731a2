#pragma once
// The subcommands of `stochtex` (docs/design.md §6), one source file each. Each add_*
// function adds its subcommand and options to the app and returns it with its handler, which
// main.cpp runs when that subcommand was given. Exit codes: 0 ok, 1 runtime failure (bad file,
// numerical failure), 2 usage error. A handler returns 0 or 1 and throws std::invalid_argument
// for usage errors (checked before any long work) and other exceptions for runtime failures.

#include <CLI/CLI.hpp>
#include <functional>

namespace stochtex::cli {

inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

struct Command {
  CLI::App* subcommand = nullptr;  // `*subcommand` is true when it was given
  std::function<int()> run;        // owns the options the parse fills
  // No output of the command may replace a file it read (core/input_file.hpp protect_inputs):
  // true for every command but the studio, a server that rewrites the files of its store.
  bool protects_inputs = true;
};

Command add_analyze_command(CLI::App& app);
Command add_render_command(CLI::App& app);
Command add_render_mesh_command(CLI::App& app);
Command add_synth_command(CLI::App& app);
Command add_gaussian_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_mix_command(CLI::App& app);
Command add_export_shader_command(CLI::App& app);
Command add_export_web_command(CLI::App& app);
Command add_edit_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_methods_command(CLI::App& app);
Command add_languages_command(CLI::App& app);
Command add_studio_command(CLI::App& app);

}  // namespace stochtex::cli
