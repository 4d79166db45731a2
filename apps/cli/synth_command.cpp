// `stochtex synth INPUT -m METHOD -o IMAGE --size WxH`: analyze and render in one step, the model
// kept in memory.

#include <fmt/core.h>

#include <memory>
#include <string>
#include <vector>

#include "analyze_command.hpp"
#include "commands.hpp"
#include "render_command.hpp"

namespace stochtex::cli {

Command add_synth_command(CLI::App& app) {
  struct Options {
    AnalyzeOptions analyze;
    RenderSettings settings;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("synth", "analyze + render in one step");
  add_analyze_options(command, options->analyze);
  add_render_options(command, options->settings, options->output);
  return {command, [options] {
            // What analyze says once it succeeds (the exemplar's colour, whether it tiles),
            // said after the render's files, as analyze says it after the model's.
            std::vector<std::string> notes;
            render_to_file([&] { return run_analyze(options->analyze, &notes); }, options->settings,
                           options->output, options->analyze.input);
            for (const std::string& note : notes) fmt::print(stderr, "{}\n", note);
            return 0;
          }};
}

}  // namespace stochtex::cli
