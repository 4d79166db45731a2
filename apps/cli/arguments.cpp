#include "arguments.hpp"

#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <regex>
#include <stdexcept>
#include <utility>

#include "io/image_io.hpp"
#include "model/map_layout.hpp"

namespace stochtex::cli {

CLI::Validator finite_range(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !(value >= min && value <= max))
          return fmt::format("Value {} not in range [{} - {}]", text, min, max);
        return {};
      },
      fmt::format("FLOAT in [{} - {}]", min, max));
}

void check_no_empty_values(const CLI::App& command) {
  for (const CLI::Option* option : command.get_options()) {
    if (option->get_expected_min() == 0) continue;  // a flag
    for (const std::string& value : option->results())
      if (value.empty())
        throw std::invalid_argument(
            fmt::format("{} was given an empty value; give one or leave the option out",
                        option->get_name(false, true)));
  }
}

std::optional<Size> parse_size(const std::string& text) {
  static const std::regex pattern(R"((\d{1,7})x(\d{1,7}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) return std::nullopt;
  return Size{std::stoi(match[1]), std::stoi(match[2])};
}

Size size_option(const std::string& text) {
  const std::optional<Size> size = parse_size(text);
  if (!size)
    throw std::invalid_argument("--size must be WIDTHxHEIGHT, e.g. 512x512, not '" + text + "'");
  return *size;
}

Size output_size(const std::string& text) {
  const Size size = size_option(text);
  if (size.width < 1 || size.height < 1 || !renderer::fits_in_memory(size.width, size.height))
    throw std::invalid_argument(
        fmt::format("--size {} is out of range: each side must be 1 to {} and the "
                    "image at most {} pixels",
                    text, renderer::kMaxInMemorySide, renderer::kMaxInMemoryPixels));
  return size;
}

renderer::PixelRegion parse_region(const std::string& text) {
  static const std::regex pattern(R"((\d{1,7}),(\d{1,7}),(\d{1,7}),(\d{1,7}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw std::invalid_argument(
        "--region must be X,Y,WIDTH,HEIGHT in pixels of the --size image, "
        "e.g. 0,0,256,256, not '" +
        text + "'");
  return {std::stoi(match[1]), std::stoi(match[2]), std::stoi(match[3]), std::stoi(match[4])};
}

std::optional<Vec2d> parse_number_pair(const std::string& text) {
  static const std::regex pattern(R"(\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) return std::nullopt;
  try {
    std::size_t used_x = 0;
    std::size_t used_y = 0;
    const Vec2d pair{std::stod(match[1], &used_x), std::stod(match[2], &used_y)};
    if (used_x == match[1].str().size() && used_y == match[2].str().size() &&
        std::isfinite(pair.x) && std::isfinite(pair.y))
      return pair;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::map<std::string, std::string, std::less<>> parse_params(
    const std::vector<std::string>& items) {
  std::map<std::string, std::string, std::less<>> params;
  for (const auto& item : items) {
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0)
      throw std::invalid_argument("-p expects key=value, e.g. -p mni=30, not '" + item + "'");
    params[item.substr(0, equals)] = item.substr(equals + 1);
  }
  return params;
}

MapArgument parse_map_argument(const std::string& text) {
  static const std::regex pattern(R"(([a-z0-9_]{1,32})(:([a-z]+))?(:([a-z]+))?=(.+))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw std::invalid_argument(
        "--map expects NAME=FILE, NAME:KIND=FILE or NAME:KIND:COLOUR_SPACE=FILE with a name of 1 "
        "to 32 of a-z, 0-9 and _, e.g. --map albedo=rock_albedo.png, not '" +
        text + "'");
  MapArgument map{match[1], std::nullopt, std::nullopt, match[6]};
  // Each qualifier is a kind or a colour space, whose names differ.
  for (const int group : {3, 5}) {
    if (!match[group].matched) continue;
    const std::string word = match[group].str();
    if (const auto kind = map_kind_from_name(word); kind && !map.kind) {
      map.kind = kind;
    } else if (const auto space = colour_space_from_name(word); space && !map.colour_space) {
      map.colour_space = space;
    } else {
      throw std::invalid_argument("--map " + text + ": '" + word +
                                  "' is not a kind (colour, normal, height, scalar) or a colour "
                                  "space (srgb, linear, data), or it repeats one");
    }
  }
  return map;
}

ImageF load_exemplar(const std::string& path,
                     std::function<void(int width, int height, int channels)> check_declared) {
  ImageReadLimits limits;
  limits.check_declared = std::move(check_declared);
  ImageF image = read_image(path, limits);
  validate_exemplar(image.view(), path);
  return image;
}

ReadExemplar read_exemplar(const std::string& path, std::optional<ColourSpace> space,
                           const ImageReadLimits& limits) {
  if (space) return {read_image(path, limits), *space, {}};
  ImageColour colour;
  ImageF image = read_image(path, limits, &colour);
  return {std::move(image), colour.space,
          fmt::format("{}: {} ({})", path, colour_space_name(colour.space), colour.origin)};
}

std::optional<ColourSpace> option_space(const std::string& text) {
  return text == "auto" ? std::nullopt : colour_space_from_name(text);
}

}  // namespace stochtex::cli
