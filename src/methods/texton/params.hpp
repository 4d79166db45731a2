#pragma once
// Texton noise parameters (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017), described once.
// The record feeds the CLI (`-p name=value`), the model file and docs/methods/texton.md.

#include <array>

#include "stochtex/model.hpp"

namespace stochtex::texton {

inline constexpr std::array<double, 4> kAllowedOrders = {0, 1, 3, 5};

inline constexpr std::array<ParamInfo, 4> kParams = {{
    {"support", 128, 2, 1024, true,
     "side of the square support S of the texton coefficients, in exemplar pixels (section 4.2); "
     "clamped to the exemplar's smaller side"},
    {"order", 1, 0, 5, true,
     "B-spline interpolation order k of the texton: 0 nearest, 1 bilinear (the paper's choice), "
     "3 cubic, 5 quintic (section 10)",
     kAllowedOrders},
    {"iterations", 50, 0, 10000, true,
     "number n of alternating projections of Algorithm 1 (section 4.2)"},
    {"mni", 30, 1, 10000, false,
     "mean number of impacts: the mean count of textons covering a point (sections 3.3, 9); the "
     "evaluation cost per sample grows linearly with it"},
}};

}  // namespace stochtex::texton
