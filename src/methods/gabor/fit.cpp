#include "methods/gabor/fit.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "spectral/fft.hpp"

namespace stochtex::gabor {
namespace {

using Complex = std::complex<float>;
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

double dot(std::span<const float> a, std::span<const float> b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += static_cast<double>(a[i]) * b[i];
  return sum;
}

// The buffers of a duality-gap evaluation, kept by the fit across its checks: the correlation
// alone is a grid per band.
struct GapBuffers {
  std::vector<float> model;
  std::vector<float> residual;
  std::vector<std::vector<float>> correlation;
};

// The duality gap at the coefficients `alpha` on the bands' grids (GaussianDictionary::grid_size),
// the layout the fit iterates in.
DualityGap duality_gap(const GaussianDictionary& dictionary, std::span<const float> target,
                       const std::vector<std::vector<float>>& alpha, double nu,
                       GapBuffers& buffers) {
  // Primal: ||S_n(alpha) - s||^2 + nu sum(alpha), alpha >= 0. Its Lagrange dual (Kim et al. 2007,
  // section III, with the sign constraint) is max_z -||z||^2 / 4 - z^T s subject to
  // S_n^T z >= -nu. The dual point is the scaled residual z = -2 t r, r = s - S_n(alpha), with the
  // best t that stays feasible: t <= nu / max(2 S_n^T r) and t* = r^T s / ||r||^2 unconstrained.
  std::vector<float>& model = buffers.model;
  dictionary.apply_grid(alpha, model);
  std::vector<float>& residual = buffers.residual;
  residual.resize(model.size());
  for (std::size_t i = 0; i < model.size(); ++i) residual[i] = target[i] - model[i];
  std::vector<std::vector<float>>& correlation = buffers.correlation;
  dictionary.adjoint_grid(residual, correlation);
  // Off its band's grid, alpha and the correlation are zero: only the grid is visited (skipping
  // zeros changes neither the largest value, which starts at 0, nor the sum).
  double largest = 0.0;
  double l1 = 0.0;
  for (std::size_t b = 0; b < alpha.size(); ++b)
    for (std::size_t i = 0; i < alpha[b].size(); ++i) {
      largest = std::max(largest, 2.0 * correlation[b][i]);
      l1 += alpha[b][i];
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

}  // namespace

DualityGap duality_gap(const GaussianDictionary& dictionary, std::span<const float> target,
                       const std::vector<std::vector<float>>& alpha, double nu) {
  GapBuffers buffers;
  return duality_gap(dictionary, target, dictionary.to_grids(alpha), nu, buffers);
}

SpectrumFit fit_spectrum(const GaussianDictionary& dictionary, std::span<const float> target,
                         const FitOptions& options, const std::function<void(double)>& progress) {
  const auto bands = static_cast<std::size_t>(dictionary.band_count());
  const std::size_t plane = dictionary.plane_size();
  if (target.size() != plane)
    throw std::invalid_argument("fit_spectrum: the target does not match the dictionary");
  SpectrumFit fit;
  // The iterates hold each band's grid alone (GaussianDictionary::grid_size), visited band by band
  // in row-major order; fit.alpha gets the full planes at the end.
  std::vector<std::vector<float>> alpha(bands);
  for (std::size_t b = 0; b < bands; ++b)
    alpha[b].assign(dictionary.grid_size(static_cast<int>(b)), 0.0f);
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
  dictionary.adjoint_grid(target, correlation);
  for (const auto& c : correlation)
    for (const float v : c) fit.nu_max = std::max(fit.nu_max, 2.0 * v);
  fit.residual_norm = fit.target_norm;
  if (!(fit.nu_max > 0.0)) {
    fit.alpha = dictionary.to_planes(alpha);
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
    for (std::size_t b = 0; b < bands; ++b) steps[b].assign(alpha[b].size(), 1.0f);
    std::vector<float> image;
    dictionary.apply_grid(steps, image);
    std::vector<std::vector<float>> row_sums;
    dictionary.adjoint_grid(image, row_sums);
    for (std::size_t b = 0; b < bands; ++b)
      for (std::size_t i = 0; i < steps[b].size(); ++i)
        steps[b][i] = row_sums[b][i] > 0.0f
                          ? static_cast<float>(1.0 / (2.0 * kLipschitzMargin * row_sums[b][i]))
                          : 0.0f;
  }

  std::vector<std::vector<float>> extrapolated = alpha;
  std::vector<std::vector<float>> previous = alpha;
  std::vector<std::vector<float>> gradient;
  GapBuffers gap_buffers;
  std::vector<float> model;
  std::vector<float> residual(plane);
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
    extrapolated = alpha;
    double momentum = 1.0;
    for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
      ++fit.iterations;
      dictionary.apply_grid(extrapolated, model);
      for (std::size_t i = 0; i < plane; ++i) residual[i] = model[i] - target[i];
      dictionary.adjoint_grid(residual, gradient);
      // Proximal step of nu ||a||_1 + indicator(a >= 0): a shifted, clipped gradient step.
      const auto penalty = static_cast<float>(nu);
      double restart_test = 0.0;
      for (std::size_t b = 0; b < bands; ++b) {
        float* const current = alpha[b].data();
        float* const last = previous[b].data();
        const float* const from = extrapolated[b].data();
        const float* const step_of = steps[b].data();
        const float* const slope = gradient[b].data();
        for (std::size_t i = 0; i < alpha[b].size(); ++i) {
          last[i] = current[i];
          const float step = step_of[i];
          const float value = std::max(0.0f, from[i] - step * (2.0f * slope[i] + penalty));
          current[i] = value;
          // In the preconditioned variable: the inner product weighted by D = 1 / (2 step).
          if (step > 0.0f)
            restart_test += static_cast<double>(from[i] - value) * (value - last[i]) / step;
        }
      }
      // Adaptive restart (O'Donoghue & Candes 2015): when the step goes against the momentum,
      // the momentum is reset. FISTA keeps its O(1/k^2) rate and gains linear convergence once
      // the support of the sparse solution has settled.
      if (restart_test > 0.0) momentum = 1.0;
      const double next_momentum = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum * momentum));
      const auto blend = static_cast<float>((momentum - 1.0) / next_momentum);
      momentum = next_momentum;
      for (std::size_t b = 0; b < bands; ++b)
        for (std::size_t i = 0; i < alpha[b].size(); ++i)
          extrapolated[b][i] = alpha[b][i] + blend * (alpha[b][i] - previous[b][i]);
      if (iteration % kGapCheckInterval == 0 || iteration == options.max_iterations) {
        const DualityGap gap = duality_gap(dictionary, target, alpha, nu, gap_buffers);
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
  dictionary.apply_grid(alpha, model);
  fit.residual_norm = unweighted_norm(model);
  fit.alpha = dictionary.to_planes(alpha);
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

std::vector<float> decimate_spectrum(std::span<const float> plane, int width, int height,
                                     int factor) {
  const int coarse_width = width / factor;
  const int coarse_height = height / factor;
  std::vector<double> tent;
  for (int k = 1 - factor; k < factor; ++k)
    tent.push_back(1.0 - std::abs(k) / static_cast<double>(factor));
  std::vector<float> result(static_cast<std::size_t>(coarse_width) * coarse_height);
  for (int y = 0; y < coarse_height; ++y)
    for (int x = 0; x < coarse_width; ++x) {
      double sum = 0.0;
      for (int ky = 1 - factor; ky < factor; ++ky) {
        const int fine_y = (y * factor + ky + height) % height;
        for (int kx = 1 - factor; kx < factor; ++kx) {
          const int fine_x = (x * factor + kx + width) % width;
          sum += tent[static_cast<std::size_t>(ky + factor - 1)] *
                 tent[static_cast<std::size_t>(kx + factor - 1)] *
                 plane[static_cast<std::size_t>(fine_y) * width + fine_x];
        }
      }
      result[static_cast<std::size_t>(y) * coarse_width + x] = static_cast<float>(sum);
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

}  // namespace stochtex::gabor
