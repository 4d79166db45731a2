// `stochtex analyze INPUT -m METHOD -o MODEL.stx`: exemplar (or, for lrp, a target spectrum) ->
// model file.

#include "analyze_command.hpp"

#include <fmt/core.h>

#include <map>
#include <memory>
#include <stdexcept>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/image_io.hpp"
#include "progress.hpp"
#include "target_option.hpp"

namespace stochtex::cli {
void add_analyze_options(CLI::App* command, AnalyzeOptions& options) {
  auto* input = command->add_option("INPUT", options.input, "exemplar image (PNG, EXR or PFM)");
  command->add_option("--target", options.target, std::string(kTargetHelp))->excludes(input);
  command->add_option("--method,-m", options.method, "texture method (see `stochtex methods`)")
      ->required();
  command->add_option("-p,--param", options.params,
                      "method parameter key=value (repeatable; listed below)");
  command->footer("\nmethods and parameters (-p name=default):\n" + methods_text());
  command
      ->add_option("--analysis-seed", options.seed, "seed of the analysis' random initialisation")
      ->capture_default_str();
}

Model run_analyze(const AnalyzeOptions& options) {
  const ParamValues params = resolve_params(options.method, parse_params(options.params));
  if (!options.target.empty())
    return target_model(options.target, options.method, params, options.seed);
  if (options.input.empty())
    throw std::invalid_argument("give an exemplar INPUT or, for lrp, a --target spectrum");
  const ImageF exemplar = load_exemplar(options.input);
  Progress progress("analyse");
  progress.message(fmt::format("analysing {} with {}...", options.input, options.method));
  return analyze(options.method, exemplar.view(), params, options.seed, options.input,
                 [&](double fraction) { progress(fraction); });
}

Command add_analyze_command(CLI::App& app) {
  struct Options {
    AnalyzeOptions analyze;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("analyze", "exemplar -> model file (.stx)");
  add_analyze_options(command, options->analyze);
  command->add_option("-o,--output", options->output, "model file to write (.stx)")->required();
  return {command, [options] {
            check_output_path(options->output, false, options->analyze.input);
            save_model(run_analyze(options->analyze), options->output);
            fmt::print(stderr, "wrote {}\n", options->output);
            return 0;
          }};
}

}  // namespace stochtex::cli
