#pragma once
// Analysis of histogram-preserving tiling and blending: the Gaussianisation T of the exemplar
// (sections 4.1-4.2) and its inverse T^-1 as look-up tables (section 4.3), by one of two
// transports, and the transports themselves (public for tests and benchmarks).

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "methods/tiling/model.hpp"
#include "methods/tiling/params.hpp"
#include "stochtex/image.hpp"

namespace stochtex::tiling {

// Iterated sliced optimal transport (Pitie et al. 2007, Rabin et al. 2011): each iteration draws
// a random orthonormal basis of R^dims and, along each of its directions, moves every point so that
// its rank among the projected points meets the same-rank quantile of the target's projection. The
// points converge to the target distribution along a near-optimal (L2) displacement. `source` and
// the result are count x dims, interleaved. Deterministic in `seed`.
std::vector<float> sliced_transport_to_points(std::span<const float> source,
                                              std::span<const float> target, int dims,
                                              int iterations, std::uint32_t seed);
// The same towards the continuous Gaussian of eq. (20) (mean 1/2, deviation 1/6 per axis): its
// projection on a unit direction d is the 1-D Gaussian of mean sum(d)/2 and deviation 1/6, whose
// quantiles are exact, so no Gaussian point set needs to be drawn or sorted.
std::vector<float> sliced_transport_to_gaussian(std::span<const float> source, int dims,
                                                int iterations, std::uint32_t seed);

// Exact 1-D transport of `values` to the Gaussian of eq. (20): the value of rank k among n becomes
// 1/2 + Phi^-1((k + 1/2) / n) / 6, written to `gaussian` (n entries). Fills `table` with T^-1: the
// quantiles of `values` at the uniform levels (k + 1/2) / table.size() of eq. (22).
void gaussianise_1d(std::span<const float> values, std::span<float> gaussian,
                    std::span<float> table);
// The radial T of a normal map's slopes (GroupTransform::radial): `slopes` and `gaussian` hold n
// pairs; the pair of magnitude rank k among n keeps its direction and gets the radius of the 2-D
// Gaussian of eq. (20) at level (k + 1/2) / n, uniform_to_radius. Fills `table` with T^-1's
// magnitudes: the quantiles of |s| at the uniform levels (k + 1/2) / table.size().
void gaussianise_radial(std::span<const float> slopes, std::span<float> gaussian,
                        std::span<float> table);

// The tile radius chosen from the exemplar (tile_radius = 0). Section 5.3 asks the tiles to capture
// the exemplar's frequency content: the blend multiplies the exemplar's covariance by the overlap
// of the tiles' weights, which fades over about a tile, so periods longer than a tile's diameter
// are lost. The radius returned is the smallest edge e (a fraction of the smaller side) such that
// at most kAutoTileLeak of the power of the exemplar's periodic component (each channel weighted
// by its own power) lies at periods longer than 2 e, clamped to [kAutoTileRadiusMin, 1/2]: a
// larger tile than the exemplar's width would repeat its content within one tile.
inline constexpr double kAutoTileLeak = 0.005;
inline constexpr double kAutoTileRadiusMin = 0.25;
double auto_tile_radius(ImageView<const float> exemplar);

// Histogram-preserving tiling and blending analysis. `maps`: a material's layout (issue 18), whose
// maps go through T and T^-1 in groups of their own (material_groups in analysis.cpp).
TilingModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                    std::span<const MapInfo> maps = {});

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<TilingModel>) {
  return {
      "histogram-preserving tiling and blending (Heitz, Neyret 2018): 3 patches of the "
      "Gaussianised exemplar and one look-up per sample",
      kFields,
      {.per_pixel = 40, .per_channel = 25},
      kMaxChannels,
      false};  // a material's normal map comes from the same patches as its height
}

}  // namespace stochtex::tiling
