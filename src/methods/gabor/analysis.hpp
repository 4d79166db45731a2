#pragma once
// Gabor noise by example, analysis (sections 3.2, 5 and 7): the periodogram of the periodic
// component, its sparse non-negative decomposition into bandwidth-quantised Gaussians, and the
// colour space of the independent channel synthesis. The pieces are public for tests.

#include <complex>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "methods/gabor/edit_analysis.hpp"
#include "methods/gabor/model.hpp"
#include "methods/gabor/params.hpp"
#include "spectral/fft.hpp"
#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::gabor {

// The Gaussians of eq. (7) on a width x height frequency plane (bins; row-major, DC at (0, 0),
// frequency (m_x / width, m_y / height) cycles per pixel, indices wrapping). Band b holds one
// Gaussian of bandwidth a_b at every bin of a sub-grid of step ~FWHM_b / 2 bins per axis
// (section 5.3: the widest Gaussians sit on a sub-sampled grid so the problem stays well
// conditioned). Each Gaussian is sampled periodically (the pixel grid aliases frequencies beyond
// Nyquist) and normalised to unit l2 norm, the usual column normalisation of basis pursuit: the
// paper's coefficient K^2 (section 5.1), like a unit-mass normalisation, makes a wide Gaussian
// cost far more l1 norm than a narrow one for the same fit, so the diffuse part of a spectrum is
// dropped and the noise loses variance (measured with unit-mass columns: 28% on metal_grey_256).
// A coefficient c adds c * mass(b) to the variance. The operator S_n of eq. (8) and its adjoint are
// FFT convolutions, one per band.
class GaussianDictionary {
 public:
  // The narrowest band spans `narrowest` bins (1: down to one bin, the paper's dictionary).
  GaussianDictionary(int width, int height, int narrowest = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  int band_count() const { return static_cast<int>(bands_.size()); }
  int band(int index) const { return bands_[static_cast<std::size_t>(index)].band; }
  // Steps of band `index`'s sub-grid: its Gaussians sit at bins (i step_x, j step_y).
  int step_x(int index) const { return bands_[static_cast<std::size_t>(index)].step_x; }
  int step_y(int index) const { return bands_[static_cast<std::size_t>(index)].step_y; }
  // 1 where band `index` has a Gaussian, 0 elsewhere (width x height).
  std::span<const float> mask(int index) const {
    return bands_[static_cast<std::size_t>(index)].mask;
  }
  // Sum of the normalised Gaussian of band `index`: the variance per unit coefficient.
  double mass(int index) const { return bands_[static_cast<std::size_t>(index)].mass; }
  // The sampled, normalised Gaussian of band `index` centred at bin (0, 0).
  std::span<const float> kernel(int index) const {
    return bands_[static_cast<std::size_t>(index)].kernel;
  }
  std::size_t plane_size() const { return static_cast<std::size_t>(width_) * height_; }

  // spectrum = S_n(alpha); alpha holds band_count() planes.
  void apply(const std::vector<std::vector<float>>& alpha, std::vector<float>& spectrum) const;
  // out = S_n^T(spectrum), zero off each band's grid.
  void adjoint(std::span<const float> spectrum, std::vector<std::vector<float>>& out) const;
  // Data weights w (width x height, positive): the operator becomes diag(w) S_n, so that a fit
  // minimises ||w (S_n(alpha) - S_ex)||^2 (a weighted data term; see spectrum_weights). Empty:
  // unweighted, eq. (8) as printed.
  void set_weights(std::vector<float> weights) { weights_ = std::move(weights); }
  std::span<const float> weights() const { return weights_; }

 private:
  struct Band {
    int band = 0;
    std::vector<float> mask;
    int step_x = 1;
    int step_y = 1;
    std::unique_ptr<Fft2d> coarse_fft;  // null when the band covers every bin
    mutable std::vector<float> coarse_plane;
    mutable std::vector<std::complex<float>> coarse_spectrum;
    mutable std::vector<std::complex<float>> coarse_row;  // the coarse DFT, both half-planes
    double mass = 0;
    std::vector<float> kernel;
    std::vector<float> kernel_spectrum;  // real: the kernel is even
    // Where kernel_spectrum is not negligible (above kSupportThreshold of its peak): a wide
    // Gaussian's spectrum is narrow, so a coarse band's products and folds run over these rows
    // (0 .. height - 1) and columns (0 .. width - 1, both half-planes) only, with the coarse bins
    // they map to.
    std::vector<int> support_rows;
    std::vector<int> support_coarse_rows;
    std::vector<int> support_columns;
    std::vector<int> support_coarse_columns;
  };
  int width_;
  int height_;
  std::vector<Band> bands_;
  std::unique_ptr<Fft2d> fft_;
  mutable std::vector<std::complex<float>> work_spectrum_;
  mutable std::vector<std::complex<float>> sum_spectrum_;
  std::vector<float> weights_;
  mutable std::vector<float> weighted_;
};

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

// Duality gap of eq. (8) at a non-negative alpha, and its primal objective.
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

// Data weights of the fit: w = (level / max level)^-gamma, the level being the periodogram
// smoothed by a Gaussian of kLevelSmoothing bins (floored at 1e-6 of its peak). The periodogram's
// noise has a standard deviation equal to its mean, so an unweighted fit (gamma = 0, the paper's)
// spends its l1 budget on the strong bins near DC and drops the diffuse part of the spectrum;
// gamma = 1/2 makes the l1 shrinkage proportional to the local level, gamma = 1 fits relative
// errors.
std::vector<float> spectrum_weights(std::span<const float> periodogram, int width, int height,
                                    double gamma);

// Colour (section 7). Matrices are n x n, row-major, in double.
using Matrix = std::vector<double>;

// Lagged correlation matrices C(xi) of eq. (9) of the centred channels (circular lags, as the
// periodic component is periodic) for every lag with |xi_x|, |xi_y| <= max_lag; C(0) first.
std::vector<Matrix> lagged_correlations(const std::vector<std::vector<float>>& channels, int width,
                                        int height, int max_lag);
// T such that T C(0) T^T = I and T C(xi) T^T is as diagonal as it can be for all xi together:
// whitening by C(0), then the Jacobi angles of Cardoso & Souloumiac (1996) on the symmetrised
// whitened matrices (approximate joint diagonalisation, section 7).
Matrix joint_diagonalizer(const std::vector<Matrix>& correlations, int n);
// T = the eigenvectors of C(0) as rows, largest variance first (the PCA colour space).
Matrix principal_axes(const Matrix& covariance, int n);
// J(T) of eq. (10), normalised: sum_xi off(T C T^T) / sum_xi ||T C T^T||_F^2 with T's rows scaled
// so that every channel has unit variance (the paper does not state its normalisation; this one
// makes J a fraction in [0, 1] that does not depend on the channels' scales).
double off_diagonality(const Matrix& transform, const std::vector<Matrix>& correlations, int n);

// The method's analysis. `progress` (may be empty) is called from the calling thread with the
// fraction done, at each iteration of the fit that thread runs; an exception it throws stops every
// channel's fit at its next iteration and is rethrown.
GaborModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                   const std::function<void(double)>& progress = {});

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<GaborModel>) {
  return {.summary =
              "Gabor noise by example (Galerne, Lagae, Lefebvre, Drettakis 2012): a sparse "
              "sum of bandwidth-quantised Gaussians fitted to the spectrum, ~2N kernels per "
              "sample",
          .fields = kFields,
          .analysis_memory = {.per_pixel = 200, .per_channel = 260},
          .max_channels = kMaxChannels,
          // The sparse fit takes about 100 times the other methods' analyses per pixel.
          .analysis_cost = 100.0,
          .edit = &kEdit};
}

}  // namespace stochtex::gabor
