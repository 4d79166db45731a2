#include "methods/gabor/colour_space.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>

#include "methods/gabor/eigen_matrix.hpp"
#include "spectral/fft.hpp"
#include "spectral/principal_components.hpp"

namespace stochtex::gabor {
namespace {

using Complex = std::complex<float>;

}  // namespace

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
        // The Givens rotation G (G_pp = G_qq = c, G_pq = -s, G_qp = s) changes columns p and q of
        // `rotation` (rotation G) and rows then columns p and q of each matrix (G^T A G, the rows
        // as the columns of A^T): each new entry is the sum of the same two products a dense
        // product would add to zeros.
        const auto rotate_columns = [&](auto&& m) {
          for (int i = 0; i < n; ++i) {
            const double mp = m(i, p);
            const double mq = m(i, q);
            m(i, p) = c * mp + s * mq;
            m(i, q) = -s * mp + c * mq;
          }
        };
        rotate_columns(rotation);
        for (auto& a : matrices) {
          rotate_columns(a.transpose());
          rotate_columns(a);
        }
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

}  // namespace stochtex::gabor
