#pragma once
// Gabor noise by example, the spectrum fit (sections 3.2 and 5): the periodogram of a channel, the
// data weights of the fit, and its sparse non-negative decomposition into the Gaussians of the
// dictionary (dictionary.hpp) by basis pursuit denoising (eq. 8).

#include <functional>
#include <span>
#include <vector>

#include "methods/gabor/dictionary.hpp"

namespace stochtex::gabor {

struct FitOptions {
  double kappa = 1.0 / 256.0;
  int max_iterations = 400;     // per homotopy step
  double gap_tolerance = 1e-3;  // stop when duality gap <= tolerance * primal objective
};

struct SpectrumFit {
  std::vector<std::vector<float>> alpha;  // one plane per band of the dictionary
  double nu = 0;                          // kappa * nu_max
  double nu_max = 0;                      // 2 ||S_n^T(S_ex)||_inf
  double primal = 0;                      // objective of eq. (8) at alpha
  double gap = 0;                         // duality gap at alpha: primal - optimum <= gap
  int iterations = 0;                     // FISTA iterations over all homotopy steps
  int steps = 0;                          // homotopy steps (kappa = 1/2, 1/4, ..., kappa)
  bool converged = false;                 // the last step met the gap tolerance
  double residual_norm = 0;               // ||S_n(alpha) - S_ex||_2, unweighted
  double target_norm = 0;                 // ||S_ex||_2, unweighted
};

// Non-negative basis pursuit denoising (eq. 8) by FISTA (Beck & Teboulle 2009) with the
// duality-gap stop (Kim et al. 2007), over the homotopy kappa = 1/2, 1/4, ... down to
// options.kappa, each step warm-started from the previous one (section 5.2). With the
// dictionary's weights w, `target` is the weighted spectrum w S_ex and the problem is eq. (8) for
// the operator diag(w) S_n. FISTA is diagonally preconditioned: coefficient j steps by
// 1 / (2 D_j), D = A^T A 1 (A the operator: non-negative entries, so diag(D) majorises A^T A).
// `progress` (may be empty) is called after each iteration with the fraction done; an exception
// it throws stops the fit.
SpectrumFit fit_spectrum(const GaussianDictionary& dictionary, std::span<const float> target,
                         const FitOptions& options,
                         const std::function<void(double)>& progress = {});

// Duality gap of eq. (8) at a non-negative alpha (zero off each band's grid, as a fit's), and its
// primal objective.
struct DualityGap {
  double primal = 0;
  double dual = 0;
  double gap = 0;
};
DualityGap duality_gap(const GaussianDictionary& dictionary, std::span<const float> target,
                       const std::vector<std::vector<float>>& alpha, double nu);

// Periodogram |DFT(plane)|^2 / (width height)^2 on the full width x height plane (section 3.2):
// it sums to the plane's mean square.
std::vector<float> periodogram(std::span<const float> plane, int width, int height);

// The periodogram on a coarser plane of (width / factor) x (height / factor) bins, bin j reading
// the bins factor j + k of `plane` with the triangle weights (1 - |k_x| / factor)
// (1 - |k_y| / factor), |k| < factor: the weights of every fine bin sum to 1, so the coarse plane
// keeps the total (the variance), and it stays symmetric under m -> -m. factor divides both sizes.
std::vector<float> decimate_spectrum(std::span<const float> plane, int width, int height,
                                     int factor);

// Data weights of the fit: w = (level / max level)^-gamma, the level being the periodogram
// smoothed by a Gaussian of kLevelSmoothing bins (floored at 1e-6 of its peak). The periodogram's
// noise has a standard deviation equal to its mean, so an unweighted fit (gamma = 0, the paper's)
// spends its l1 budget on the strong bins near DC and drops the diffuse part of the spectrum;
// gamma = 1/2 makes the l1 shrinkage proportional to the local level, gamma = 1 fits relative
// errors.
std::vector<float> spectrum_weights(std::span<const float> periodogram, int width, int height,
                                    double gamma);

}  // namespace stochtex::gabor
