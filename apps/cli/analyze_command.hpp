#pragma once
// The options and work of `stochtex analyze`, which `stochtex synth` shares.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

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

}  // namespace stochtex::cli
