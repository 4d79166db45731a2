#pragma once
// The n x n row-major matrices of the colour space (colour_space.hpp) to and from Eigen, for the
// files that do linear algebra on them; kept out of colour_space.hpp so that its includers do not
// compile Eigen.

#include <Eigen/Dense>
#include <cstddef>

#include "methods/gabor/colour_space.hpp"

namespace stochtex::gabor {

inline Eigen::MatrixXd to_eigen(const Matrix& m, int n) {
  Eigen::MatrixXd result(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) result(i, j) = m[static_cast<std::size_t>(i) * n + j];
  return result;
}

inline Matrix from_eigen(const Eigen::MatrixXd& m) {
  const auto n = static_cast<int>(m.rows());
  Matrix result(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) result[static_cast<std::size_t>(i) * n + j] = m(i, j);
  return result;
}

}  // namespace stochtex::gabor
