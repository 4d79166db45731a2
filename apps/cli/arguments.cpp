#include "arguments.hpp"

#include <fmt/core.h>

#include <cmath>
#include <cstdint>
#include <exception>
#include <regex>
#include <stdexcept>

#include "io/image_io.hpp"

namespace stochtex::cli {

std::optional<Size> parse_size(const std::string& text) {
  static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) return std::nullopt;
  return Size{std::stoi(match[1]), std::stoi(match[2])};
}

Size output_size(const std::string& text) {
  constexpr int kMaxSide = 32768;
  constexpr std::int64_t kMaxPixels = std::int64_t{1} << 26;
  const std::optional<Size> size = parse_size(text);
  if (!size)
    throw std::invalid_argument("--size must be WIDTHxHEIGHT, e.g. 512x512, not '" + text + "'");
  if (size->width < 1 || size->height < 1 || size->width > kMaxSide || size->height > kMaxSide ||
      static_cast<std::int64_t>(size->width) * size->height > kMaxPixels)
    throw std::invalid_argument(
        fmt::format("--size {} is out of range: each side must be 1 to {} and the "
                    "image at most {} pixels",
                    text, kMaxSide, kMaxPixels));
  return *size;
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

ImageF load_exemplar(const std::string& path) {
  ImageF image = read_image(path);
  validate_exemplar(image.view(), path);
  return image;
}

}  // namespace stochtex::cli
