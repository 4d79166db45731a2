#pragma once
// Lloyd's k-means of points on the integer plane, with a random initialisation drawn from a
// counter-based generator (core/hash.hpp), so that a seed gives the same groups everywhere. lrp
// breaks each stratum of its spectrum into sub-strata with it.

#include <array>
#include <vector>

#include "core/hash.hpp"

namespace stochtex {

// Groups `points` into `clusters` groups by at most `iterations` of Lloyd's algorithm, initialised
// on distinct points drawn with `rng` (random seeding). Every group ends non-empty: with no more
// points than groups, group j holds point j mod points.size() alone.
std::vector<std::vector<std::array<int, 2>>> kmeans(const std::vector<std::array<int, 2>>& points,
                                                    int clusters, int iterations, CounterRng& rng);

}  // namespace stochtex
