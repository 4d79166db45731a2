#pragma once
// Principal components of a colour covariance (core/colour_statistics.hpp), for the analyses: the
// PCA colour decorrelation of tiling and lrp (Heeger & Bergen 1995) and gabor's PCA colour space
// and whitening (section 7). Eigen does the work, so it lives in stochtex::analysis.

#include <span>
#include <vector>

namespace stochtex {

// The eigen-decomposition of a symmetric n x n matrix (row-major): the variances (eigenvalues) in
// increasing order and the unit axes (eigenvectors) as the columns of `axes`, row-major:
// axes[c * n + k] is channel c of axis k. Each axis has the sign Eigen's SelfAdjointEigenSolver
// gives it, fixed for a given matrix; models store these axes, so the convention is part of their
// bytes.
struct PrincipalComponents {
  std::vector<double> variances;
  std::vector<double> axes;
};
PrincipalComponents principal_components(std::span<const double> matrix, int n);

}  // namespace stochtex
