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
};

// -o (an image), --size (required), --origin, --scale, --seed, --region, the tiled OpenEXR options
// and the render options.
void add_render_options(CLI::App* command, RenderSettings& settings, std::string& output);

// Checks --size, --region, --origin, the output path (which may not be the `input` file) and, for a
// tiled OpenEXR output, the free disk space, then renders the model that `make_model` returns
// (called after those checks, so that usage errors come first) with the settings' backend and
// writes the image to `output`: in memory, or strip by strip into a tiled OpenEXR file for .exr
// output beyond the in-memory limit or with --tiled, --mipmap or --half. An output format that
// cannot hold the model's channels is refused before the render.
void render_to_file(const std::function<Model()>& make_model, const RenderSettings& settings,
                    const std::string& output, const std::string& input);

}  // namespace stochtex::cli
