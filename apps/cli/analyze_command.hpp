#pragma once
// The options and work of `stochtex analyze`, which `stochtex synth` shares.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "io/exemplar_region.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

struct AnalyzeOptions {
  std::string input;
  std::string target;
  std::vector<std::string> maps;  // a material: --map NAME[:KIND]=FILE, in channel order
  std::string normal_y = "up";
  bool synthesise_normals = false;
  std::string method;
  std::vector<std::string> params;
  std::uint32_t seed = 0;
  std::string colour_space = "auto";
  std::string crop;          // --crop WIDTHxHEIGHT+X+Y, empty for the whole image
  double scale_input = 0.0;  // --scale-input; 0: the method's default (io/exemplar_region.hpp)
};

// INPUT, --target, --map, --normal-y, --synthesise-normals, --method, -p, --analysis-seed,
// --colour-space, --crop and --scale-input.
void add_analyze_options(CLI::App* command, AnalyzeOptions& options);

// The model of the options' exemplar or target. The method and parameters are checked before
// anything is read, so usage errors come first. With --colour-space auto, `notes` gets what each
// file said its colour is (ReadExemplar::note), for the caller to print once it succeeds.
Model run_analyze(const AnalyzeOptions& options, std::vector<std::string>* notes = nullptr);

// --scale-input's check: a factor in (0, 1].
CLI::Validator scale_input_validator();

// The exemplar `path` in `space` (auto where none), cropped and scaled to the region `method`
// analyses (`region`'s crop and factor, or the method's analysis side by default); an image or
// region the method cannot analyse within the memory budget is refused before decoding.
// `scale_note` gets the sentence that says a scale the user did not ask for (empty otherwise),
// for the caller to print before the analysis' wait.
ReadExemplar read_exemplar_region(const std::string& path, std::optional<ColourSpace> space,
                                  const std::string& method, const ExemplarRegion& region,
                                  std::string& scale_note);

}  // namespace stochtex::cli
