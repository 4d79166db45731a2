#pragma once
// Gabor noise by example, the colour space of the independent channel synthesis (section 7): the
// lagged correlation matrices of the channels, their approximate joint diagonaliser, the PCA axes
// and the off-diagonality criterion of eq. (10) that compares them.

#include <vector>

namespace stochtex::gabor {

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

}  // namespace stochtex::gabor
