#pragma once
// Binary masks on a size x size torus (row-major, `size` cells a side), for the analyses that
// work on the frequency plane of a sampled spectrum, which is periodic: lrp's strata wrap around
// the Nyquist border.

#include <vector>

namespace stochtex {

// Squared Euclidean distance from each cell to the nearest cell outside `inside` (nonzero: inside),
// by the separable transform of Felzenszwalb & Huttenlocher (2012). Each line is transformed three
// periods long and read in the middle, which is exact on the torus.
std::vector<double> periodic_distance_squared(const std::vector<char>& inside, int size);

// Labels of the 8-connected parts of `inside` (0, 1, ... in the order of their first cell; -1
// outside).
std::vector<int> connected_parts(const std::vector<char>& inside, int size);

}  // namespace stochtex
