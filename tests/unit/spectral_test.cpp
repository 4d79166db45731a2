// FFT wrapper, periodic + smooth decomposition, ADSN (the Gaussian version of an exemplar), and the
// analyses' generic algorithms: masks on the torus and k-means.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "core/hash.hpp"
#include "spectral/adsn.hpp"
#include "spectral/fft.hpp"
#include "spectral/kmeans.hpp"
#include "spectral/periodic.hpp"
#include "spectral/torus_masks.hpp"

namespace stochtex::spectral_test {
namespace {

ImageF random_image(int width, int height, int channels, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF image(width, height, channels);
  for (float& value : image.pixels()) value = uniform(engine);
  return image;
}

TEST(Fft, RoundTripIsIdentity) {
  for (const auto& [width, height] : {std::pair{16, 16}, std::pair{17, 10}, std::pair{1, 7}}) {
    const ImageF image = random_image(width, height, 1, 3);
    const Fft2d fft(width, height);
    std::vector<std::complex<float>> spectrum(fft.spectrum_size());
    std::vector<float> back(fft.image_size());
    fft.forward(image.pixels(), spectrum);
    fft.inverse(spectrum, back);
    for (std::size_t i = 0; i < back.size(); ++i) EXPECT_NEAR(back[i], image.pixels()[i], 1e-6f);
  }
}

TEST(Fft, ForwardIsTheUnnormalisedDft) {
  // A cosine of frequency (3, 2) on a 16 x 8 grid has its energy at exactly bin (3, 2).
  const int width = 16;
  const int height = 8;
  std::vector<float> image(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image[static_cast<std::size_t>(y) * width + x] = static_cast<float>(
          std::cos(2.0 * std::numbers::pi * (3.0 * x / width + 2.0 * y / height)));
  const Fft2d fft(width, height);
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  fft.forward(image, spectrum);
  for (int r = 0; r < height; ++r)
    for (int q = 0; q < fft.spectrum_width(); ++q) {
      const float expected = (q == 3 && r == 2) ? 0.5f * width * height : 0.0f;
      EXPECT_NEAR(std::abs(spectrum[static_cast<std::size_t>(r) * fft.spectrum_width() + q]),
                  expected, 1e-3f);
    }
}

TEST(Fft, RowPrunedTransformsMatchTheFullTransforms) {
  const int width = 20;
  const int height = 12;
  const int rows = 5;
  ImageF image = random_image(width, height, 1, 4);
  for (int y = rows; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y, 0) = 0.0f;
  const Fft2d full(width, height);
  const RowPrunedFft2d pruned(width, height, rows);
  std::vector<std::complex<float>> expected(full.spectrum_size());
  std::vector<std::complex<float>> actual(pruned.spectrum_size());
  full.forward(image.pixels(), expected);
  pruned.forward(image.pixels().first(pruned.rows_size()), actual);
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(std::abs(actual[i] - expected[i]), 0.0f, 1e-4f) << i;
  // Inverse of an arbitrary spectrum: the first rows agree with the full inverse.
  const ImageF other = random_image(width, height, 1, 5);
  full.forward(other.pixels(), expected);
  std::vector<float> all(full.image_size());
  std::vector<float> first(pruned.rows_size());
  full.inverse(expected, all);
  pruned.inverse(expected, first);
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_NEAR(first[i], all[i], 1e-5f) << i;
}

TEST(Periodic, SmoothPartSolvesMoisansPoissonEquation) {
  // u = p + s where s is the zero-mean solution of Laplacian_periodic(s) = v, v the boundary
  // image of u (Moisan 2011, eq. 13). Check that equation pixel by pixel on s = u - p.
  const int width = 24;
  const int height = 19;
  ImageF image = random_image(width, height, 2, 5);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y, 1) += 0.1f * static_cast<float>(x + 2 * y);
  const ImageF periodic = periodic_component(image.view());
  for (int c = 0; c < 2; ++c) {
    auto s = [&](int x, int y) {
      x = (x + width) % width;
      y = (y + height) % height;
      return static_cast<double>(image.at(x, y, c)) - periodic.at(x, y, c);
    };
    double mean_u = 0.0;
    double mean_p = 0.0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        double boundary = 0.0;
        if (x == 0) boundary += image.at(width - 1, y, c) - image.at(0, y, c);
        if (x == width - 1) boundary -= image.at(width - 1, y, c) - image.at(0, y, c);
        if (y == 0) boundary += image.at(x, height - 1, c) - image.at(x, 0, c);
        if (y == height - 1) boundary -= image.at(x, height - 1, c) - image.at(x, 0, c);
        const double laplacian =
            s(x - 1, y) + s(x + 1, y) + s(x, y - 1) + s(x, y + 1) - 4.0 * s(x, y);
        EXPECT_NEAR(laplacian, boundary, 2e-4) << "pixel " << x << ", " << y;
        mean_u += image.at(x, y, c);
        mean_p += periodic.at(x, y, c);
      }
    EXPECT_NEAR(mean_u, mean_p, 1e-3);
  }
}

TEST(Periodic, ImageWithoutBorderJumpsIsItsOwnPeriodicComponent) {
  // When the last column equals the first and the last row the first, the boundary image v is 0,
  // so s = 0 and p = u exactly.
  ImageF image = random_image(20, 15, 1, 6);
  for (int y = 0; y < 15; ++y) image.at(19, y, 0) = image.at(0, y, 0);
  for (int x = 0; x < 20; ++x) image.at(x, 14, 0) = image.at(x, 0, 0);
  const ImageF periodic = periodic_component(image.view());
  for (std::size_t i = 0; i < image.pixels().size(); ++i)
    EXPECT_NEAR(periodic.pixels()[i], image.pixels()[i], 1e-5f);
}

TEST(Adsn, HasTheExemplarsMeanAndCovarianceAtAnySize) {
  // A colour exemplar with correlated channels: channel 1 = channel 0 + small noise, channel 2
  // independent. ADSN keeps mean and the full colour covariance (one noise for all channels).
  const int size = 64;
  const ImageF base = random_image(size, size, 3, 11);
  ImageF exemplar(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      exemplar.at(x, y, 0) = base.at(x, y, 0);
      exemplar.at(x, y, 1) = 0.8f * base.at(x, y, 0) + 0.2f * base.at(x, y, 1);
      exemplar.at(x, y, 2) = 0.3f + 0.5f * base.at(x, y, 2);
    }
  const ImageF periodic = periodic_component(exemplar.view());
  const ImageF sample = adsn(exemplar.view(), 300, 220, 9);
  ASSERT_EQ(sample.width(), 300);
  ASSERT_EQ(sample.height(), 220);
  auto stats = [](const ImageF& image, std::vector<double>& mean, std::vector<double>& cov) {
    const std::size_t n = image.pixel_count();
    mean.assign(3, 0.0);
    cov.assign(9, 0.0);
    for (std::size_t p = 0; p < n; ++p)
      for (int c = 0; c < 3; ++c) mean[c] += image.pixels()[p * 3 + c] / static_cast<double>(n);
    for (std::size_t p = 0; p < n; ++p)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          cov[i * 3 + j] += (image.pixels()[p * 3 + i] - mean[i]) *
                            (image.pixels()[p * 3 + j] - mean[j]) / static_cast<double>(n);
  };
  std::vector<double> mean_e, cov_e, mean_s, cov_s;
  stats(periodic, mean_e, cov_e);
  stats(sample, mean_s, cov_s);
  // The exemplar is white noise, so the ADSN is close to white and each estimate averages
  // ~66000 nearly independent pixels: relative standard error ~ sqrt(2 / 66000) ~ 0.6%. The
  // bounds are 5 standard errors.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(mean_s[c], mean_e[c], 5.0 * std::sqrt(cov_e[c * 4] / 66000.0));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(
          cov_s[i * 3 + j], cov_e[i * 3 + j],
          5.0 * std::sqrt((cov_e[i * 4] * cov_e[j * 4] + cov_e[i * 3 + j] * cov_e[i * 3 + j]) /
                          66000.0))
          << "covariance " << i << j;
}

TEST(Adsn, IsDeterministicAndSeeded) {
  const ImageF exemplar = random_image(32, 32, 1, 2);
  const ImageF a = adsn(exemplar.view(), 40, 40, 1);
  const ImageF b = adsn(exemplar.view(), 40, 40, 1);
  const ImageF c = adsn(exemplar.view(), 40, 40, 2);
  EXPECT_TRUE(std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()));
  EXPECT_FALSE(std::equal(a.pixels().begin(), a.pixels().end(), c.pixels().begin()));
}

TEST(TorusMasks, DistanceWrapsAroundTheBorder) {
  // Every cell of an 8 x 8 torus is inside but (0, 0): the distance reaches it across the border.
  const int size = 8;
  std::vector<char> inside(static_cast<std::size_t>(size) * size, 1);
  inside[0] = 0;
  const std::vector<double> distance = periodic_distance_squared(inside, size);
  const auto at = [&](int x, int y) { return distance[static_cast<std::size_t>(y) * size + x]; };
  EXPECT_EQ(at(0, 0), 0.0);
  EXPECT_EQ(at(1, 0), 1.0);
  EXPECT_EQ(at(7, 0), 1.0);
  EXPECT_EQ(at(7, 7), 2.0);
  EXPECT_EQ(at(4, 4), 32.0);
  EXPECT_EQ(at(6, 3), 13.0);
}

TEST(TorusMasks, PartsConnectDiagonallyAcrossTheBorder) {
  // (0, 0) and (5, 5) touch diagonally across the corner of a 6 x 6 torus; (3, 2) is alone.
  const int size = 6;
  std::vector<char> inside(static_cast<std::size_t>(size) * size, 0);
  const auto index = [&](int x, int y) { return static_cast<std::size_t>(y) * size + x; };
  inside[index(0, 0)] = inside[index(5, 5)] = inside[index(3, 2)] = 1;
  const std::vector<int> part = connected_parts(inside, size);
  EXPECT_EQ(part[index(0, 0)], 0);
  EXPECT_EQ(part[index(5, 5)], 0);
  EXPECT_EQ(part[index(3, 2)], 1);
  EXPECT_EQ(std::count(part.begin(), part.end(), -1), size * size - 3);
}

TEST(Kmeans, SeparatesDistantClusters) {
  const std::vector<std::array<int, 2>> near{{0, 0}, {0, 1}, {1, 0}};
  const std::vector<std::array<int, 2>> far{{100, 100}, {100, 101}, {101, 100}};
  std::vector<std::array<int, 2>> points = near;
  points.insert(points.end(), far.begin(), far.end());
  for (std::uint32_t key = 0; key < 8; ++key) {
    CounterRng rng(key);
    std::vector<std::vector<std::array<int, 2>>> groups = kmeans(points, 2, 50, rng);
    ASSERT_EQ(groups.size(), 2u);
    for (auto& group : groups) std::sort(group.begin(), group.end());
    std::sort(groups.begin(), groups.end());
    EXPECT_EQ(groups[0], near) << "key " << key;
    EXPECT_EQ(groups[1], far) << "key " << key;
  }
}

TEST(Kmeans, GivesEveryGroupAPointWhenThereAreFewer) {
  const std::vector<std::array<int, 2>> points{{1, 2}, {3, 4}};
  CounterRng rng(1);
  const std::vector<std::vector<std::array<int, 2>>> groups = kmeans(points, 3, 50, rng);
  ASSERT_EQ(groups.size(), 3u);
  const std::vector<std::array<int, 2>> first{points[0]};
  const std::vector<std::array<int, 2>> second{points[1]};
  EXPECT_EQ(groups[0], first);
  EXPECT_EQ(groups[1], second);
  EXPECT_EQ(groups[2], first);
}

}  // namespace
}  // namespace stochtex::spectral_test
