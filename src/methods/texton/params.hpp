#pragma once
// Texton noise parameters (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017), described once
// (methods/param_record.hpp). The record feeds the CLI (`-p name=value`), the model file and
// docs/methods/texton.md.

#include <algorithm>
#include <array>

#include "methods/param_record.hpp"

namespace stochtex::texton {

// support 0 (the default) lets the exemplar decide: its whole smaller side when that is at most
// kWholeSupportMax (no support crop: Algorithm 1's support projection is the identity), else
// kCroppedSupport. docs/methods/texton.md, "Fidelity on the shipped exemplars", has the
// measurements.
inline constexpr int kWholeSupportMax = 256;
inline constexpr int kCroppedSupport = 128;

// The side of the texton for a `support` parameter and a width x height exemplar.
constexpr int texton_support(int support, int width, int height) {
  const int side = std::min(width, height);
  if (support == 0) return side <= kWholeSupportMax ? side : kCroppedSupport;
  return std::min(support, side);
}

// The point process of the impacts (`points`). poisson: the paper's (sections 3.3, 8): a Poisson
// number of uniform points per grid cell, each scattering the texton with weight 1. balanced (the
// default, our variant): each cell holds the same whole number of points (the cells are sized
// for it, CellCount::whole_mean in core/cell_count.hpp; model.cpp) on a randomly shifted lattice
// (evaluate.hpp's CellCache), each scattering the texton with a random sign eps_j in {-1, +1}
// (section 7's marks). With signs of mean zero the covariance is lambda C for any points that are
// each uniform in their cell (the cross terms cancel), so the model is unchanged; but one render's
// variance no longer moves with how many points it holds and where (docs/methods/texton.md,
// "Fidelity on the shipped exemplars").
enum PointProcess : int { kPoissonPoints = 0, kBalancedPoints = 1 };

struct Params {
  int support = 0;
  int order = 1;
  int iterations = 50;
  double mni = 30;
  int points = kBalancedPoints;

  bool operator==(const Params&) const = default;
};

inline constexpr std::array<ParamChoice, 4> kOrders = {
    {{"nearest", 0}, {"bilinear", 1}, {"cubic", 3}, {"quintic", 5}}};

inline constexpr std::array<ParamChoice, 2> kPointProcesses = {
    {{"poisson", kPoissonPoints}, {"balanced", kBalancedPoints}}};

inline constexpr std::array<ParamField<Params>, 5> kFields = {{
    chosen_number_field<&Params::support>(
        "support", 2, 1024,
        "side of the square support S of the texton coefficients, in exemplar pixels (section "
        "4.2), clamped to the exemplar's smaller side; 0: the whole exemplar when its "
        "smaller side is at most 256, else 128"),
    choice_field<&Params::order>(
        "order", kOrders,
        "B-spline interpolation order k of the texton: nearest (k = 0), bilinear (k = 1, the "
        "paper's choice), cubic (k = 3), quintic (k = 5) (section 10)"),
    number_field<&Params::iterations>(
        "iterations", 0, 10000, "number n of alternating projections of Algorithm 1 (section 4.2)"),
    number_field<&Params::mni>(
        "mni", 1, 10000,
        "mean number of impacts: the mean count of textons covering a point (sections 3.3, 9); "
        "the evaluation cost per sample grows linearly with it"),
    choice_field<&Params::points>(
        "points", kPointProcesses,
        "point process of the impacts: poisson (the paper's: Poisson counts of uniform points, "
        "weight 1) or balanced (the same whole number of points in every cell, on a shifted "
        "lattice, each with a random sign as in section 7: the same covariance, and one render's "
        "variance steadier)"),
}};

inline constexpr auto kParams = param_infos(kFields);

}  // namespace stochtex::texton
