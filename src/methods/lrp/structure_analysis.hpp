#pragma once
// Analysis of the structure of local random-phase noise (section 5 of Gilet et al. 2014): the
// fixed-phase region R of energy ratio r (section 5.1), the structure image and its subdivision
// into blocks of J_R cosines (section 5.3), the turbulence noise (section 5.2).

#include <cstdint>
#include <span>
#include <vector>

#include "methods/lrp/structure.hpp"
#include "stochtex/image.hpp"

namespace stochtex::lrp {

// Section 5.3: the subdivision stops once the mean colour deviation of n_R from the structure
// image is below the colour precision, "1/256 in general".
inline constexpr double kStructureTolerance = 1.0 / 256.0;

// R for one decorrelated channel: the frequencies of highest power of a size x size crop holding
// the fraction `ratio` of its energy (section 5.1), and the structure image, the inverse Fourier
// transform of the crop's spectrum on R only (section 5.3).
struct FixedPhaseRegion {
  int size = 0;
  std::vector<float> structure_image;  // size x size, row-major, zero mean
  std::vector<int> bins;               // full-plane indices ky * size + kx of R (both k and -k)
  double energy_fraction = 0.0;        // energy of R over the crop's energy (>= ratio)
};

// `component` is one zero-mean decorrelated channel of the exemplar; R is taken on the periodic
// component (Moisan) of its top-left size x size crop, "any of the blocks used in Welch's method".
FixedPhaseRegion fixed_phase_region(ImageView<const float> component, int size, double ratio);
// Zeroes the power of R's frequencies (size x size, as SpectrumTarget), leaving the complement to
// the random strata (section 5.1: "the complement is still computed as in section 4").
void remove_region(std::vector<double>& power, const FixedPhaseRegion& region);
// J_R = rJ (section 5.3), at least one cosine when r > 0.
int structure_cosines(double ratio, int cosines);

// The outcome of the subdivision of section 5.3, per level tried (for tests and docs).
struct SubdivisionLevel {
  int blocks = 0;          // B per side
  double deviation = 0.0;  // mean |colour deviation| of n_R from the structure image
};

// Section 5.3: J_R cosines per block, blocks subdivided (B = 1, 2, 4...) until the mean colour
// deviation (colour = basis * channels, `colour_basis` row-major channels x channels) is below
// kStructureTolerance, blocks reach 2 pixels, or the table would exceed the model file's limit.
// Returns the StructureData without turbulence or placement; `levels` (may be null) receives the
// deviation of every level tried.
StructureData reduce_structure(std::span<const FixedPhaseRegion> regions, int cosines_per_block,
                               std::span<const float> colour_basis,
                               std::vector<SubdivisionLevel>* levels = nullptr);

// Section 5.2: the turbulence noise n_T of `power` (size x size, a channel's full spectrum),
// kTurbulenceStrata strata of kTurbulenceCosines cosines scaled to unit variance, into
// `structure` with sigma = `turbulence`. Nothing is stored when sigma is 0.
void plan_turbulence(std::span<const double> power, int size, double turbulence, std::uint32_t key,
                     StructureData& structure);

}  // namespace stochtex::lrp
