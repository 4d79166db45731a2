// Determinism (docs/design.md §4): the output is a pure function of (model, position, footprint,
// seed), bit for bit, whatever the thread count, tile size or region split; and p = 1e7 is as
// precise as p = 0.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::render_test {
namespace {

const Model& test_model() {
  static const Model model = [] {
    std::mt19937 engine(8);
    std::normal_distribution<float> normal(0.5f, 0.1f);
    ImageF exemplar(48, 48, 3);
    for (float& value : exemplar.pixels()) value = normal(engine);
    return analyze("texton", exemplar.view(), {{"support", 16}, {"iterations", 10}}, 3);
  }();
  return model;
}

ImageF render_with(const Grid& grid, std::uint32_t seed, int threads, int tile,
                   int supersample = 1) {
  ImageF out(grid.width, grid.height, test_model().channels());
  RenderOptions options;
  options.threads = threads;
  options.tile_size = tile;
  options.supersample = supersample;
  render(test_model(), grid, seed, out.view(), options);
  return out;
}

using test_support::same_bytes;

TEST(Render, BitIdenticalWhateverTheThreadsAndTiles) {
  for (const double scale : {1.0, 6.0}) {
    const Grid grid{{-30.5, 12.25}, scale, 97, 83};
    const ImageF reference = render_with(grid, 7, 1, 64);
    EXPECT_TRUE(same_bytes(reference, render_with(grid, 7, 2, 64)));
    EXPECT_TRUE(same_bytes(reference, render_with(grid, 7, 3, 13)));
    EXPECT_TRUE(same_bytes(reference, render_with(grid, 7, 2, 1000)));
    EXPECT_TRUE(same_bytes(reference, render_with(grid, 7, 4, 1)));
  }
  const Grid supersampled{{3.0, 4.0}, 4.0, 40, 30};
  EXPECT_TRUE(
      same_bytes(render_with(supersampled, 7, 1, 64, 3), render_with(supersampled, 7, 2, 7, 3)));
}

TEST(Render, RegionsInPiecesEqualTheWhole) {
  const Grid whole{{5.0, -9.0}, 1.5, 90, 70};
  const ImageF reference = render_with(whole, 11, 2, 32);
  // Four unequal pieces rendered on their own, pasted together.
  ImageF pasted(whole.width, whole.height, test_model().channels());
  const int split_x = 37;
  const int split_y = 22;
  for (const auto& [x0, y0, w, h] :
       {std::array{0, 0, split_x, split_y}, std::array{split_x, 0, whole.width - split_x, split_y},
        std::array{0, split_y, split_x, whole.height - split_y},
        std::array{split_x, split_y, whole.width - split_x, whole.height - split_y}}) {
    Grid piece = whole;
    piece.width = w;
    piece.height = h;
    piece.first_pixel_x = x0;
    piece.first_pixel_y = y0;
    const ImageF part = render_with(piece, 11, 1, 16);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < part.channels(); ++c) pasted.at(x0 + x, y0 + y, c) = part.at(x, y, c);
  }
  EXPECT_TRUE(same_bytes(reference, pasted));
}

TEST(Render, EvaluateMatchesRenderPointByPoint) {
  const Grid grid{{1.0, 2.0}, 1.0, 8, 8};
  const ImageF rendered = render_with(grid, 3, 1, 64);
  std::vector<Vec2d> points;
  std::vector<Footprint> footprints;
  for (int j = 7; j >= 0; --j)  // any order: evaluation is pointwise
    for (int i = 0; i < 8; ++i) {
      points.push_back({1.0 + i + 0.5, 2.0 + j + 0.5});
      footprints.push_back({{1.0, 0.0}, {0.0, 1.0}});
    }
  ImageF values(64, 1, 3);
  evaluate(test_model(), points, footprints, 3, values.view());
  for (int k = 0; k < 64; ++k) {
    const int i = k % 8;
    const int j = 7 - k / 8;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(values.at(k, 0, c), rendered.at(i, j, c));
  }
}

TEST(Render, OnePointAtATimeEqualsOneBatch) {
  // Batches reuse the Poisson points of the cells they visit (texton CellCache); a point evaluated
  // alone draws them afresh. Both must give the same bits, footprints or not.
  std::vector<Vec2d> points;
  for (int k = 0; k < 200; ++k) points.push_back({k * 1.37 - 40.0, (k % 17) * 3.1 + 1e6});
  for (const double scale : {1.0, 5.0}) {
    const std::vector<Footprint> footprints(points.size(), Footprint{{scale, 0.0}, {0.0, scale}});
    ImageF batch(static_cast<int>(points.size()), 1, 3);
    evaluate(test_model(), points, footprints, 9, batch.view());
    for (std::size_t k = 0; k < points.size(); ++k) {
      ImageF single(1, 1, 3);
      evaluate(test_model(), std::span(points).subspan(k, 1), std::span(footprints).subspan(k, 1),
               9, single.view());
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(single.at(0, 0, c), batch.at(static_cast<int>(k), 0, c)) << k;
    }
  }
}

TEST(Render, SeedsGiveDifferentImages) {
  const Grid grid{{0.0, 0.0}, 1.0, 32, 32};
  const ImageF a = render_with(grid, 1, 2, 64);
  const ImageF b = render_with(grid, 2, 2, 64);
  std::size_t equal = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) equal += a.pixels()[i] == b.pixels()[i];
  EXPECT_LT(equal, a.pixels().size() / 100);
}

// Mean squared difference between horizontally adjacent pixels: the fine detail of a render.
double neighbour_energy(const ImageF& image) {
  double sum = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 1; x < image.width(); ++x)
      for (int c = 0; c < image.channels(); ++c) {
        const double d = image.at(x, y, c) - image.at(x - 1, y, c);
        sum += d * d;
      }
  return sum / (static_cast<double>(image.height()) * (image.width() - 1) * image.channels());
}

TEST(Render, FarFromTheOriginIsAsPreciseAsAtTheOrigin) {
  // Zoomed in (0.05 exemplar pixels per output pixel): positions computed in float near 1e7
  // (spacing 1) would repeat over 20-pixel runs and the fine detail would collapse.
  double near_energy = 0.0;
  double far_energy = 0.0;
  double near_variance = 0.0;
  double far_variance = 0.0;
  for (std::uint32_t seed = 0; seed < 8; ++seed) {
    const ImageF near = render_with({{0.0, 0.0}, 0.05, 96, 96}, seed, 2, 64);
    const ImageF far = render_with({{1e7, -1e7}, 0.05, 96, 96}, seed, 2, 64);
    near_energy += neighbour_energy(near);
    far_energy += neighbour_energy(far);
    const ImageF near_wide = render_with({{0.0, 0.0}, 1.0, 64, 64}, seed, 2, 64);
    const ImageF far_wide = render_with({{1e7, -1e7}, 1.0, 64, 64}, seed, 2, 64);
    for (const auto& [image, variance] :
         {std::pair{&near_wide, &near_variance}, std::pair{&far_wide, &far_variance}}) {
      double sum = 0.0;
      double square = 0.0;
      for (const float value : image->pixels()) {
        sum += value;
        square += static_cast<double>(value) * value;
      }
      const double n = static_cast<double>(image->pixels().size());
      *variance += square / n - (sum / n) * (sum / n);
    }
  }
  // Both are averages over 8 independent renders of the same stationary field; their ratio
  // fluctuates by ~10-20% (measured), a precision collapse divides it by ~20.
  EXPECT_GT(far_energy / near_energy, 0.6);
  EXPECT_LT(far_energy / near_energy, 1.0 / 0.6);
  EXPECT_GT(far_variance / near_variance, 0.6);
  EXPECT_LT(far_variance / near_variance, 1.0 / 0.6);
}

}  // namespace
}  // namespace stochtex::render_test
