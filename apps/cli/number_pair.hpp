#pragma once
// "X,Y" command-line values (--origin, --translate): two finite decimal numbers.

#include <optional>
#include <string>

#include "stochtex/model.hpp"

namespace stochtex::cli {

// The pair, or nothing when `text` is not two finite numbers separated by a comma (spaces
// allowed around them).
std::optional<Vec2d> parse_number_pair(const std::string& text);

}  // namespace stochtex::cli
