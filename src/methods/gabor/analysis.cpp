#include "methods/gabor/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "core/colour_statistics.hpp"
#include "core/parallel.hpp"
#include "methods/gabor/params.hpp"
#include "spectral/periodic.hpp"
#include "spectral/principal_components.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gabor {
namespace {

using Complex = std::complex<float>;
constexpr double kPi = std::numbers::pi;
// The FISTA steps keep a 10% margin under the diagonal majoriser (float rounding of the FFT
// operators; a slightly short step only slows down).
constexpr double kLipschitzMargin = 1.1;
// Standard deviation, in bins, of the Gaussian that smooths the periodogram into the level of
// the fit's data weights (spectrum_weights): wider than the periodogram's one-bin noise, narrower
// than the spectral features the weights must follow.
constexpr double kLevelSmoothing = 2.0;
// FISTA checks the duality gap every this many iterations (a check costs one more S_n S_n^T).
constexpr int kGapCheckInterval = 10;
constexpr double kIntermediateGapFactor = 5.0;
// The operators skip the bins where a band's kernel spectrum is below this fraction of its peak:
// the level of the single-precision FFT's own rounding error (~1e-7 log2 n of the peak), not a
// Gaussian's tail worth keeping. The fits change within the solver's tolerance (docs).
constexpr float kSupportThreshold = 1e-6f;
// Lags |xi|_inf <= 4 of the lagged correlation matrices (section 7): 81 matrices. Longer lags of a
// 128^2 exemplar carry mostly estimation noise.
constexpr int kMaxLag = 4;
// The channels' fits run in parallel, each with its own dictionary and iterates (~370 bytes a
// pixel at 256², measured): at most this many at once, so that the analysis memory row
// (registry_row) bounds a material of up to kMaxChannels channels on any core count (9 channels
// at 256², 4 fits in flight: 1852 bytes a pixel against the row's 2540; 9 in flight: 3325).
// Exemplars of 1 to 4 channels fit every channel at once where the cores allow, as before.
constexpr int kMaxFitsInFlight = 4;
// narrowest = 0 (automatic): the first fit's dictionary stops at bands of this FWHM in bins. The
// l2 fit of a feature narrower than the dictionary's Gaussians spreads it and inflates its mass
// (a one-bin peak fitted by one Gaussian of any width gets twice its mass): when the first fit's
// variance exceeds the periodogram's by more than kAutoVarianceExcess, it is redone down to one
// bin (measured: wood_planks_256 1.31, rock_sandstone_512 1.06, the diffuse exemplars 0.99-1.03).
// The coarse fit costs about kAutoCoarseShare of the full one (its bands are all sub-sampled).
constexpr int kAutoNarrowest = 4;
constexpr double kAutoVarianceExcess = 1.15;
constexpr double kAutoCoarseShare = 0.25;

double dot(std::span<const float> a, std::span<const float> b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += static_cast<double>(a[i]) * b[i];
  return sum;
}

Eigen::MatrixXd to_eigen(const Matrix& m, int n) {
  Eigen::MatrixXd result(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) result(i, j) = m[static_cast<std::size_t>(i) * n + j];
  return result;
}

Matrix from_eigen(const Eigen::MatrixXd& m) {
  const auto n = static_cast<int>(m.rows());
  Matrix result(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) result[static_cast<std::size_t>(i) * n + j] = m(i, j);
  return result;
}

// Step of band b's sub-grid (section 5.3): about half the band's FWHM of 2^-b * size bins, so
// neighbouring Gaussians overlap at half height, and a power of two that divides the size so the
// band can be transformed on the coarse grid alone.
int grid_step(int size, int band) {
  const double target = std::ldexp(static_cast<double>(size), -band) / 2.0;
  int step = 1;
  while (2 * step <= target && size % (2 * step) == 0) step *= 2;
  return step;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Dictionary (eq. 7)

GaussianDictionary::GaussianDictionary(int width, int height, int narrowest)
    : width_(width), height_(height), fft_(std::make_unique<Fft2d>(width, height)) {
  const int longest = std::max(width, height);
  const std::size_t plane = plane_size();
  work_spectrum_.resize(fft_->spectrum_size());
  sum_spectrum_.resize(fft_->spectrum_size());
  // Band b has a FWHM of 2^-b cycles per pixel = 2^-b * size bins (section 4.3); the narrowest
  // band kept spans `narrowest` bins of the longer side (one: the paper's), band 0 always.
  for (int b = 0;
       b < kMaxBands && (b == 0 || std::ldexp(static_cast<double>(longest), -b) >= narrowest);
       ++b) {
    Band band;
    band.band = b;
    const double sigma = bandwidth(b) / (2.0 * std::sqrt(kPi));  // cycles per pixel (eq. 3)
    const int step_x = grid_step(width, b);
    const int step_y = grid_step(height, b);
    band.step_x = step_x;
    band.step_y = step_y;
    if (step_x > 1 || step_y > 1) {
      band.coarse_fft = std::make_unique<Fft2d>(width / step_x, height / step_y);
      band.coarse_plane.resize(band.coarse_fft->image_size());
      band.coarse_spectrum.resize(band.coarse_fft->spectrum_size());
      band.coarse_row.resize(band.coarse_fft->image_size());
    }
    band.mask.assign(plane, 0.0f);
    band.kernel.assign(plane, 0.0f);
    double squared = 0.0;
    for (int y = 0; y < height; ++y) {
      const int signed_y = y <= height / 2 ? y : y - height;
      for (int x = 0; x < width; ++x) {
        const int signed_x = x <= width / 2 ? x : x - width;
        // The steps divide the sizes: the sub-grid is symmetric under m -> -m, so symmetric
        // iterates stay symmetric.
        if (x % step_x == 0 && y % step_y == 0)
          band.mask[static_cast<std::size_t>(y) * width + x] = 1.0f;
        double value = 0.0;
        for (int ky = -2; ky <= 2; ++ky)
          for (int kx = -2; kx <= 2; ++kx) {
            const double fx = (signed_x + kx * width) / static_cast<double>(width);
            const double fy = (signed_y + ky * height) / static_cast<double>(height);
            value += std::exp(-(fx * fx + fy * fy) / (2.0 * sigma * sigma));
          }
        band.kernel[static_cast<std::size_t>(y) * width + x] = static_cast<float>(value);
        squared += value * value;
      }
    }
    const double norm = std::sqrt(squared);
    band.mass = 0.0;
    for (float& v : band.kernel) {
      v = static_cast<float>(v / norm);
      band.mass += v;
    }
    fft_->forward(band.kernel, work_spectrum_);
    band.kernel_spectrum.resize(work_spectrum_.size());
    for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
      band.kernel_spectrum[i] = work_spectrum_[i].real();
    // Support of the kernel's spectrum: a Gaussian of sd ~2^b / (2 pi 0.42) bins for band b.
    const int half = fft_->spectrum_width();
    float peak = 0.0f;
    for (const float v : band.kernel_spectrum) peak = std::max(peak, std::abs(v));
    int reach_x = 0;
    int reach_y = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < half; ++x)
        if (std::abs(band.kernel_spectrum[static_cast<std::size_t>(y) * half + x]) >
            kSupportThreshold * peak) {
          reach_x = std::max(reach_x, x);
          reach_y = std::max(reach_y, std::min(y, height - y));
        }
    const int coarse_width = width / step_x;
    const int coarse_height = height / step_y;
    for (int y = 0; y < height; ++y)
      if (std::min(y, height - y) <= reach_y) {
        band.support_rows.push_back(y);
        band.support_coarse_rows.push_back(y % coarse_height);
      }
    for (int x = 0; x < width; ++x)
      if (std::min(x, width - x) <= reach_x) {
        band.support_columns.push_back(x);
        band.support_coarse_columns.push_back(x % coarse_width);
      }
    bands_.push_back(std::move(band));
  }
}

// A band on a sub-grid of steps (sx, sy) is an upsampled image of (W / sx) x (H / sy) values:
// its DFT is the coarse DFT repeated sx x sy times, and decimating a full image to the sub-grid
// folds its DFT onto the coarse one. So a sub-sampled band costs a coarse FFT, not a full one.
void GaussianDictionary::apply(const std::vector<std::vector<float>>& alpha,
                               std::vector<float>& spectrum) const {
  std::fill(sum_spectrum_.begin(), sum_spectrum_.end(), Complex(0.0f, 0.0f));
  const int half = width_ / 2 + 1;
  for (std::size_t b = 0; b < bands_.size(); ++b) {
    const Band& band = bands_[b];
    const std::vector<float>& kernel = band.kernel_spectrum;
    if (!band.coarse_fft) {
      fft_->forward(alpha[b], work_spectrum_);
      for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
        sum_spectrum_[i] += work_spectrum_[i] * kernel[i];
      continue;
    }
    const int coarse_width = width_ / band.step_x;
    const int coarse_height = height_ / band.step_y;
    const int coarse_half = coarse_width / 2 + 1;
    for (int j = 0; j < coarse_height; ++j)
      for (int i = 0; i < coarse_width; ++i)
        band.coarse_plane[static_cast<std::size_t>(j) * coarse_width + i] =
            alpha[b][static_cast<std::size_t>(j * band.step_y) * width_ + i * band.step_x];
    band.coarse_fft->forward(band.coarse_plane, band.coarse_spectrum);
    // The coarse DFT is Hermitian: its missing half comes from the conjugate at -k. Bin k of the
    // full spectrum reads coarse bin k mod (coarse size), tiled row by row without divisions.
    const std::size_t coarse_rows = static_cast<std::size_t>(coarse_height);
    std::vector<Complex>& row = band.coarse_row;
    for (std::size_t cy = 0; cy < coarse_rows; ++cy) {
      const std::size_t mirror_y = (coarse_rows - cy) % coarse_rows;
      for (int cx = 0; cx < coarse_width; ++cx)
        row[static_cast<std::size_t>(cy) * coarse_width + cx] =
            cx < coarse_half
                ? band.coarse_spectrum[cy * coarse_half + cx]
                : std::conj(band.coarse_spectrum[mirror_y * coarse_half + (coarse_width - cx)]);
    }
    // Only where the kernel's spectrum is not negligible.
    for (std::size_t r = 0; r < band.support_rows.size(); ++r) {
      const Complex* coarse =
          &row[static_cast<std::size_t>(band.support_coarse_rows[r]) * coarse_width];
      const std::size_t offset = static_cast<std::size_t>(band.support_rows[r]) * half;
      for (std::size_t c = 0; c < band.support_columns.size(); ++c) {
        const auto kx = static_cast<std::size_t>(band.support_columns[c]);
        if (kx < static_cast<std::size_t>(half))
          sum_spectrum_[offset + kx] +=
              coarse[band.support_coarse_columns[c]] * kernel[offset + kx];
      }
    }
  }
  spectrum.resize(plane_size());
  fft_->inverse(sum_spectrum_, spectrum);
  if (!weights_.empty())
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= weights_[i];
}

void GaussianDictionary::adjoint(std::span<const float> spectrum,
                                 std::vector<std::vector<float>>& out) const {
  // The kernels are even, so the adjoint of a convolution by them is the same convolution.
  if (weights_.empty()) {
    fft_->forward(spectrum, sum_spectrum_);
  } else {
    weighted_.resize(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) weighted_[i] = spectrum[i] * weights_[i];
    fft_->forward(weighted_, sum_spectrum_);
  }
  out.resize(bands_.size());
  const int half = width_ / 2 + 1;
  for (std::size_t b = 0; b < bands_.size(); ++b) {
    const Band& band = bands_[b];
    const std::vector<float>& kernel = band.kernel_spectrum;
    out[b].resize(plane_size());
    if (!band.coarse_fft) {
      for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
        work_spectrum_[i] = sum_spectrum_[i] * kernel[i];
      fft_->inverse(work_spectrum_, out[b]);
      continue;
    }
    const int coarse_width = width_ / band.step_x;
    const int coarse_height = height_ / band.step_y;
    const int coarse_half = coarse_width / 2 + 1;
    // Fold the product onto the coarse spectrum: every full bin k adds to coarse bin
    // k mod (coarse size); bins where the kernel's spectrum is negligible are skipped. The full
    // spectrum's missing half is the conjugate at -k (the kernel is even and real).
    std::vector<Complex>& row = band.coarse_row;
    std::fill(row.begin(), row.end(), Complex(0.0f, 0.0f));
    for (std::size_t r = 0; r < band.support_rows.size(); ++r) {
      const int ky = band.support_rows[r];
      Complex* coarse = &row[static_cast<std::size_t>(band.support_coarse_rows[r]) * coarse_width];
      const std::size_t offset = static_cast<std::size_t>(ky) * half;
      const std::size_t mirror = static_cast<std::size_t>((height_ - ky) % height_) * half;
      for (std::size_t c = 0; c < band.support_columns.size(); ++c) {
        const auto kx = static_cast<std::size_t>(band.support_columns[c]);
        const std::size_t mirrored = mirror + static_cast<std::size_t>(width_) - kx;
        coarse[band.support_coarse_columns[c]] +=
            kx < static_cast<std::size_t>(half)
                ? sum_spectrum_[offset + kx] * kernel[offset + kx]
                : std::conj(sum_spectrum_[mirrored]) * kernel[mirrored];
      }
    }
    for (int cy = 0; cy < coarse_height; ++cy)
      for (int cx = 0; cx < coarse_half; ++cx)
        band.coarse_spectrum[static_cast<std::size_t>(cy) * coarse_half + cx] =
            row[static_cast<std::size_t>(cy) * coarse_width + cx];
    // Decimation keeps 1 / (sx sy) of the samples; Fft2d::inverse divides by the coarse size.
    const auto fold = static_cast<float>(1.0 / (band.step_x * band.step_y));
    for (Complex& value : band.coarse_spectrum) value *= fold;
    band.coarse_fft->inverse(band.coarse_spectrum, band.coarse_plane);
    std::fill(out[b].begin(), out[b].end(), 0.0f);
    for (int j = 0; j < coarse_height; ++j)
      for (int i = 0; i < coarse_width; ++i)
        out[b][static_cast<std::size_t>(j * band.step_y) * width_ + i * band.step_x] =
            band.coarse_plane[static_cast<std::size_t>(j) * coarse_width + i];
  }
}

// ---------------------------------------------------------------------------------------------
// Non-negative basis pursuit denoising (eq. 8)

DualityGap duality_gap(const GaussianDictionary& dictionary, std::span<const float> target,
                       const std::vector<std::vector<float>>& alpha, double nu) {
  // Primal: ||S_n(alpha) - s||^2 + nu sum(alpha), alpha >= 0. Its Lagrange dual (Kim et al. 2007,
  // section III, with the sign constraint) is max_z -||z||^2 / 4 - z^T s subject to
  // S_n^T z >= -nu. The dual point is the scaled residual z = -2 t r, r = s - S_n(alpha), with the
  // best t that stays feasible: t <= nu / max(2 S_n^T r) and t* = r^T s / ||r||^2 unconstrained.
  std::vector<float> model;
  dictionary.apply(alpha, model);
  std::vector<float> residual(model.size());
  for (std::size_t i = 0; i < model.size(); ++i) residual[i] = target[i] - model[i];
  std::vector<std::vector<float>> correlation;
  dictionary.adjoint(residual, correlation);
  double largest = 0.0;
  double l1 = 0.0;
  for (std::size_t b = 0; b < alpha.size(); ++b) {
    for (const float c : correlation[b]) largest = std::max(largest, 2.0 * c);
    for (const float a : alpha[b]) l1 += a;
  }
  const double residual_squared = dot(residual, residual);
  const double residual_target = dot(residual, target);
  DualityGap result;
  result.primal = residual_squared + nu * l1;
  double t = residual_squared > 0.0 ? residual_target / residual_squared : 0.0;
  if (largest > 0.0) t = std::min(t, nu / largest);
  t = std::max(t, 0.0);
  result.dual = -t * t * residual_squared + 2.0 * t * residual_target;
  result.gap = std::max(0.0, result.primal - result.dual);
  return result;
}

SpectrumFit fit_spectrum(const GaussianDictionary& dictionary, std::span<const float> target,
                         const FitOptions& options, const std::function<void(double)>& progress) {
  const auto bands = static_cast<std::size_t>(dictionary.band_count());
  const std::size_t plane = dictionary.plane_size();
  if (target.size() != plane)
    throw std::invalid_argument("fit_spectrum: the target does not match the dictionary");
  SpectrumFit fit;
  fit.alpha.assign(bands, std::vector<float>(plane, 0.0f));
  // The unweighted residual ||S_n(alpha) - S_ex|| of (weighted) model and target.
  const std::span<const float> weights = dictionary.weights();
  const auto unweighted_norm = [&](std::span<const float> model) {
    double sum = 0.0;
    for (std::size_t i = 0; i < plane; ++i) {
      const double difference = static_cast<double>(model[i]) - target[i];
      sum += weights.empty()
                 ? difference * difference
                 : difference * difference / (static_cast<double>(weights[i]) * weights[i]);
    }
    return std::sqrt(sum);
  };
  fit.target_norm = unweighted_norm(std::vector<float>(plane, 0.0f));
  std::vector<std::vector<float>> correlation;
  dictionary.adjoint(target, correlation);
  for (const auto& c : correlation)
    for (const float v : c) fit.nu_max = std::max(fit.nu_max, 2.0 * v);
  fit.residual_norm = fit.target_norm;
  if (!(fit.nu_max > 0.0)) {
    fit.converged = true;  // alpha = 0 is optimal for every nu
    return fit;
  }
  // Gradient of ||A a - s||^2 is 2 A^T (A a - s). A has non-negative entries, so A^T A is
  // majorised by the diagonal of its row sums D = A^T A 1 (diag(D) - A^T A is diagonally
  // dominant): coefficient j steps by 1 / (2 D_j), i.e. FISTA in the variable D^1/2 a, whose
  // Lipschitz constant is at most 2. Against the global step 1 / (2 ||A||^2) this lets the
  // narrow bands and, with data weights, the weakly weighted bins move as fast as the rest.
  std::vector<std::vector<float>> steps(bands);
  {
    for (std::size_t b = 0; b < bands; ++b) {
      const std::span<const float> mask = dictionary.mask(static_cast<int>(b));
      steps[b].assign(mask.begin(), mask.end());
    }
    std::vector<float> image;
    dictionary.apply(steps, image);
    std::vector<std::vector<float>> row_sums;
    dictionary.adjoint(image, row_sums);
    for (std::size_t b = 0; b < bands; ++b)
      for (std::size_t i = 0; i < plane; ++i)
        steps[b][i] = steps[b][i] > 0.0f && row_sums[b][i] > 0.0f
                          ? static_cast<float>(1.0 / (2.0 * kLipschitzMargin * row_sums[b][i]))
                          : 0.0f;
  }

  std::vector<std::vector<float>> extrapolated = fit.alpha;
  std::vector<std::vector<float>> previous = fit.alpha;
  std::vector<std::vector<float>> gradient;
  std::vector<float> model;
  std::vector<float> residual(plane);
  // Only the bins of each band's sub-grid carry coefficients: the other entries stay zero.
  // visit(band, index) runs over those, band by band, row by row.
  const auto for_each_coefficient = [&](auto&& visit) {
    for (std::size_t b = 0; b < bands; ++b) {
      const int step_x = dictionary.step_x(static_cast<int>(b));
      const int step_y = dictionary.step_y(static_cast<int>(b));
      for (int y = 0; y < dictionary.height(); y += step_y)
        for (int x = 0; x < dictionary.width(); x += step_x)
          visit(b, static_cast<std::size_t>(y) * dictionary.width() + x);
    }
  };
  // Homotopy (section 5.2): kappa = 1/2, 1/4, ..., then options.kappa, each step warm-started.
  std::vector<double> kappas;
  for (double kappa = 0.5; kappa > options.kappa; kappa *= 0.5) kappas.push_back(kappa);
  kappas.push_back(options.kappa);
  for (const double kappa : kappas) {
    const double steps_before = fit.steps;
    const double nu = kappa * fit.nu_max;
    fit.nu = nu;
    ++fit.steps;
    fit.converged = false;
    extrapolated = fit.alpha;
    double momentum = 1.0;
    for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
      ++fit.iterations;
      dictionary.apply(extrapolated, model);
      for (std::size_t i = 0; i < plane; ++i) residual[i] = model[i] - target[i];
      dictionary.adjoint(residual, gradient);
      // Proximal step of nu ||a||_1 + indicator(a >= 0): a shifted, clipped gradient step.
      const auto penalty = static_cast<float>(nu);
      double restart_test = 0.0;
      for_each_coefficient([&](std::size_t b, std::size_t i) {
        previous[b][i] = fit.alpha[b][i];
        const float step = steps[b][i];
        const float value =
            std::max(0.0f, extrapolated[b][i] - step * (2.0f * gradient[b][i] + penalty));
        fit.alpha[b][i] = value;
        // In the preconditioned variable: the inner product weighted by D = 1 / (2 step).
        if (step > 0.0f)
          restart_test +=
              static_cast<double>(extrapolated[b][i] - value) * (value - previous[b][i]) / step;
      });
      // Adaptive restart (O'Donoghue & Candes 2015): when the step goes against the momentum,
      // the momentum is reset. FISTA keeps its O(1/k^2) rate and gains linear convergence once
      // the support of the sparse solution has settled.
      if (restart_test > 0.0) momentum = 1.0;
      const double next_momentum = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum * momentum));
      const auto blend = static_cast<float>((momentum - 1.0) / next_momentum);
      momentum = next_momentum;
      for_each_coefficient([&](std::size_t b, std::size_t i) {
        extrapolated[b][i] = fit.alpha[b][i] + blend * (fit.alpha[b][i] - previous[b][i]);
      });
      if (iteration % kGapCheckInterval == 0 || iteration == options.max_iterations) {
        const DualityGap gap = duality_gap(dictionary, target, fit.alpha, nu);
        fit.primal = gap.primal;
        fit.gap = gap.gap;
        // Intermediate homotopy steps only seed the next one: a looser gap is enough there.
        const double tolerance = kappa == kappas.back()
                                     ? options.gap_tolerance
                                     : kIntermediateGapFactor * options.gap_tolerance;
        if (gap.gap <= tolerance * gap.primal) {
          fit.converged = true;
          break;
        }
      }
      if (progress)
        progress((steps_before + static_cast<double>(iteration) / options.max_iterations) /
                 static_cast<double>(kappas.size()));
    }
  }
  dictionary.apply(fit.alpha, model);
  fit.residual_norm = unweighted_norm(model);
  return fit;
}

std::vector<float> periodogram(std::span<const float> plane, int width, int height) {
  const Fft2d fft(width, height);
  std::vector<Complex> spectrum(fft.spectrum_size());
  fft.forward(plane, spectrum);
  const int half = fft.spectrum_width();
  const double pixels = static_cast<double>(width) * height;
  const double normalisation = 1.0 / (pixels * pixels);
  std::vector<float> result(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // The other half-plane by Hermitian symmetry: X(-m) = conj(X(m)).
      const bool stored = x < half;
      const int sx = stored ? x : width - x;
      const int sy = stored ? y : (height - y) % height;
      const Complex value = spectrum[static_cast<std::size_t>(sy) * half + sx];
      result[static_cast<std::size_t>(y) * width + x] =
          static_cast<float>(std::norm(value) * normalisation);
    }
  return result;
}

std::vector<float> spectrum_weights(std::span<const float> periodogram, int width, int height,
                                    double gamma) {
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  if (!(gamma > 0.0)) return {};
  const Fft2d fft(width, height);
  std::vector<float> blur(pixels);
  double total = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = std::min(x, width - x);
      const double dy = std::min(y, height - y);
      const double value =
          std::exp(-(dx * dx + dy * dy) / (2.0 * kLevelSmoothing * kLevelSmoothing));
      blur[static_cast<std::size_t>(y) * width + x] = static_cast<float>(value);
      total += value;
    }
  for (float& v : blur) v = static_cast<float>(v / total);
  std::vector<Complex> kernel(fft.spectrum_size());
  std::vector<Complex> spectrum(fft.spectrum_size());
  fft.forward(blur, kernel);
  fft.forward(periodogram, spectrum);
  // The blur is even and real: its DFT is real.
  for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= kernel[i].real();
  std::vector<float> level(pixels);
  fft.inverse(spectrum, level);
  const float peak = *std::max_element(level.begin(), level.end());
  std::vector<float> weights(pixels, 1.0f);
  if (!(peak > 0.0f)) return weights;
  for (std::size_t i = 0; i < pixels; ++i)
    weights[i] = static_cast<float>(std::pow(std::max(level[i] / peak, 1e-6f), -gamma));
  return weights;
}

// ---------------------------------------------------------------------------------------------
// Colour (section 7)

std::vector<Matrix> lagged_correlations(const std::vector<std::vector<float>>& channels, int width,
                                        int height, int max_lag) {
  const auto n = static_cast<int>(channels.size());
  const Fft2d fft(width, height);
  std::vector<std::vector<Complex>> spectra(channels.size(),
                                            std::vector<Complex>(fft.spectrum_size()));
  for (std::size_t c = 0; c < channels.size(); ++c) fft.forward(channels[c], spectra[c]);
  const int lags = 2 * max_lag + 1;
  std::vector<Matrix> result(static_cast<std::size_t>(lags) * lags,
                             Matrix(static_cast<std::size_t>(n) * n));
  std::vector<Complex> cross(fft.spectrum_size());
  std::vector<float> correlation(fft.image_size());
  // C_ij(xi) = 1/|Omega| sum_x I_i(x) I_j(x + xi) = inverse DFT of conj(X_i) X_j (circular).
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < cross.size(); ++k)
        cross[k] = std::conj(spectra[i][k]) * spectra[j][k];
      fft.inverse(cross, correlation);
      std::size_t index = 0;
      // C(0) first, then the other lags in raster order.
      const auto store = [&](int lx, int ly, std::size_t slot) {
        const int x = (lx + width) % width;
        const int y = (ly + height) % height;
        result[slot][static_cast<std::size_t>(i) * n + j] =
            correlation[static_cast<std::size_t>(y) * width + x];
      };
      store(0, 0, index++);
      for (int ly = -max_lag; ly <= max_lag; ++ly)
        for (int lx = -max_lag; lx <= max_lag; ++lx)
          if (lx != 0 || ly != 0) store(lx, ly, index++);
    }
  return result;
}

Matrix principal_axes(const Matrix& covariance, int n) {
  const PrincipalComponents components = principal_components(covariance, n);
  // The variances come in increasing order: the axes as rows, largest variance first.
  Matrix result(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      result[static_cast<std::size_t>(i) * n + j] =
          components.axes[static_cast<std::size_t>(j) * n + (n - 1 - i)];
  return result;
}

Matrix joint_diagonalizer(const std::vector<Matrix>& correlations, int n) {
  // Whitening: W = Lambda^-1/2 E^T makes W C(0) W^T = I; eigenvalues are floored so a channel with
  // no variance (a grey image stored as RGB) stays finite.
  const PrincipalComponents components = principal_components(correlations.front(), n);
  const Eigen::Map<const Eigen::VectorXd> variances(components.variances.data(), n);
  const double floor = 1e-9 * std::max(1e-30, variances.maxCoeff());
  const Eigen::VectorXd scale = variances.cwiseMax(floor).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd whitening = scale.asDiagonal() * to_eigen(components.axes, n).transpose();
  std::vector<Eigen::MatrixXd> matrices;
  for (std::size_t k = 1; k < correlations.size(); ++k) {
    const Eigen::MatrixXd c = to_eigen(correlations[k], n);
    matrices.push_back(whitening * (0.5 * (c + c.transpose())) * whitening.transpose());
  }
  // Cardoso & Souloumiac (1996): sweeps of Givens rotations; for the pair (p, q) the angle that
  // minimises the off-diagonal energy of all matrices together is the principal direction of the
  // 2 x 2 matrix G = sum_k g_k g_k^T, g_k = (A_pp - A_qq, A_pq + A_qp).
  Eigen::MatrixXd rotation = Eigen::MatrixXd::Identity(n, n);
  constexpr double kThreshold = 1e-12;
  constexpr int kMaxSweeps = 100;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    bool rotated = false;
    for (int p = 0; p < n - 1; ++p)
      for (int q = p + 1; q < n; ++q) {
        double g00 = 0.0, g01 = 0.0, g11 = 0.0;
        for (const auto& a : matrices) {
          const double u = a(p, p) - a(q, q);
          const double v = a(p, q) + a(q, p);
          g00 += u * u;
          g01 += u * v;
          g11 += v * v;
        }
        const double ton = g00 - g11;
        const double toff = 2.0 * g01;
        const double theta = 0.5 * std::atan2(toff, ton + std::sqrt(ton * ton + toff * toff));
        const double c = std::cos(theta);
        const double s = std::sin(theta);
        if (std::abs(s) <= kThreshold) continue;
        rotated = true;
        Eigen::MatrixXd givens = Eigen::MatrixXd::Identity(n, n);
        givens(p, p) = c;
        givens(p, q) = -s;
        givens(q, p) = s;
        givens(q, q) = c;
        rotation = rotation * givens;
        for (auto& a : matrices) a = givens.transpose() * a * givens;
      }
    if (!rotated) break;
  }
  return from_eigen(rotation.transpose() * whitening);
}

double off_diagonality(const Matrix& transform, const std::vector<Matrix>& correlations, int n) {
  Eigen::MatrixXd t = to_eigen(transform, n);
  const Eigen::MatrixXd covariance = t * to_eigen(correlations.front(), n) * t.transpose();
  for (int i = 0; i < n; ++i) {
    const double variance = covariance(i, i);
    if (variance > 0.0) t.row(i) /= std::sqrt(variance);
  }
  double off = 0.0;
  double total = 0.0;
  for (const Matrix& c : correlations) {
    const Eigen::MatrixXd a = t * to_eigen(c, n) * t.transpose();
    total += a.squaredNorm();
    off += a.squaredNorm() - a.diagonal().squaredNorm();
  }
  return total > 0.0 ? off / total : 0.0;
}

// ---------------------------------------------------------------------------------------------
// The analysis

GaborModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t /*seed*/,
                   const std::function<void(double)>& progress) {
  const int width = exemplar.width;
  const int height = exemplar.height;
  const int channels = exemplar.channels;
  const auto colour_space = static_cast<int>(params.colour_space);
  FitOptions options;
  options.kappa = params.kappa;
  options.max_iterations = params.iterations;

  // The periodic component (section 3.2, [Moisan 2011]): no cross artefact in its spectrum.
  const ImageF periodic = periodic_component(exemplar);
  const std::size_t pixels = periodic.pixel_count();
  std::vector<float> mean;
  for (const double value : channel_means(periodic.view()))
    mean.push_back(static_cast<float>(value));
  std::vector<std::vector<float>> centred(static_cast<std::size_t>(channels),
                                          std::vector<float>(pixels));
  for (int c = 0; c < channels; ++c) {
    for (std::size_t i = 0; i < pixels; ++i)
      centred[c][i] = periodic.pixels()[i * channels + c] - mean[c];
  }

  // Colour space (section 7): T maps centred colours to the synthesis channels.
  FitReport report;
  Matrix transform(static_cast<std::size_t>(channels) * channels, 0.0);
  for (int c = 0; c < channels; ++c) transform[static_cast<std::size_t>(c) * channels + c] = 1.0;
  if (channels > 1) {
    const std::vector<Matrix> correlations =
        lagged_correlations(centred, width, height, std::min({kMaxLag, width / 2, height / 2}));
    const Matrix independent = joint_diagonalizer(correlations, channels);
    const Matrix pca = principal_axes(correlations.front(), channels);
    report.offdiagonality_independent = off_diagonality(independent, correlations, channels);
    report.offdiagonality_pca = off_diagonality(pca, correlations, channels);
    report.offdiagonality_rgb = off_diagonality(transform, correlations, channels);
    if (colour_space == static_cast<int>(ColourSpace::independent)) transform = independent;
    if (colour_space == static_cast<int>(ColourSpace::pca)) transform = pca;
  }
  const Eigen::MatrixXd forward = to_eigen(transform, channels);
  const Eigen::MatrixXd backward = forward.inverse();
  std::vector<float> mixing(static_cast<std::size_t>(channels) * channels);
  for (int i = 0; i < channels; ++i)
    for (int j = 0; j < channels; ++j)
      mixing[static_cast<std::size_t>(i) * channels + j] = static_cast<float>(backward(i, j));
  if (!std::all_of(mixing.begin(), mixing.end(), [](float v) { return std::isfinite(v); }))
    throw Error(ErrorCode::numerical, "gabor: the colour transform is singular");

  // Each synthesis channel's spectrum is fitted on its own (independent channel synthesis), the
  // channels in parallel, each with its own dictionary (the operators keep work buffers). Each fit
  // is the same whatever the thread count.
  std::vector<std::vector<float>> targets(static_cast<std::size_t>(channels));
  for (int k = 0; k < channels; ++k) {
    std::vector<float> plane(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      double value = 0.0;
      for (int c = 0; c < channels; ++c)
        value += forward(k, c) * static_cast<double>(centred[c][i]);
      plane[i] = static_cast<float>(value);
    }
    targets[static_cast<std::size_t>(k)] = periodogram(plane, width, height);
  }
  // Per channel: its Gaussians and the unweighted residual and target norms of its fit.
  struct ChannelFit {
    std::vector<GaussianComponent> gaussians;
    double residual_norm = 0.0;
    double target_norm = 0.0;
  };
  std::vector<ChannelFit> fits(static_cast<std::size_t>(channels));
  // Progress: every fit records its fraction; the calling thread reports their mean. What the hook
  // throws is kept, and the other fits stop at their next iteration.
  std::vector<std::atomic<double>> fit_fraction(fits.size());
  std::atomic<bool> cancelled{false};
  std::exception_ptr cancellation;
  const auto caller = std::this_thread::get_id();
  // Fit k's progress, its fraction mapped onto [from, to].
  const auto fit_progress = [&](std::size_t k, double from,
                                double to) -> std::function<void(double)> {
    if (!progress) return {};
    return [&, k, from, to](double fraction) {
      fit_fraction[k] = from + (to - from) * fraction;
      if (std::this_thread::get_id() != caller) {
        if (cancelled) throw Error(ErrorCode::numerical, "gabor: the analysis was cancelled");
        return;
      }
      double sum = 0.0;
      for (const auto& f : fit_fraction) sum += f;
      try {
        progress(sum / static_cast<double>(fit_fraction.size()));
      } catch (...) {
        cancellation = std::current_exception();
        cancelled = true;
        throw;
      }
    };
  };
  // Fits channel k with a dictionary whose narrowest band spans `narrowest` bins; the weighted
  // problem: operator diag(w) S_n, target w S_ex.
  const auto fit_channel = [&](std::size_t k, int narrowest, std::span<const float> weights,
                               std::span<const float> target, double from, double to) {
    GaussianDictionary dictionary(width, height, narrowest);
    dictionary.set_weights(std::vector<float>(weights.begin(), weights.end()));
    const SpectrumFit fit = fit_spectrum(dictionary, target, options, fit_progress(k, from, to));
    ChannelFit result;
    result.residual_norm = fit.residual_norm;
    result.target_norm = fit.target_norm;
    // Every non-zero coefficient is a Gaussian (section 5.1). The fit runs on the full plane with
    // a symmetric target, so its iterates are symmetric: the Gaussians at m and -m form one pair
    // of eq. (6) with variance alpha(m) + alpha(-m) (half-plane, section 5.3).
    for (int b = 0; b < dictionary.band_count(); ++b) {
      const std::vector<float>& alpha = fit.alpha[static_cast<std::size_t>(b)];
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const std::size_t index = static_cast<std::size_t>(y) * width + x;
          const std::size_t mirror =
              static_cast<std::size_t>((height - y) % height) * width + (width - x) % width;
          if (mirror < index) continue;
          const auto variance = static_cast<float>(
              dictionary.mass(b) * (mirror == index ? alpha[index] : alpha[index] + alpha[mirror]));
          if (!(variance > 0.0f)) continue;
          const int signed_x = x < (width + 1) / 2 ? x : x - width;
          const int signed_y = y < (height + 1) / 2 ? y : y - height;
          result.gaussians.push_back({static_cast<int>(k), dictionary.band(b),
                                      static_cast<float>(static_cast<double>(signed_x) / width),
                                      static_cast<float>(static_cast<double>(signed_y) / height),
                                      variance});
        }
    }
    return result;
  };
  try {
    parallel_for(
        fits.size(), std::min(resolve_thread_count(0), kMaxFitsInFlight), [&](std::size_t k) {
          std::vector<float> weights =
              spectrum_weights(targets[k], width, height, params.weighting);
          double target_variance = 0.0;
          for (const float v : targets[k]) target_variance += v;
          for (std::size_t i = 0; i < weights.size(); ++i) targets[k][i] *= weights[i];
          const auto fitted_variance = [&] {
            double variance = 0.0;
            for (const GaussianComponent& g : fits[k].gaussians) variance += g.variance;
            return variance;
          };
          if (params.narrowest > 0) {
            fits[k] = fit_channel(k, params.narrowest, weights, targets[k], 0.0, 1.0);
          } else {
            // Automatic: the dictionary down to kAutoNarrowest bins first; the full one (one
            // bin) when that fit inflates the variance (features narrower than its Gaussians).
            fits[k] = fit_channel(k, kAutoNarrowest, weights, targets[k], 0.0, kAutoCoarseShare);
            if (fitted_variance() > kAutoVarianceExcess * target_variance)
              fits[k] = fit_channel(k, 1, weights, targets[k], kAutoCoarseShare, 1.0);
          }
          // The channel's noise gets its periodogram's variance (the periodic component's, as
          // ADSN's); the fit error reports the fit itself.
          const double variance = fitted_variance();
          if (params.renormalise && variance > 0.0)
            for (GaussianComponent& g : fits[k].gaussians)
              g.variance = static_cast<float>(g.variance * (target_variance / variance));
        });
  } catch (...) {
    if (cancellation) std::rethrow_exception(cancellation);
    throw;
  }
  std::vector<GaussianComponent> gaussians;
  double residual_squared = 0.0;
  double target_squared = 0.0;
  for (ChannelFit& fit : fits) {
    residual_squared += fit.residual_norm * fit.residual_norm;
    target_squared += fit.target_norm * fit.target_norm;
    gaussians.insert(gaussians.end(), fit.gaussians.begin(), fit.gaussians.end());
    fit.gaussians = {};
  }
  report.sparseness =
      static_cast<double>(gaussians.size()) / (static_cast<double>(pixels) * channels);
  report.fit_error = target_squared > 0.0 ? std::sqrt(residual_squared / target_squared) : 0.0;
  if (gaussians.size() > kMaxGaussians)
    throw Error(ErrorCode::invalid_input,
                "gabor: the fit has more Gaussians than a model may hold; raise kappa");
  return GaborModel(channels, params.impulses, colour_space, std::move(gaussians),
                    std::move(mixing), std::move(mean), report);
}

}  // namespace stochtex::gabor
