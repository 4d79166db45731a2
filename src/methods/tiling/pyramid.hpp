#pragma once
// What a tiling model derives at construction, level by level of its mip pyramid (section 5.4):
// the levels of the Gaussianised exemplar G, and T^-1 prefiltered for each level (the follow-up
// of Deliot & Heitz 2019).

#include <vector>

#include "methods/tiling/model.hpp"

namespace stochtex::tiling {

// Level l + 1 averages 2 x 2 texels of level l with periodic wrap, so every level keeps the mean
// of G exactly and the exemplar's period (texels_per_pixel = level width / exemplar width).
std::vector<std::vector<float>> build_pyramid(const std::vector<float>& base, int width, int height,
                                              int channels, std::vector<int>& widths,
                                              std::vector<int>& heights);

// Whether `group`'s T^-1 tables give channel `channel` (one of the group's) as linear light: a
// srgb channel of the 3-D table, of a direct table or of a one-channel decorrelated group (whose
// output mean + b t is a function of its one table; b not 0), with the histogram blend's T^-1.
// Groups of several decorrelated channels mix their tables linearly and cannot be decoded in them.
bool decodes_in_tables(const TilingData& d, const TableGroup& group, int channel);

// T^-1 prefiltered for each level of the pyramid `texels` (level l is widths[l] x heights[l], as
// build_pyramid makes it; see prefilter_kernel in pyramid.cpp): appends level l's 3-D table to
// `level_luts` and its 1-D tables to `level_tables`, level 0's as the model has them. The residual
// deviation differs per channel.
void prefilter_levels(const TilingData& d, const TilingLayout& layout,
                      const std::vector<std::vector<float>>& texels, const std::vector<int>& widths,
                      const std::vector<int>& heights, std::vector<float>& level_luts,
                      std::vector<float>& level_tables);

}  // namespace stochtex::tiling
