#include "spectral/principal_components.hpp"

#include <Eigen/Dense>
#include <cstddef>

namespace stochtex {

PrincipalComponents principal_components(std::span<const double> matrix, int n) {
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = matrix[static_cast<std::size_t>(i) * n + j];
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(m);
  PrincipalComponents result;
  result.variances.assign(solver.eigenvalues().begin(), solver.eigenvalues().end());
  result.axes.resize(static_cast<std::size_t>(n) * n);
  for (int c = 0; c < n; ++c)
    for (int k = 0; k < n; ++k)
      result.axes[static_cast<std::size_t>(c) * n + k] = solver.eigenvectors()(c, k);
  return result;
}

}  // namespace stochtex
