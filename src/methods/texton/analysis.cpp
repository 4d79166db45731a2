#include "methods/texton/analysis.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "core/hash.hpp"
#include "methods/texton/evaluate.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"
#include "spectral/white_noise.hpp"

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

Eigen::MatrixXd symmetric_power(const Eigen::MatrixXd& matrix, double power) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(matrix);
  // Eigenvalues of a covariance are >= 0; a floor keeps a channel with no variance finite.
  const double floor = 1e-12 * std::max(1e-30, solver.eigenvalues().cwiseAbs().maxCoeff());
  Eigen::VectorXd values = solver.eigenvalues().cwiseMax(floor).array().pow(power);
  return solver.eigenvectors() * values.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace

TextonModel analyze(ImageView<const float> exemplar, const ParamValues& params,
                    std::uint32_t seed) {
  const int width = exemplar.width;
  const int height = exemplar.height;
  const int channels = exemplar.channels;
  const int support = std::min({static_cast<int>(params.at("support")), width, height});
  const int order = static_cast<int>(params.at("order"));
  const int iterations = static_cast<int>(params.at("iterations"));
  const double mean_impacts = params.at("mni");

  // Preprocess: the periodic component (section 4.2, [Moi11]), then the normalised kernel
  // t_u = (p - mean(p)) / sqrt(|Omega|) of section 3.2.
  const ImageF periodic = periodic_component(exemplar);
  const std::size_t pixels = periodic.pixel_count();
  std::vector<float> mean(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    double sum = 0.0;
    for (std::size_t i = 0; i < pixels; ++i) sum += periodic.pixels()[i * channels + c];
    mean[c] = static_cast<float>(sum / static_cast<double>(pixels));
  }
  const Fft2d fft(width, height);
  const int spectrum_width = fft.spectrum_width();
  const std::size_t spectrum_size = fft.spectrum_size();
  const float normalisation = static_cast<float>(1.0 / std::sqrt(static_cast<double>(pixels)));
  std::vector<std::vector<Complex>> kernel_spectrum(static_cast<std::size_t>(channels));
  std::vector<float> plane(pixels);
  for (int c = 0; c < channels; ++c) {
    for (std::size_t i = 0; i < pixels; ++i)
      plane[i] = (periodic.pixels()[i * channels + c] - mean[c]) * normalisation;
    kernel_spectrum[c].resize(spectrum_size);
    fft.forward(plane, kernel_spectrum[c]);
  }

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
  std::vector<std::vector<float>> alpha(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c)
    alpha[c] = gaussian_white_noise(pixels, cell_key(c, 0, seed, Stream::analysis));
  std::vector<std::vector<Complex>> alpha_spectrum(static_cast<std::size_t>(channels),
                                                   std::vector<Complex>(spectrum_size));
  for (int iteration = 0; iteration < iterations; ++iteration) {
    for (int c = 0; c < channels; ++c) fft.forward(alpha[c], alpha_spectrum[c]);
    for (std::size_t i = 0; i < spectrum_size; ++i) {
      // alpha-hat <- (t-hat* alpha-hat / |t-hat* alpha-hat|) t-hat / sqrt(b-hat): the phase of the
      // projection of alpha-hat on the line spanned by t-hat (grey: the phase of alpha-hat).
      Complex inner = 0.0f;
      for (int c = 0; c < channels; ++c)
        inner += std::conj(kernel_spectrum[c][i]) * alpha_spectrum[c][i];
      const float magnitude = std::sqrt(std::norm(inner));  // std::abs is hypot: slow
      const Complex phase = magnitude > 0.0f ? inner / magnitude : Complex(1.0f);
      for (int c = 0; c < channels; ++c) alpha_spectrum[c][i] = phase * kernel_spectrum[c][i];
    }
    for (int c = 0; c < channels; ++c) {
      fft.inverse(alpha_spectrum[c], alpha[c]);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          if (x >= support || y >= support)
            alpha[c][static_cast<std::size_t>(y) * width + x] = 0.0f;
    }
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
  Eigen::MatrixXd target_covariance = Eigen::MatrixXd::Zero(channels, channels);
  for (std::size_t p = 0; p < pixels; ++p)
    for (int i = 0; i < channels; ++i)
      for (int j = 0; j < channels; ++j)
        target_covariance(i, j) +=
            (periodic.pixels()[p * channels + i] - mean[i]) *
            static_cast<double>(periodic.pixels()[p * channels + j] - mean[j]);
  target_covariance /= static_cast<double>(pixels);
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

  return TextonModel(channels, support, order, mean_impacts, std::move(coefficients),
                     std::move(mean));
}

}  // namespace stochtex::texton
