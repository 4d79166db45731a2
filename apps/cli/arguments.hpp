#pragma once
// Values given on the command line, parsed in one place: WIDTHxHEIGHT sizes (render, synth,
// gaussian, report), X,Y pairs (--origin, --translate) and exemplar files. Each command words its
// own error sentence around them; the ones here throw std::invalid_argument (a usage error) or,
// for files, stochtex::Error.

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/plan.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

struct Size {
  int width = 0;
  int height = 0;
};

// CLI::Range for a floating-point option that also refuses NaN, which CLI::Range lets through
// (every comparison with NaN is false).
CLI::Validator finite_range(double min, double max);

// Refuses an option given an empty value (`--seed ''`), which CLI11 would take as the default:
// one sentence naming the option. Checked for every option of the command that was run.
void check_no_empty_values(const CLI::App& command);

// WIDTHxHEIGHT with 1 to 7 digits per side, or nothing.
std::optional<Size> parse_size(const std::string& text);

// A --size, WIDTHxHEIGHT; its range is the command's to check. render and synth check it with the
// rest of their request (renderer::plan_render), where a streamed output allows larger sides.
Size size_option(const std::string& text);

// The --size of an image held in memory: each side 1 to renderer::kMaxInMemorySide and at most
// renderer::kMaxInMemoryPixels.
Size output_size(const std::string& text);

// The --region X,Y,WIDTH,HEIGHT of render and synth, in pixels of the --size image; whether it
// lies inside that image is checked with the rest of the request (renderer::plan_render).
renderer::PixelRegion parse_region(const std::string& text);

// The pair, or nothing when `text` is not two finite numbers separated by a comma (spaces
// allowed around them).
std::optional<Vec2d> parse_number_pair(const std::string& text);

// The -p key=value items of analyze and mix, as text values for resolve_params.
std::map<std::string, std::string, std::less<>> parse_params(const std::vector<std::string>& items);

// One --map NAME[:KIND][:COLOUR_SPACE]=FILE of analyze: a material map's name, its kind when
// given (colour, normal, height, scalar), its colour space when given (srgb, linear, data) and
// its file.
struct MapArgument {
  std::string name;
  std::optional<MapKind> kind;
  std::optional<ColourSpace> colour_space;
  std::string file;
};
MapArgument parse_map_argument(const std::string& text);

// The image at `path`, checked to be usable as an exemplar. `check_declared` (see
// ImageReadLimits) refuses, before the pixels are decoded, a size the command cannot afford.
ImageF load_exemplar(const std::string& path,
                     std::function<void(int width, int height, int channels)> check_declared = {});

// The image at `path` as `space` says its values are, or with none (--colour-space auto) as the
// file says (read_image's ImageColour), with that colour space and, for auto, the note a command
// prints once it succeeds: "x.png: srgb (no colour chunk: sRGB by default)".
struct ReadExemplar {
  ImageF image;
  ColourSpace space = ColourSpace::data;
  std::string note;
};
ReadExemplar read_exemplar(const std::string& path, std::optional<ColourSpace> space,
                           const ImageReadLimits& limits);

// --colour-space's value: none for auto, else its colour space.
std::optional<ColourSpace> option_space(const std::string& text);

}  // namespace stochtex::cli
