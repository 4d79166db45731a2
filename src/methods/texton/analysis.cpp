#include "methods/texton/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "core/colour_statistics.hpp"
#include "core/hash.hpp"
#include "methods/texton/evaluate.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"
#include "spectral/principal_components.hpp"
#include "spectral/white_noise.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::texton {
namespace {

using Complex = std::complex<float>;

// One axis of b-hat: the DFT over `length` samples of the B-spline of degree 2k+1 sampled on the
// integers, the autocorrelation psi~ * psi of the order-k interpolation kernel (section 4.1 and
// section 10). It is real and positive (a sampled odd-degree B-spline has a positive spectrum).
std::vector<double> sampled_bspline_spectrum(int order, int length, int frequencies) {
  std::vector<double> spectrum(static_cast<std::size_t>(frequencies));
  for (int q = 0; q < frequencies; ++q) {
    double value = bspline(2 * order + 1, 0.0);
    for (int m = 1; m <= order; ++m)
      value += 2.0 * bspline(2 * order + 1, m) * std::cos(2.0 * std::numbers::pi * q * m / length);
    spectrum[q] = value;
  }
  return spectrum;
}

// Step 1.b of Algorithm 1 in colour (section 4.3): alpha-hat <- (t-hat* alpha-hat /
// |t-hat* alpha-hat|) t-hat / sqrt(b-hat), the phase of the projection of alpha-hat on the line
// spanned by t-hat (grey: the phase of alpha-hat). `kernel` already holds t-hat / sqrt(b-hat).
// One phase per frequency for all channels keeps the joint cross-spectrum t-hat t-hat^*, whatever
// the channel count (a material's maps too: issue 18).
// This is the hottest loop of the analysis: the channel count is a template parameter so the
// channel loops unroll (Channels = 0: any count up to kMaxChannels, read from `kernel`), and
// complex products are written out because std::complex's operator* checks for NaN operands (C99
// Annex G) and is several times slower.
template <int Channels>
void project_spectrum(const std::vector<std::vector<Complex>>& kernel,
                      std::vector<std::vector<Complex>>& alpha) {
  constexpr int kSlots = Channels > 0 ? Channels : kMaxChannels;
  const int channels = Channels > 0 ? Channels : static_cast<int>(kernel.size());
  std::array<const Complex*, kSlots> t;
  std::array<Complex*, kSlots> a;
  for (int c = 0; c < channels; ++c) {
    t[c] = kernel[c].data();
    a[c] = alpha[c].data();
  }
  const std::size_t size = kernel[0].size();
  for (std::size_t i = 0; i < size; ++i) {
    float inner_re = 0.0f;
    float inner_im = 0.0f;
    for (int c = 0; c < channels; ++c) {
      inner_re += t[c][i].real() * a[c][i].real() + t[c][i].imag() * a[c][i].imag();
      inner_im += t[c][i].real() * a[c][i].imag() - t[c][i].imag() * a[c][i].real();
    }
    const float magnitude_squared = inner_re * inner_re + inner_im * inner_im;
    const float inverse = magnitude_squared > 0.0f ? 1.0f / std::sqrt(magnitude_squared) : 0.0f;
    const float phase_re = magnitude_squared > 0.0f ? inner_re * inverse : 1.0f;
    const float phase_im = inner_im * inverse;
    for (int c = 0; c < channels; ++c)
      a[c][i] = Complex(phase_re * t[c][i].real() - phase_im * t[c][i].imag(),
                        phase_re * t[c][i].imag() + phase_im * t[c][i].real());
  }
}

// The decomposition is principal_components' (one instantiation of Eigen's eigen-solver for the
// library: it is among the costliest templates to compile).
Eigen::MatrixXd symmetric_power(const Eigen::MatrixXd& matrix, double power) {
  const auto n = static_cast<int>(matrix.rows());
  std::vector<double> entries(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) entries[static_cast<std::size_t>(i) * n + j] = matrix(i, j);
  const PrincipalComponents components = principal_components(entries, n);
  const Eigen::Map<const Eigen::VectorXd> eigenvalues(components.variances.data(), n);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      eigenvectors(components.axes.data(), n, n);
  // Eigenvalues of a covariance are >= 0; a floor keeps a channel with no variance finite.
  const double floor = 1e-12 * std::max(1e-30, eigenvalues.cwiseAbs().maxCoeff());
  Eigen::VectorXd values = eigenvalues.cwiseMax(floor).array().pow(power);
  return eigenvectors * values.asDiagonal() * eigenvectors.transpose();
}

}  // namespace

std::vector<std::vector<std::complex<float>>> normalised_kernel_spectrum(
    const Fft2d& fft, ImageView<const float> periodic, std::span<const float> mean) {
  const std::size_t pixels = static_cast<std::size_t>(periodic.width) * periodic.height;
  const int channels = periodic.channels;
  const float normalisation = static_cast<float>(1.0 / std::sqrt(static_cast<double>(pixels)));
  std::vector<std::vector<Complex>> kernel_spectrum(static_cast<std::size_t>(channels));
  std::vector<float> plane(pixels);
  for (int c = 0; c < channels; ++c) {
    for (std::size_t i = 0; i < pixels; ++i)
      plane[i] = (periodic.data[i * channels + c] - mean[c]) * normalisation;
    kernel_spectrum[c].resize(fft.spectrum_size());
    fft.forward(plane, kernel_spectrum[c]);
  }
  return kernel_spectrum;
}

TextonModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                    const std::function<void(double)>& progress) {
  // Preprocess: the periodic component (section 4.2, [Moi11]), then the normalised kernel
  // t_u = (p - mean(p)) / sqrt(|Omega|) of section 3.2.
  const ImageF periodic = periodic_component(exemplar);
  std::vector<float> mean;
  for (const double value : channel_means(periodic.view()))
    mean.push_back(static_cast<float>(value));
  const Fft2d fft(exemplar.width, exemplar.height);
  // The target of the colour correction: the exemplar's covariance about the float mean the
  // kernel is centred on.
  const std::vector<double> target = channel_covariance(periodic.view(), mean);
  std::vector<float> coefficients =
      texton_coefficients(fft, normalised_kernel_spectrum(fft, periodic.view(), mean), target,
                          params, seed, true, progress);
  const int support = texton_support(params.support, exemplar.width, exemplar.height);
  return TextonModel(exemplar.channels, support, params.order, params.mni, params.points,
                     std::move(coefficients), std::move(mean));
}

std::vector<float> texton_coefficients(
    const Fft2d& fft, std::vector<std::vector<std::complex<float>>> kernel_spectrum,
    std::span<const double> target, const Params& params, std::uint32_t seed, bool fade_border,
    const std::function<void(double)>& progress) {
  const int width = fft.width();
  const int height = fft.height();
  const int channels = static_cast<int>(kernel_spectrum.size());
  const int support = texton_support(params.support, width, height);
  const int order = params.order;
  const int iterations = params.iterations;
  const std::size_t pixels = fft.image_size();
  const int spectrum_width = fft.spectrum_width();
  const std::size_t spectrum_size = fft.spectrum_size();

  // Spectral constraint of eq. (4): |alpha-hat| = |t-hat_u| / sqrt(b-hat), in colour as the
  // cross-spectrum projection of section 4.3. Divide t-hat by sqrt(b-hat) once.
  const std::vector<double> b_x = sampled_bspline_spectrum(order, width, spectrum_width);
  const std::vector<double> b_y = sampled_bspline_spectrum(order, height, height);
  for (int r = 0; r < height; ++r)
    for (int q = 0; q < spectrum_width; ++q) {
      const auto scale = static_cast<float>(1.0 / std::sqrt(b_x[q] * b_y[r]));
      for (auto& spectrum : kernel_spectrum)
        spectrum[static_cast<std::size_t>(r) * spectrum_width + q] *= scale;
    }

  // Algorithm 1: random initialisation, then n alternating projections on the spectral constraint
  // and on the support S (the top-left S x S square: the DFT is circular, so its position is free).
  // After the first support projection alpha is zero outside the first S rows, so it is kept as
  // those rows only and transformed with row-pruned FFTs (same result, about half the work).
  const RowPrunedFft2d pruned(width, height, support);
  // A texton as wide as the exemplar: the projections leave it large at its square's border (on
  // rock_sandstone's 256^2 height, 0.65 of its centre), so each copy ends in a jump and the sum of
  // copies shows a grid of horizontal and vertical streaks. Where the support is the whole
  // exemplar, step 2 also imposes a raised-cosine fall to 0 over the support's outer eighth (the
  // ratios to ADSN's spectral error fall: grass_lawn_128 1.17 -> 1.09, wood_planks 0.89 -> 0.71;
  // a 128 of 512 support has room to decay and rose with it: moss 1.05 -> 1.14, so it is not
  // windowed). docs/methods/texton.md, "The plaid of smooth exemplars". The mixing's kernels
  // (fade_border false) keep the paper's projection: there the window moved the rho = 0.5
  // spectrum away from the amplitude mean of the ends (0.10 -> 0.19, texton_mix_quality_test).
  std::vector<float> window(static_cast<std::size_t>(support), 1.0f);
  if (fade_border && support == std::min(width, height)) {
    const double fall = std::max(1, support / 8);
    for (int i = 0; i < support; ++i) {
      const double inside = std::min(i, support - 1 - i) + 0.5;
      if (inside < fall)
        window[static_cast<std::size_t>(i)] =
            static_cast<float>(0.5 - 0.5 * std::cos(std::numbers::pi * inside / fall));
    }
  }
  std::vector<std::vector<float>> alpha(static_cast<std::size_t>(channels));
  std::vector<std::vector<Complex>> alpha_spectrum(static_cast<std::size_t>(channels),
                                                   std::vector<Complex>(spectrum_size));
  for (int c = 0; c < channels; ++c) {
    const std::vector<float> noise =
        gaussian_white_noise(pixels, cell_key(c, 0, seed, Stream::analysis));
    fft.forward(noise, alpha_spectrum[c]);
    alpha[c].assign(noise.begin(), noise.begin() + static_cast<std::ptrdiff_t>(pruned.rows_size()));
  }
  for (int iteration = 0; iteration < iterations; ++iteration) {
    // 1. Impose the spectrum |t-hat| / sqrt(b-hat) (alpha_spectrum holds the DFT of alpha).
    switch (channels) {
      case 1:
        project_spectrum<1>(kernel_spectrum, alpha_spectrum);
        break;
      case 2:
        project_spectrum<2>(kernel_spectrum, alpha_spectrum);
        break;
      case 3:
        project_spectrum<3>(kernel_spectrum, alpha_spectrum);
        break;
      case 4:
        project_spectrum<4>(kernel_spectrum, alpha_spectrum);
        break;
      default:
        project_spectrum<0>(kernel_spectrum, alpha_spectrum);
        break;
    }
    // 2. Impose the support: keep the top-left support x support square.
    for (int c = 0; c < channels; ++c) {
      pruned.inverse(alpha_spectrum[c], alpha[c]);
      for (int y = 0; y < support; ++y) {
        const auto row = alpha[c].begin() + static_cast<std::ptrdiff_t>(y) * width;
        std::fill(row + support, row + width, 0.0f);
        for (int x = 0; x < support; ++x)
          row[x] *= window[static_cast<std::size_t>(y)] * window[static_cast<std::size_t>(x)];
      }
      if (iteration + 1 < iterations) pruned.forward(alpha[c], alpha_spectrum[c]);
    }
    if (progress) progress(static_cast<double>(iteration + 1) / iterations);
  }

  std::vector<float> coefficients(static_cast<std::size_t>(support) * support * channels);
  for (int y = 0; y < support; ++y)
    for (int x = 0; x < support; ++x)
      for (int c = 0; c < channels; ++c)
        coefficients[(static_cast<std::size_t>(y) * support + x) * channels + c] =
            alpha[c][static_cast<std::size_t>(y) * width + x];

  // Colour covariance correction (section 4.3, [GLM14, DMR16]): the support projection loses
  // variance. The noise covariance at lag 0 is sum_{k,l} alpha(k) alpha(l)^T b(k - l), with b the
  // sampled B-spline of degree 2k+1 (nonzero for |m| <= k). The linear map A with
  // A Sigma_alpha A^T = Sigma_u closest to the identity (the optimal transport map between the two
  // Gaussians) corrects it without rotating colours.
  std::vector<double> b_taps(static_cast<std::size_t>(order + 1));
  for (int m = 0; m <= order; ++m) b_taps[m] = bspline(2 * order + 1, m);
  Eigen::MatrixXd noise_covariance = Eigen::MatrixXd::Zero(channels, channels);
  for (int dy = -order; dy <= order; ++dy)
    for (int dx = -order; dx <= order; ++dx) {
      const double weight = b_taps[static_cast<std::size_t>(std::abs(dx))] *
                            b_taps[static_cast<std::size_t>(std::abs(dy))];
      for (int y = std::max(0, -dy); y < std::min(support, support - dy); ++y)
        for (int x = std::max(0, -dx); x < std::min(support, support - dx); ++x) {
          const float* a = &coefficients[(static_cast<std::size_t>(y) * support + x) * channels];
          const float* b =
              &coefficients[(static_cast<std::size_t>(y + dy) * support + x + dx) * channels];
          for (int i = 0; i < channels; ++i)
            for (int j = 0; j < channels; ++j) noise_covariance(i, j) += weight * a[i] * b[j];
        }
    }
  noise_covariance = 0.5 * (noise_covariance + noise_covariance.transpose());
  const Eigen::MatrixXd target_covariance =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          target.data(), channels, channels);
  const Eigen::MatrixXd root = symmetric_power(noise_covariance, 0.5);
  const Eigen::MatrixXd inverse_root = symmetric_power(noise_covariance, -0.5);
  const Eigen::MatrixXd correction =
      inverse_root * symmetric_power(root * target_covariance * root, 0.5) * inverse_root;
  Eigen::VectorXd texel(channels);
  for (std::size_t t = 0; t < static_cast<std::size_t>(support) * support; ++t) {
    for (int c = 0; c < channels; ++c) texel[c] = coefficients[t * channels + c];
    const Eigen::VectorXd corrected = correction * texel;
    for (int c = 0; c < channels; ++c)
      coefficients[t * channels + c] = static_cast<float>(corrected[c]);
  }

  return coefficients;
}

}  // namespace stochtex::texton
