#pragma once
// Gabor noise by example, the dictionary of the spectrum fit (eq. 7, section 5.3): the
// bandwidth-quantised Gaussians on the frequency plane, and the operator S_n and its adjoint as FFT
// convolutions. The fit itself is fit.hpp.

#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "spectral/fft.hpp"

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
  // Steps of band `index`'s sub-grid: its Gaussians sit at bins (i step_x, j step_y). The steps
  // divide the sizes, so the sub-grid is symmetric under m -> -m and symmetric iterates stay
  // symmetric.
  int step_x(int index) const { return bands_[static_cast<std::size_t>(index)].step_x; }
  int step_y(int index) const { return bands_[static_cast<std::size_t>(index)].step_y; }
  // Sum of the normalised Gaussian of band `index`: the variance per unit coefficient.
  double mass(int index) const { return bands_[static_cast<std::size_t>(index)].mass; }
  // The sampled, normalised Gaussian of band `index` centred at bin (0, 0).
  std::span<const float> kernel(int index) const {
    return bands_[static_cast<std::size_t>(index)].kernel;
  }
  std::size_t plane_size() const { return static_cast<std::size_t>(width_) * height_; }

  // The coefficients of band `index` on its sub-grid alone: (width / step_x) x (height / step_y)
  // values, row-major (bin (i step_x, j step_y) at j width / step_x + i). An iterative solver keeps
  // these: off its grid a band's coefficients are zero.
  std::size_t grid_size(int index) const;
  // A full plane per band (zero off the band's grid) from the bands' grid coefficients, and back.
  std::vector<std::vector<float>> to_planes(const std::vector<std::vector<float>>& grids) const;
  std::vector<std::vector<float>> to_grids(const std::vector<std::vector<float>>& planes) const;

  // spectrum = S_n(coefficients), the coefficients on the bands' grids (grid_size(b) values a
  // band).
  void apply_grid(const std::vector<std::vector<float>>& coefficients,
                  std::vector<float>& spectrum) const;
  // out = S_n^T(spectrum) on the bands' grids (out[b] takes grid_size(b) values).
  void adjoint_grid(std::span<const float> spectrum, std::vector<std::vector<float>>& out) const;
  // The same on full planes (alpha and out: band_count() planes, zero off each band's grid).
  void apply(const std::vector<std::vector<float>>& alpha, std::vector<float>& spectrum) const;
  void adjoint(std::span<const float> spectrum, std::vector<std::vector<float>>& out) const;
  // Data weights w (width x height, positive): the operator becomes diag(w) S_n, so that a fit
  // minimises ||w (S_n(alpha) - S_ex)||^2 (a weighted data term; see spectrum_weights). Empty:
  // unweighted, eq. (8) as printed.
  void set_weights(std::vector<float> weights) { weights_ = std::move(weights); }
  std::span<const float> weights() const { return weights_; }

 private:
  // Columns column .. column + length - 1 of the full plane, which fold onto coarse columns
  // coarse_column .. coarse_column + length - 1.
  struct ColumnRun {
    int column = 0;
    int coarse_column = 0;
    int length = 0;
  };
  struct Band {
    int band = 0;
    int step_x = 1;
    int step_y = 1;
    std::unique_ptr<Fft2d> coarse_fft;  // null when the band covers every bin
    mutable std::vector<std::complex<float>> coarse_spectrum;
    mutable std::vector<std::complex<float>> coarse_row;  // the coarse DFT, both half-planes
    double mass = 0;
    std::vector<float> kernel;
    std::vector<float> kernel_spectrum;  // real: the kernel is even
    // Where kernel_spectrum is not negligible (above kSupportThreshold of its peak): a wide
    // Gaussian's spectrum is narrow, so a coarse band's products and folds run over these rows
    // (0 .. height - 1) and columns (0 .. width - 1, both half-planes) only, with the coarse bins
    // they map to. The columns are runs that map to consecutive coarse columns, in increasing
    // order: those of the stored half-plane (x < width / 2 + 1), then those of the other half.
    std::vector<int> support_rows;
    std::vector<int> support_coarse_rows;
    std::vector<ColumnRun> stored_runs;
    std::vector<ColumnRun> mirrored_runs;
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

}  // namespace stochtex::gabor
