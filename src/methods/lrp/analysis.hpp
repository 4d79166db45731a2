#pragma once
// Analysis of local random-phase noise (sections 4.1-4.4 of the paper): a target power spectrum,
// from an exemplar (Welch's method) or given as a continuous function sampled on a grid, is cut
// into L equal-energy strata, each shrunk by erosion and broken into J_S sub-strata by k-means.

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "methods/lrp/model.hpp"
#include "methods/lrp/params.hpp"
#include "methods/lrp/target_analysis.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp {

// A power spectrum on the size x size grid of frequencies k / size (cycles per pixel): row-major,
// the vertical frequency as the row, DC at (0, 0), symmetric (power(k) == power(-k)). Its sum is
// the variance of the noise; `mean` is added to it.
struct SpectrumTarget {
  int size = 0;
  std::vector<double> power;
  double mean = 0.0;
};

// Continuous targets of the paper's figure 10, sampled on a size x size grid (size >= 8, even).
// A ring of radius `radius` and Gaussian profile of standard deviation `width` (cycles per pixel).
SpectrumTarget ring_spectrum(int size, double radius, double width, double variance);
// An anisotropic Gaussian pair at +-(centre_x, centre_y) with standard deviations `along` in the
// direction of the centre and `across` perpendicular to it (cycles per pixel); a centre of (0, 0)
// gives a low-pass blob elongated along x.
SpectrumTarget gaussian_spectrum(int size, double centre_x, double centre_y, double along,
                                 double across, double variance);

// One stratum as the analysis builds it; exposed for tests and docs.
struct StratumPlan {
  double energy = 0.0;        // E_S, the stratum's share of the variance
  int bins = 0;               // |S|: frequencies of the stratum on the full plane
  double lowest_power = 0.0;  // the stratum is {k : power(k) in [lowest_power, highest_power]}
  double highest_power = 0.0;
  Stratum sampling;             // J_S, Delta_S, A_S
  double erosion_radius = 0.0;  // delta in frequency bins (section 4.3)
  double eroded_radius = 0.0;   // the radius actually used (smaller when delta would empty S)
  std::vector<std::vector<std::array<int, 2>>> substrata;  // signed bins, upper half-plane
  // Amplitude of each frequency of `substrata` relative to A_S: all 1 as published (section
  // 4.3), or shaped by the target's power (parameter `amplitudes`, analysis.cpp).
  std::vector<std::vector<float>> weights;
};

// The largest power of two strictly below the exemplar's smaller side (section 4.4).
int welch_size(int width, int height);
// Welch's estimate (section 4.4, metrics.hpp) is the spectrum blurred by its Hann window: a
// frequency on bin k lands on k and its neighbours with weights 1/6, 2/3, 1/6 per axis. A model
// renders each bin as a frequency, so the render's own estimate is blurred twice (parameter
// `deblur`, docs/methods/lrp.md). This undoes most of that blur on a size x size estimate (DC at
// index 0): a 5-tap approximation of the inverse per axis, negative values clamped to zero, DC
// kept at zero. A tone had 44% of its power on its bin and gets 92% back (test); the sum is kept
// but for the clamped values (9% for a tone, which is all side lobes).
std::vector<double> deblur_welch(std::span<const double> power, int size);
// The radius, in cycles per lattice spacing, of the disc holding `fraction` of the energy of the
// 2-D window's spectrum |W-hat|^2 (W(x) = w(|x|)), by numerical Hankel transform (section 4.3).
double window_energy_radius(double fraction);
// A stratum's lattice spacing: section 4.3's Delta_S = T sqrt(J_S) / sqrt(2 |S|) times `widen`
// (parameter `widen`), at least `floor` pixels (parameter `spacing`). The defaults are the paper's.
struct SpacingRule {
  double widen = 1.0;
  double floor = 0.0;
};
// Sections 4.2-4.3 for one channel: `power` is a SpectrumTarget's power (size x size). `shaped`:
// per-frequency amplitudes (parameter `amplitudes`). `key` seeds the k-means initialisation of
// each stratum.
std::vector<StratumPlan> plan_strata(std::span<const double> power, int size, int strata,
                                     int cosines, bool shaped, SpacingRule spacing,
                                     std::uint32_t key);

// The model of an exemplar: PCA-decorrelated channels, Welch spectrum of each, strata.
LrpModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed);
// The grey model of a continuous target (section 6.1, figure 10).
LrpModel analyze_spectrum(const SpectrumTarget& target, const Params& params, std::uint32_t seed);
// The same as a library Model (render, evaluate, save_model work on it); `params` may be partial.
Model spectrum_model(const SpectrumTarget& target, const ParamValues& params = {},
                     std::uint32_t seed = 0);

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<LrpModel>) {
  return {.summary =
              "local random-phase noise (Gilet et al. 2014): windowed cosines with random "
              "phases on a lattice, 9 (J + L) cosines and windows per channel and sample",
          .fields = kFields,
          .analysis_memory = {.per_pixel = 36, .per_channel = 12},
          .max_channels = kMaxChannels,
          .target = &kTarget};
}

}  // namespace stochtex::lrp
