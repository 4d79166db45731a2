#include "number_pair.hpp"

#include <cmath>
#include <exception>
#include <regex>

namespace stochtex::cli {

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

}  // namespace stochtex::cli
