#pragma once
// Histogram-preserving tiling and blending parameters (Heitz & Neyret, "High-Performance
// By-Example Noise using a Histogram-Preserving Blending Operator", HPG 2018), described once.
// The record feeds the CLI (`-p name=value`), the model file and docs/methods/tiling.md.

#include <array>

#include "stochtex/model.hpp"

namespace stochtex::tiling {

inline constexpr std::array<double, 2> kTransports = {0, 1};
inline constexpr std::array<double, 3> kBlends = {0, 1, 2};
inline constexpr std::array<double, 2> kFlags = {0, 1};

inline constexpr std::array<ParamInfo, 7> kParams = {{
    {"tile_radius", 0.5, 0.05, 4.0, false,
     "radius of the hexagonal tiles (the edge of the triangle lattice) as a fraction of the "
     "exemplar's smaller side; section 5.3 uses about one half"},
    {"transport", 0, 0, 1, true,
     "Gaussianisation T: 0 iterated sliced optimal transport in colour space (sections 4.1-4.3), "
     "1 PCA-decorrelated per-channel 1-D transport (Deliot & Heitz 2019)",
     kTransports},
    {"iterations", 64, 1, 2000, true,
     "iterations of the sliced transport, each along 3 orthogonal random directions (transport 0)"},
    {"lut_size", 32, 2, 64, true,
     "cells per axis of the 3-D look-up table of T^-1 for colour exemplars (section 4.3)"},
    {"table_size", 1024, 16, 65536, true,
     "entries of each 1-D look-up table of T^-1 (grey and alpha channels, transport 1)"},
    {"blend", 0, 0, 2, true,
     "blending operator: 0 histogram-preserving (eq. 18); 1 variance-preserving on the exemplar "
     "as is (eq. 8), the fast path for Gaussian inputs such as `stochtex gaussian` output (no T, "
     "no T^-1; section 6.1); 2 linear (eq. 3), a baseline that loses contrast between vertices",
     kBlends},
    {"stationarity", 0, 0, 1, true,
     "1: before the analysis, remove from the colour the variations of periods longer than about a "
     "tile (a periodic Gaussian high-pass of deviation tile edge / pi), the preprocessing of "
     "section 5.3 for exemplars with large-scale variations; the histogram kept is then the "
     "filtered exemplar's",
     kFlags},
}};

}  // namespace stochtex::tiling
