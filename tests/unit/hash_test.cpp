// The randomness spec of docs/design.md §5. The vectors below were computed with an independent
// Python transcription of Jarzynski & Olano's reference GLSL (JCGT 2020, "pcg" and "pcg4d"); they
// pin the C++ (and later GLSL) code: a change here re-seeds every stored texture.

#include "core/hash.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/cell_count.hpp"

namespace stochtex::hash_test {
namespace {

// Upper critical value of the chi-square distribution with `dof` degrees of freedom at tail
// probability 1e-4 (Wilson-Hilferty approximation, accurate to ~1% for dof >= 3).
double chi_square_critical(int dof) {
  const double z = 3.719;  // standard normal quantile at 1 - 1e-4
  const double k = dof;
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

TEST(Hash, PcgMatchesReferenceVectors) {
  EXPECT_EQ(pcg_hash(0u), 0x07bb2fe2u);
  EXPECT_EQ(pcg_hash(1u), 0xa8beea3cu);
  EXPECT_EQ(pcg_hash(2u), 0x7a7ecc88u);
  EXPECT_EQ(pcg_hash(0xdeadbeefu), 0x67299972u);
  EXPECT_EQ(pcg_hash(0xffffffffu), 0xe62a4902u);
}

TEST(Hash, Pcg4dMatchesReferenceVectors) {
  EXPECT_EQ(pcg4d({0, 0, 0, 0}), (Uint4{0x0f02f829u, 0x2d568769u, 0x32b0c43bu, 0xd32548eau}));
  EXPECT_EQ(pcg4d({1, 2, 3, 4}), (Uint4{0x3622cd16u, 0xf11471d8u, 0xe1109b3fu, 0x02b94c2fu}));
  EXPECT_EQ(pcg4d({0xffffffffu, 0, 0x12345678u, 0x9e3779b9u}),
            (Uint4{0xd15ed682u, 0xe5e154ceu, 0xf2f48dd6u, 0x42bc40ecu}));
}

TEST(Hash, CellKeyAndCounterStreamMatchReferenceVectors) {
  // Negative cells enter as their two's complement low 32 bits.
  const std::uint32_t key = cell_key(-1, 5, 42, Stream::points);
  EXPECT_EQ(key, 0x4f0bff40u);
  CounterRng rng(key);
  const std::uint32_t first = rng.next();
  const std::uint32_t second = rng.next();
  const std::uint32_t third = rng.next();
  EXPECT_EQ(first, 0x38ad97b9u);
  EXPECT_EQ(second, 0x535e0413u);
  EXPECT_EQ(third, 0x8906aa8bu);
}

TEST(Hash, CellKey3dMatchesReferenceVectorsAndLeaves2dKeysAlone) {
  // The 3-D key (surface noise) hashes the 2-D key again with z: 2-D keys are unchanged, and the
  // plane z = 0 does not repeat them.
  const std::uint32_t key = cell_key(-1, 5, -3, 42, Stream::points);
  EXPECT_EQ(key, 0xda30818cu);
  CounterRng rng(key);
  const std::uint32_t first = rng.next();
  const std::uint32_t second = rng.next();
  EXPECT_EQ(first, 0xf3103d40u);
  EXPECT_EQ(second, 0x5c51f367u);
  EXPECT_EQ(cell_key(-1, 5, 0, 42, Stream::points), 0x070fbd7fu);
  EXPECT_NE(cell_key(-1, 5, 0, 42, Stream::points), cell_key(-1, 5, 42, Stream::points));
  EXPECT_NE(cell_key(0, 0, 0, 1, Stream::points), cell_key(0, 0, 1, 1, Stream::points));
  EXPECT_NE(cell_key(0, 0, 0, 1, Stream::points), cell_key(0, 0, 0, 2, Stream::points));
}

TEST(Hash, CellKeysDifferAcrossCellsSeedsStreamsAndFar) {
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(0, 0, 2, Stream::points));
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(0, 0, 1, Stream::phases));
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(1, 0, 1, Stream::points));
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(0, 1, 1, Stream::points));
  // No small hidden period (a classic bug: cell index modulo 1024).
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(1024, 0, 1, Stream::points));
  EXPECT_NE(cell_key(0, 0, 1, Stream::points), cell_key(65536, 0, 1, Stream::points));
}

TEST(Hash, UniformIsUniform) {
  // Chi-square over 64 bins of one uniform from each of 2^18 cells: a fixed draw, so the
  // statistic is reproducible; it exceeds the 1e-4 critical value only if the hash is biased.
  constexpr int kBins = 64;
  constexpr int kDraws = 1 << 18;
  std::vector<int> histogram(kBins, 0);
  for (int i = 0; i < kDraws; ++i) {
    CounterRng rng(cell_key(i % 512, i / 512, 7, Stream::points));
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++histogram[static_cast<std::size_t>(u * kBins)];
  }
  const double expected = static_cast<double>(kDraws) / kBins;
  double chi_square = 0.0;
  for (const int count : histogram)
    chi_square += (count - expected) * (count - expected) / expected;
  EXPECT_LT(chi_square, chi_square_critical(kBins - 1));
}

class PoissonTest : public ::testing::TestWithParam<double> {};

TEST_P(PoissonTest, CountsFollowThePoissonLaw) {
  const double mean = GetParam();
  const CellCount sampler = CellCount::poisson(mean);
  EXPECT_NEAR(sampler.mean(), mean, 1e-5 * mean);
  constexpr int kDraws = 200000;
  const int max_count = static_cast<int>(mean + 20.0 * std::sqrt(mean) + 30.0);
  std::vector<double> observed(static_cast<std::size_t>(max_count) + 1, 0.0);
  double sum = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    CounterRng rng(cell_key(i, -i, 3, Stream::points));
    const std::uint32_t k = sampler(rng);
    sum += k;
    observed[std::min<std::size_t>(k, static_cast<std::size_t>(max_count))] += 1.0;
  }
  // Exact probabilities in double; bins pooled from both ends until each expects >= 20 draws.
  std::vector<double> probability(observed.size());
  double p = std::exp(-mean);
  for (int k = 0; k <= max_count; ++k) {
    probability[static_cast<std::size_t>(k)] = p;
    p *= mean / (k + 1);
  }
  double chi_square = 0.0;
  int bins = 0;
  double pooled_expected = 0.0;
  double pooled_observed = 0.0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    pooled_expected += probability[k] * kDraws;
    pooled_observed += observed[k];
    if (pooled_expected >= 20.0) {
      chi_square += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) /
                    pooled_expected;
      ++bins;
      pooled_expected = 0.0;
      pooled_observed = 0.0;
    }
  }
  ASSERT_GE(bins, 2);
  EXPECT_LT(chi_square, chi_square_critical(std::max(bins - 1, 3))) << "mean " << mean;
  // The sample mean is within 5 standard errors of the Poisson mean.
  EXPECT_NEAR(sum / kDraws, mean, 5.0 * std::sqrt(mean / kDraws));
}

// Small means (one chunk), the chunk limit, and large means split into several exact chunks.
INSTANTIATE_TEST_SUITE_P(Means, PoissonTest, ::testing::Values(0.3, 2.5, 10.8, 16.0, 30.0, 250.0));

class BalancedCountTest : public ::testing::TestWithParam<double> {};

// Each chunk of mean m_c holds floor(m_c) or floor(m_c) + 1 points, the latter with probability
// frac(m_c): counts lie within [c floor(m_c), c (floor(m_c) + 1)] for c chunks, and the frequency
// of each value is binomial around its probability (checked to 5 standard errors).
TEST_P(BalancedCountTest, CountsAreTheLeastVariableOfTheirMean) {
  const double mean = GetParam();
  const CellCount sampler = CellCount::balanced(mean);
  EXPECT_NEAR(sampler.mean(), mean, 1e-5 * mean);
  const double chunk_mean = mean / sampler.chunks();
  const double whole = std::floor(chunk_mean);
  const double fraction = chunk_mean - whole;
  constexpr int kDraws = 200000;
  double sum = 0.0;
  double sum_squares = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    CounterRng rng(cell_key(i, -i, 3, Stream::points));
    const double k = sampler(rng);
    ASSERT_GE(k, whole * sampler.chunks());
    ASSERT_LE(k, (whole + 1.0) * sampler.chunks());
    sum += k;
    sum_squares += k * k;
  }
  const double variance_expected = sampler.chunks() * fraction * (1.0 - fraction);
  EXPECT_NEAR(sum / kDraws, mean, 5.0 * std::sqrt(variance_expected / kDraws) + 1e-9);
  const double variance = sum_squares / kDraws - (sum / kDraws) * (sum / kDraws);
  // A sample variance of n draws of a bounded variable: its standard error is at most
  // sqrt(chunks / (16 n)) (the fourth central moment of a Bernoulli is at most 1/16).
  EXPECT_NEAR(variance, variance_expected, 5.0 * std::sqrt(sampler.chunks() / (16.0 * kDraws)));
  EXPECT_LE(variance_expected, 0.25 * sampler.chunks());
}

// Whole and fractional means, the chunk limit, and several chunks.
INSTANTIATE_TEST_SUITE_P(Means, BalancedCountTest,
                         ::testing::Values(0.3, 2.5, 10.8, 11.0, 16.0, 30.0, 250.0));

// whole_mean gives the least mean >= m (and >= 1) whose chunks all hold a whole number of points:
// every draw of balanced(whole_mean(m)) is that count.
TEST(WholeMeanTest, CountsOfAWholeMeanNeverVary) {
  for (const double mean : {0.3, 1.0, 10.8, 16.0, 16.5, 17.0, 30.0, 250.0, 1000.0}) {
    const double whole = CellCount::whole_mean(mean);
    const CellCount sampler = CellCount::balanced(whole);
    EXPECT_GE(whole, std::max(1.0, mean));
    EXPECT_LT(whole, std::max(1.0, mean) + sampler.chunks()) << mean;
    EXPECT_EQ(whole, std::floor(whole));
    for (int i = 0; i < 1000; ++i) {
      CounterRng rng(cell_key(i, 2 * i, 5, Stream::points));
      ASSERT_EQ(sampler(rng), whole) << "mean " << mean << ", draw " << i;
    }
  }
  EXPECT_EQ(CellCount::whole_mean(10.8), 11.0);
  EXPECT_EQ(CellCount::whole_mean(17.0), 18.0);  // two chunks of 9: 17 would split into 8.5s
}

}  // namespace
}  // namespace stochtex::hash_test
