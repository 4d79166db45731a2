#pragma once
// Values given on the command line, parsed in one place: WIDTHxHEIGHT sizes (render, synth,
// gaussian, report), X,Y pairs (--origin, --translate) and exemplar files. Each command words its
// own error sentence around them; the ones here throw std::invalid_argument (a usage error) or,
// for files, stochtex::Error.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

struct Size {
  int width = 0;
  int height = 0;
};

// WIDTHxHEIGHT with 1 to 7 digits per side, or nothing.
std::optional<Size> parse_size(const std::string& text);

// An image held in memory (render, synth, gaussian, render-mesh) has each side at most 32768 and
// at most 64 Mpixel (an 8192 x 8192 image, 1 GiB of RGBA floats), so that larger requests are
// refused up front rather than attempted as multi-gigabyte allocations. A render streamed to a
// tiled OpenEXR file has sides up to kMaxStreamedSide and any number of pixels.
inline constexpr int kMaxInMemorySide = 32768;
inline constexpr std::int64_t kMaxInMemoryPixels = std::int64_t{1} << 26;
inline constexpr int kMaxStreamedSide = 1 << 20;
bool fits_in_memory(std::int64_t width, std::int64_t height);

// The --size of an image held in memory.
Size output_size(const std::string& text);

// The --size of render and synth: each side 1 to kMaxStreamedSide; the output format's limits
// are checked with its region.
Size render_size(const std::string& text);

// The --region X,Y,WIDTH,HEIGHT of render and synth: pixels [X, X + WIDTH) x [Y, Y + HEIGHT) of
// the `frame` image, at least one pixel and inside it.
struct Region {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};
Region parse_region(const std::string& text, Size frame);

// The pair, or nothing when `text` is not two finite numbers separated by a comma (spaces
// allowed around them).
std::optional<Vec2d> parse_number_pair(const std::string& text);

// The -p key=value items of analyze and mix, as text values for resolve_params.
std::map<std::string, std::string, std::less<>> parse_params(const std::vector<std::string>& items);

// One --map NAME[:KIND]=FILE of analyze: a material map's name, its kind when given (colour,
// normal, height, scalar) and its file.
struct MapArgument {
  std::string name;
  std::optional<MapKind> kind;
  std::string file;
};
MapArgument parse_map_argument(const std::string& text);

// The image at `path`, checked to be usable as an exemplar.
ImageF load_exemplar(const std::string& path);

}  // namespace stochtex::cli
