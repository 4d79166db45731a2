#pragma once
// The Kaiser-Bessel window of LRP noise (section 3.6 of the paper) and the modified Bessel function
// it is built from. Runtime code: no dependency beyond the standard library.
//
// The paper writes w(y) = b_3(3 pi sqrt(1 - (y / 1.5)^2)) / b_3(3 pi) with
// b_3(z) = sum_m (z / 2)^(2m+3) / (m! (m+2)!), "approximated by 5 terms". Two corrections, both
// measured (tests/unit/lrp_test.cpp):
//  - the series with (m+2)! is (z / 2) I_2(z), whose window gives int_0^inf r w^2(r) dr = 0.1049;
//    the paper's own constant, 0.1126 (section 4.3), is that of the modified Bessel function of
//    order 3, I_3(z) = sum_m (z / 2)^(2m+3) / (m! (m+3)!), to four digits. We use I_3.
//  - 5 terms of the series are wrong in the window's centre, where the argument reaches 3 pi
//    (5 terms of I_3(3 pi) are 19% low); bessel_i() below is accurate to a few ulps for every
//    argument (series below 30, asymptotic expansion above).

#include <array>
#include <cmath>
#include <numbers>

namespace stochtex::lrp {

// The window vanishes outside [-1.5, 1.5] (section 3.4): with lattice nodes on the integers, a
// sample sees the 3 x 3 nodes around its nearest node only (I = 9 in equation 1).
inline constexpr double kWindowRadius = 1.5;
inline constexpr auto kWindowRadiusSquared = static_cast<float>(kWindowRadius * kWindowRadius);
// The Kaiser-Bessel shape parameter: the argument at the window's centre is pi * alpha = 3 pi.
inline constexpr double kKaiserArgument = 3.0 * std::numbers::pi;
inline constexpr int kWindowOrder = 3;

// Modified Bessel function of the first kind I_order(x), order >= 0 an integer, x >= 0.
// For x <= 30 the power series sum_m (x/2)^(2m+order) / (m! (m+order)!) is summed until its
// (positive, so cancellation-free) terms fall below 1e-17 of the sum; above, the asymptotic
// expansion e^x / sqrt(2 pi x) sum_k (-1)^k prod_{j<=k} (4 order^2 - (2j-1)^2) / (k! (8x)^k) is
// summed while its terms decrease (at x = 30 the smallest term is ~1e-25). Overflows to +inf
// beyond x ~ 713, as the function itself does.
inline double bessel_i(int order, double x) {
  if (x <= 30.0) {
    double term = 1.0;
    for (int k = 1; k <= order; ++k) term *= 0.5 * x / k;
    const double quarter_square = 0.25 * x * x;
    double sum = term;
    for (int m = 1; m < 500; ++m) {
      term *= quarter_square / (static_cast<double>(m) * (m + order));
      sum += term;
      if (term < 1e-17 * sum) break;
    }
    return sum;
  }
  const double mu = 4.0 * order * order;
  double term = 1.0;
  double sum = 1.0;
  for (int k = 1; k < 60; ++k) {
    const double next = -term * (mu - (2.0 * k - 1.0) * (2.0 * k - 1.0)) / (k * 8.0 * x);
    if (std::abs(next) >= std::abs(term) || next == 0.0) break;
    term = next;
    sum += term;
  }
  return std::exp(x) / std::sqrt(2.0 * std::numbers::pi * x) * sum;
}

// w(y) = I_3(3 pi sqrt(1 - (y / 1.5)^2)) / I_3(3 pi) for |y| < 1.5, 0 elsewhere; w(0) = 1 and w
// goes to 0 continuously at |y| = 1.5 (like t^(3/2), I_3(z) ~ z^3 near 0).
inline double kaiser_bessel_window(double y) {
  const double s = y / kWindowRadius;
  if (!(std::abs(s) < 1.0)) return 0.0;
  return bessel_i(kWindowOrder, kKaiserArgument * std::sqrt(1.0 - s * s)) /
         bessel_i(kWindowOrder, kKaiserArgument);
}

// The same window as a polynomial in t = 1 - (y / 1.5)^2 for the evaluator (no special function,
// mirrorable in GLSL): w = t sqrt(t) sum_m c_m t^m, the series of I_3 with
// c_m = (3 pi / 2)^(2m+3) / (m! (m+3)! I_3(3 pi)). The terms are positive, so Horner's scheme in
// float has no cancellation; 20 terms leave a truncation below 1e-12. The evaluator reads it with
// window_from_square (evaluate.hpp).
inline constexpr int kWindowTerms = 20;
inline std::array<float, kWindowTerms> window_coefficients() {
  std::array<float, kWindowTerms> coefficients{};
  const double half = 0.5 * kKaiserArgument;
  const double normalisation = bessel_i(kWindowOrder, kKaiserArgument);
  double term = half * half * half / 6.0;  // (z/2)^3 / (0! 3!) at z = 3 pi
  for (int m = 0; m < kWindowTerms; ++m) {
    coefficients[static_cast<std::size_t>(m)] = static_cast<float>(term / normalisation);
    term *= half * half / ((m + 1.0) * (m + 4.0));
  }
  return coefficients;
}

// int_0^inf r w^2(r) dr, the constant of equation (3) (the paper: ~0.1126), by composite Simpson
// on 2048 intervals of [0, 1.5] (w^2 r is smooth there and vanishes at 1.5; error < 1e-9).
inline double window_radial_energy() {
  constexpr int intervals = 2048;
  const double h = kWindowRadius / intervals;
  double sum = 0.0;
  for (int i = 0; i <= intervals; ++i) {
    const double r = i * h;
    const double w = kaiser_bessel_window(r);
    const double weight = (i == 0 || i == intervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * r * w * w;
  }
  return sum * h / 3.0;
}

}  // namespace stochtex::lrp
