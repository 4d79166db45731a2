#pragma once
// The options and work of `stochtex render`, which `stochtex synth` shares.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>

#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

struct RenderSettings {
  std::string size = "512x512";
  std::string origin = "0,0";
  double scale = 1.0;
  std::uint32_t seed = 0;
  int threads = 0;
  int supersample = 1;
  int tile = 64;
  bool no_filter = false;
  int bit_depth = 8;
  std::string backend = "cpu";
  std::string gl_filter = "exact";
  std::string region;  // X,Y,WIDTH,HEIGHT; empty: the whole --size image
  bool tiled = false;
  bool mipmap = false;
  bool half = false;
  std::string cpu_target = "best";  // a CpuTarget's name, or best
  bool periodic = false;
};

// -o (an image), --size (required), --origin, --scale, --seed, --region, the tiled OpenEXR options
// and the render options.
void add_render_options(CLI::App* command, RenderSettings& settings, std::string& output);

// Renders the model that `make_model` returns to `output` as the settings say, on their backend,
// printing a progress bar and the files written: renderer::render_to_file, which checks the
// request and the output (which may not be the `input` file) before it calls `make_model`, so
// that usage errors come first.
void render_to_file(const std::function<Model()>& make_model, const RenderSettings& settings,
                    const std::string& output, const std::string& input);

}  // namespace stochtex::cli
