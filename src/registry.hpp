#pragma once
// The registry's analysis of one exemplar into a model that also carries a material's maps
// (src/material.cpp); stochtex::analyze is this call without maps.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/stochtex.hpp"

namespace stochtex {

// Refuses, before any work, an analysis by `method` of a width x height exemplar of `channels`
// channels: more channels than the method analyses, or beyond the memory budget.
void check_analysis_request(std::string_view method, int width, int height, int channels,
                            const std::string& source_name);

Model analyze_exemplar(std::string_view method, ImageView<const float> exemplar,
                       const ParamValues& params, std::uint32_t seed,
                       const std::string& source_name, const std::function<void(double)>& progress,
                       std::vector<MapInfo> maps);

}  // namespace stochtex
