#pragma once
// `stochtex edit`: group editing of a Gabor noise model (Gabor noise by example, section 8). The
// Gaussians of the model's spectrum are grouped automatically after the Wold decomposition
// (periodic peaks, strongly anisotropic lines, the stochastic rest); an edit rotates, scales and
// translates a group in frequency and changes its magnitude and bandwidth.

#include <CLI/CLI.hpp>
#include <string>

namespace stochtex::cli {

struct EditOptions {
  CLI::App* command = nullptr;  // the parsed subcommand: `*command` is true when it was given
  std::string model;
  std::string output;
  std::string group = "all";
  double rotate_degrees = 0.0;
  double scale = 1.0;
  std::string translate = "0,0";
  double magnitude = 1.0;
  double bandwidth = 1.0;
  bool list_groups = false;
  bool json = false;
};

// Adds the `edit` subcommand to `app`; parsing fills `options`, which must outlive `app`.
void add_edit_command(CLI::App& app, EditOptions& options);

// Runs it. Usage errors (bad values, a model of another method) throw std::invalid_argument;
// unreadable or invalid files throw stochtex::Error. The output is written atomically.
void run_edit_command(const EditOptions& options);

}  // namespace stochtex::cli
