#include <array>
#include <utility>

#include "stochtex/colour.hpp"

namespace stochtex {
namespace {

constexpr std::array<std::pair<ColourSpace, std::string_view>, 3> kNames{{
    {ColourSpace::data, "data"},
    {ColourSpace::linear, "linear"},
    {ColourSpace::srgb, "srgb"},
}};

}  // namespace

std::string_view colour_space_name(ColourSpace space) {
  for (const auto& [value, name] : kNames)
    if (value == space) return name;
  return "data";
}

std::optional<ColourSpace> colour_space_from_name(std::string_view name) {
  for (const auto& [value, text] : kNames)
    if (text == name) return value;
  return std::nullopt;
}

}  // namespace stochtex
