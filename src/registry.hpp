#pragma once
// The registry's analysis of one exemplar into a model that also carries a material's maps
// (src/material.cpp); stochtex::analyze is this call without maps.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "methods/capabilities.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {

// Refuses, before any work, an analysis by `method` of a width x height exemplar of `channels`
// channels: more channels than the method analyses, or beyond the memory budget.
void check_analysis_request(std::string_view method, int width, int height, int channels,
                            const std::string& source_name);

// The model of an exemplar of one image in `colour_space`, or of a material's maps (each map's
// MapInfo::colour_space; `colour_space` is not used).
Model analyze_exemplar(std::string_view method, ImageView<const float> exemplar,
                       const ParamValues& params, std::uint32_t seed,
                       const std::string& source_name, const std::function<void(double)>& progress,
                       std::vector<MapInfo> maps, ColourSpace colour_space = ColourSpace::data);

// The optional capabilities of a method's row (methods/capabilities.hpp), nullptr where it has
// none; the front ends drive a method's extra features through these, never through its name.
// (target_capability throws std::invalid_argument for an unknown method; edit_capability, asked
// about a model's method, answers nullptr for one without a row, such as texton_mix.)
const TargetCapability* target_capability(std::string_view method);
const EditCapability* edit_capability(std::string_view method);
// The names of the methods with the capability, in registry order, as "a, b" for a message.
enum class CapabilityKind { target, edit };
std::string methods_with(CapabilityKind kind);

// The row's relative analysis cost per pixel and channel (RegistryRow::analysis_cost).
double analysis_cost(std::string_view method);
// The row's default analysis side (RegistryRow::analysis_side).
int analysis_side(std::string_view method);

// An edit sent as JSON ({"group": name, FIELD: number or [x, y], ...}, each optional) read against
// the capability's records; a std::invalid_argument of one sentence for a key or type it lacks.
// The values themselves are checked by the capability's edit.
EditValues edit_values_from_json(const EditCapability& edit, const nlohmann::ordered_json& body);

}  // namespace stochtex
