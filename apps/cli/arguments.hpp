#pragma once
// Values given on the command line, parsed in one place: WIDTHxHEIGHT sizes (render, synth,
// gaussian, report), X,Y pairs (--origin, --translate) and exemplar files. Each command words its
// own error sentence around them; the ones here throw std::invalid_argument (a usage error) or,
// for files, stochtex::Error.

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

// WIDTHxHEIGHT with 1 to 6 digits per side, or nothing.
std::optional<Size> parse_size(const std::string& text);

// The --size of an output image (render, synth, gaussian): each side 1 to 32768 and at most
// 64 Mpixel (an 8192 x 8192 image, 1 GiB of RGBA floats), so that larger renders are refused up
// front rather than attempted as multi-gigabyte allocations.
Size output_size(const std::string& text);

// The pair, or nothing when `text` is not two finite numbers separated by a comma (spaces
// allowed around them).
std::optional<Vec2d> parse_number_pair(const std::string& text);

// The -p key=value items of analyze and mix, as text values for resolve_params.
std::map<std::string, std::string, std::less<>> parse_params(const std::vector<std::string>& items);

// The image at `path`, checked to be usable as an exemplar.
ImageF load_exemplar(const std::string& path);

}  // namespace stochtex::cli
