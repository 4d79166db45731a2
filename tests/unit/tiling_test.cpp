// Histogram-preserving tiling and blending (src/methods/tiling): the triangle lattice, the
// look-up tables and their erf parameterisation, the transports (against an exact assignment
// solver), the model record (round trip, rejection of corrupt records), channel layouts, the
// prefiltered inverse, triplanar blending and determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "methods/tiling/analysis.hpp"
#include "methods/tiling/evaluate.hpp"
#include "methods/tiling/model.hpp"
#include "methods/tiling/params.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "model/model_file.hpp"
#include "spectral/periodic.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"
#include "test_support.hpp"

namespace stochtex::tiling::tiling_test {
namespace {

using test_support::same_bytes;

constexpr double kSqrt3 = 1.7320508075688772;

Vec2d vertex_position(std::int64_t i, std::int64_t j, double edge) {
  return {edge * (static_cast<double>(i) + 0.5 * static_cast<double>(j)),
          edge * 0.5 * kSqrt3 * static_cast<double>(j)};
}

// An exemplar with a skewed, bimodal histogram and spatial structure: what linear blending breaks.
ImageF structured_exemplar(int side, int channels, std::uint32_t seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF image(side, side, channels);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const float blob =
          std::sin(0.7f * static_cast<float>(x)) * std::cos(0.5f * static_cast<float>(y));
      for (int c = 0; c < channels; ++c) {
        const float u = uniform(engine);
        image.at(x, y, c) = blob > 0.3f ? 0.8f - 0.1f * u * u + 0.05f * static_cast<float>(c)
                                        : 0.2f * u * u * u + 0.1f * static_cast<float>(c);
      }
    }
  return image;
}

const TilingModel& tiling_of(const Model& model) {
  return std::get<TilingModel>(model.data().model);
}

TEST(TilingLattice, WeightsArePositiveSumToOneAndAreOneOnTheirVertex) {
  std::mt19937 engine(1);
  std::uniform_real_distribution<double> position(-500.0, 500.0);
  constexpr double kEdge = 37.0;
  for (int trial = 0; trial < 10000; ++trial) {
    const Vec2d p{position(engine), position(engine)};
    const LatticePoint lattice = triangle_lattice(p, kEdge);
    float sum = 0.0f;
    for (int v = 0; v < 3; ++v) {
      EXPECT_GE(lattice.weight[v], -1e-6f);
      sum += lattice.weight[v];
      // Inside the vertex's hexagonal tile: never further than one edge.
      const Vec2d vertex = vertex_position(lattice.vertex_x[v], lattice.vertex_y[v], kEdge);
      EXPECT_LE(std::hypot(p.x - vertex.x, p.y - vertex.y), kEdge * (1.0 + 1e-5));
    }
    EXPECT_NEAR(sum, 1.0f, 1e-5f);
  }
  for (std::int64_t i = -3; i <= 3; ++i)
    for (std::int64_t j = -3; j <= 3; ++j) {
      // Slightly off the vertex, so the floor of the skewed coordinates is unambiguous.
      Vec2d p = vertex_position(i, j, kEdge);
      p.x += 1e-7;
      p.y += 1e-7;
      const LatticePoint lattice = triangle_lattice(p, kEdge);
      float weight = 0.0f;
      for (int v = 0; v < 3; ++v)
        if (lattice.vertex_x[v] == i && lattice.vertex_y[v] == j) weight = lattice.weight[v];
      EXPECT_NEAR(weight, 1.0f, 1e-5f) << i << ", " << j;
    }
}

TEST(TilingLattice, WeightsAreContinuousSoTheyVanishOnTileBorders) {
  // A vertex leaves the set of three only when its weight has reached zero on its hexagon's border:
  // the weight of every vertex is a continuous (1/edge-Lipschitz, barycentric) function of p.
  // Broken variant checked: swapping the two weights of the upper triangle (an error made while
  // writing the evaluator) fails this with jumps of ~1.
  std::mt19937 engine(2);
  std::uniform_real_distribution<double> position(-300.0, 300.0);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  constexpr double kEdge = 20.0;
  constexpr double kStep = 1e-3;
  const auto weights = [](const LatticePoint& lattice) {
    std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, float>> out;
    for (int v = 0; v < 3; ++v)
      out.push_back({{lattice.vertex_x[v], lattice.vertex_y[v]}, lattice.weight[v]});
    return out;
  };
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec2d p{position(engine), position(engine)};
    const double a = angle(engine);
    const Vec2d q{p.x + kStep * std::cos(a), p.y + kStep * std::sin(a)};
    const auto wp = weights(triangle_lattice(p, kEdge));
    const auto wq = weights(triangle_lattice(q, kEdge));
    std::set<std::pair<std::int64_t, std::int64_t>> vertices;
    for (const auto& [v, w] : wp) vertices.insert(v);
    for (const auto& [v, w] : wq) vertices.insert(v);
    for (const auto& vertex : vertices) {
      float a_weight = 0.0f;
      float b_weight = 0.0f;
      for (const auto& [v, w] : wp)
        if (v == vertex) a_weight = w;
      for (const auto& [v, w] : wq)
        if (v == vertex) b_weight = w;
      // The gradient of a barycentric weight is 2 / (sqrt(3) edge); float rounding adds ~1e-6.
      ASSERT_LE(std::abs(a_weight - b_weight), 2.0 / kSqrt3 * kStep / kEdge + 1e-5)
          << "at (" << p.x << ", " << p.y << ")";
    }
  }
}

TEST(TilingLattice, FarFromTheOriginIsAsPreciseAsNearIt) {
  // docs/design.md §4: p = 1e7 must look like p = 0. The wrapped fetch position moves by a
  // quarter pixel for a quarter-pixel step there too (float p would have a resolution of 1), and
  // the weights change by the same amount as near the origin.
  constexpr double kEdge = 128.0;
  for (const double origin : {0.0, 1e7, -1e7}) {
    for (int k = 0; k < 64; ++k) {
      const Vec2d p{origin + 0.25 * k + 0.1, origin + 0.1};
      const Point2f a = wrap_position(p, 200, 100);
      const Point2f b = wrap_position({p.x + 0.25, p.y}, 200, 100);
      EXPECT_NEAR(std::fmod(b.x - a.x + 200.0f, 200.0f), 0.25f, 1e-3f) << origin;
      EXPECT_GE(a.x, 0.0f);
      EXPECT_LT(a.x, 200.0f);
      const LatticePoint la = triangle_lattice(p, kEdge);
      const LatticePoint lb = triangle_lattice({p.x + 0.25, p.y}, kEdge);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (la.vertex_x[i] == lb.vertex_x[j] && la.vertex_y[i] == lb.vertex_y[j]) {
            EXPECT_LE(std::abs(la.weight[i] - lb.weight[j]), 0.25 * 2.0 / kSqrt3 / kEdge + 1e-5);
          }
    }
  }
}

TEST(TilingTables, NormalQuantileInvertsTheNormalCdf) {
  for (const double q : {1e-9, 1e-6, 0.001, 0.02, 0.3, 0.5, 0.7, 0.98, 0.999, 1.0 - 1e-6}) {
    const double x = normal_quantile(q);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::sqrt(2.0)), q, 1e-12 + 1e-10 * q) << q;
  }
  // Eq. (22) inverts eq. (20).
  for (const double q : {0.01, 0.2, 0.5, 0.9}) {
    const auto g = static_cast<float>(kGaussianMean + kGaussianDeviation * normal_quantile(q));
    EXPECT_NEAR(gaussian_to_uniform(g), q, 1e-6) << q;
  }
}

// Eq. (22)'s erf is a rational approximation that the vectorised evaluator repeats bit for bit
// (evaluate.hpp): within 1e-7 of erf at every float, odd, and +-1 far out (libm's erff: 5.4e-8).
TEST(TilingTables, ErfRationalIsWithinFloatPrecisionOfErf) {
  double worst = 0.0;
  for (int i = -600000; i <= 600000; ++i) {
    const float x = static_cast<float>(i) * 1e-5f;
    const float y = erf_rational(x);
    worst = std::max(worst, std::abs(static_cast<double>(y) - std::erf(static_cast<double>(x))));
    ASSERT_EQ(erf_rational(-x), -y) << x;
  }
  EXPECT_LT(worst, 1e-7);
  EXPECT_GT(worst, 1e-9);  // an approximation, not libm's erf
  EXPECT_NEAR(erf_rational(1e30f), 1.0f, 1e-7f);
  EXPECT_NEAR(erf_rational(-1e30f), -1.0f, 1e-7f);
}

TEST(TilingTables, TableCoordinateClampsAndInterpolatesBetweenCellCentres) {
  int cell = -1;
  EXPECT_FLOAT_EQ(table_coordinate(0.0f, 8, cell), 0.0f);
  EXPECT_EQ(cell, 0);
  EXPECT_FLOAT_EQ(table_coordinate(1.0f, 8, cell), 1.0f);
  EXPECT_EQ(cell, 6);
  EXPECT_NEAR(table_coordinate((3 + 0.5f) / 8.0f, 8, cell), 0.0f, 1e-6);
  EXPECT_EQ(cell, 3);
  EXPECT_NEAR(table_coordinate(4.0f / 8.0f, 8, cell), 0.5f, 1e-6);
  EXPECT_EQ(cell, 3);
}

TEST(TilingTransport, OneDimensionalTransportIsTheExactRankMatching) {
  std::mt19937 engine(3);
  std::exponential_distribution<float> skewed(3.0f);
  std::vector<float> values(5000);
  for (float& v : values) v = skewed(engine);
  std::vector<float> gaussian(values.size());
  std::vector<float> table(256);
  gaussianise_1d(values, gaussian, table);
  // Monotone: the order of the values is the order of their Gaussian images.
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    EXPECT_LE(gaussian[order[k - 1]], gaussian[order[k]]);
  // Exactly the quantiles of eq. (20): mean 1/2, deviation 1/6 (up to the stratification).
  double mean = 0.0;
  double square = 0.0;
  for (const float g : gaussian) {
    mean += g;
    square += static_cast<double>(g) * g;
  }
  mean /= static_cast<double>(gaussian.size());
  const double deviation = std::sqrt(square / static_cast<double>(gaussian.size()) - mean * mean);
  EXPECT_NEAR(mean, 0.5, 1e-6);
  EXPECT_NEAR(deviation, 1.0 / 6.0, 2e-3);
  // T^-1 table: monotone, the values' quantiles at (k + 1/2) / size.
  EXPECT_TRUE(std::is_sorted(table.begin(), table.end()));
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_NEAR(table[128], sorted[static_cast<std::size_t>((128.5 / 256.0) * 5000.0)], 2e-3);
}

// Minimum-cost perfect assignment between two sets of n points: the Hungarian method with
// potentials (Kuhn 1955, Munkres 1957), O(n^3). Returns assignment[i] = target of source i.
std::vector<int> exact_assignment(const std::vector<double>& cost, int n) {
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
  std::vector<int> matched(n + 1, 0), way(n + 1, 0);
  for (int row = 1; row <= n; ++row) {
    matched[0] = row;
    int column = 0;
    std::vector<double> slack(n + 1, infinity);
    std::vector<char> used(n + 1, 0);
    do {
      used[column] = 1;
      const int current_row = matched[column];
      double delta = infinity;
      int next = 0;
      for (int j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double reduced = cost[(current_row - 1) * n + (j - 1)] - u[current_row] - v[j];
        if (reduced < slack[j]) {
          slack[j] = reduced;
          way[j] = column;
        }
        if (slack[j] < delta) {
          delta = slack[j];
          next = j;
        }
      }
      for (int j = 0; j <= n; ++j) {
        if (used[j]) {
          u[matched[j]] += delta;
          v[j] -= delta;
        } else {
          slack[j] -= delta;
        }
      }
      column = next;
    } while (matched[column] != 0);
    do {
      const int previous = way[column];
      matched[column] = matched[previous];
      column = previous;
    } while (column != 0);
  }
  std::vector<int> assignment(n);
  for (int j = 1; j <= n; ++j) assignment[matched[j] - 1] = j - 1;
  return assignment;
}

double squared_distance(const float* a, const float* b) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c)
    sum += (static_cast<double>(a[c]) - b[c]) * (static_cast<double>(a[c]) - b[c]);
  return sum;
}

// Mean squared displacement of the exact optimal assignment between a and b (n points each).
double exact_w2_squared(const std::vector<float>& a, const std::vector<float>& b, int n) {
  std::vector<double> cost(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) cost[i * n + j] = squared_distance(&a[i * 3], &b[j * 3]);
  const std::vector<int> assignment = exact_assignment(cost, n);
  double total = 0.0;
  for (int i = 0; i < n; ++i) total += cost[i * n + assignment[i]];
  return total / n;
}

TEST(TilingTransport, HungarianSolverFindsTheKnownOptimum) {
  // Points on a line: the optimal assignment is the sorted matching.
  const std::vector<double> cost = {0, 1, 4, 1, 0, 1, 4, 1, 0};
  EXPECT_EQ(exact_assignment(cost, 3), (std::vector<int>{0, 1, 2}));
  const std::vector<double> shuffled = {4, 1, 0, 1, 0, 1, 0, 1, 4};
  EXPECT_EQ(exact_assignment(shuffled, 3), (std::vector<int>{2, 1, 0}));
}

TEST(TilingTransport, SlicedTransportIsWithinAFewPercentOfTheExactOptimum) {
  // W2 gap to an exact solver (the requirement): 200 colours of a bimodal skewed
  // distribution transported onto 200 Gaussian points of eq. (20). The sliced result Z is (a)
  // almost exactly the target set (its residual W2^2 to it is tiny) and (b) reached along a
  // displacement whose cost is within a few percent of the exact optimal assignment's.
  constexpr int kPoints = 200;
  std::mt19937 engine(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<float> colours(kPoints * 3);
  std::vector<float> gaussian(kPoints * 3);
  for (int i = 0; i < kPoints; ++i) {
    const bool bright = uniform(engine) < 0.3f;
    for (int c = 0; c < 3; ++c) {
      const float u = uniform(engine);
      colours[i * 3 + c] =
          bright ? 0.85f - 0.1f * u * u : 0.1f + 0.2f * u * u * u + 0.05f * static_cast<float>(c);
      gaussian[i * 3 + c] = 0.5f + normal(engine) / 6.0f;
    }
  }
  const double exact = exact_w2_squared(colours, gaussian, kPoints);
  for (const int iterations : {16, 64, 256}) {
    const std::vector<float> moved =
        sliced_transport_to_points(colours, gaussian, 3, iterations, 11);
    double displacement = 0.0;
    for (int i = 0; i < kPoints; ++i)
      displacement += squared_distance(&colours[i * 3], &moved[i * 3]);
    displacement /= kPoints;
    // The assignment the sliced result implies: each moved point snapped to a distinct target
    // point (exactly, by the same solver). Its cost is a true assignment cost, >= the optimum.
    std::vector<double> cost(kPoints * kPoints);
    for (int i = 0; i < kPoints; ++i)
      for (int j = 0; j < kPoints; ++j)
        cost[i * kPoints + j] = squared_distance(&moved[i * 3], &gaussian[j * 3]);
    const std::vector<int> snapped = exact_assignment(cost, kPoints);
    double assigned = 0.0;
    double residual = 0.0;
    for (int i = 0; i < kPoints; ++i) {
      assigned += squared_distance(&colours[i * 3], &gaussian[snapped[i] * 3]);
      residual += cost[i * kPoints + snapped[i]];
    }
    assigned /= kPoints;
    residual /= kPoints;
    std::cout << "sliced transport, " << iterations << " iterations: displacement W2^2 "
              << displacement << ", implied assignment " << assigned << ", exact optimum " << exact
              << " (gap " << 100.0 * (assigned / exact - 1.0) << "%), residual W2^2 to the target "
              << residual << "\n";
    if (iterations == 64) {
      // The default: the implied assignment within 5% of the optimum (measured 1.3%; 16 and 256
      // iterations 1.6% and 1.9%) and a residual under 3% of it (measured 1.9%: 200 points cannot
      // all be met exactly). Broken variant checked: full steps throughout (plain iterated
      // distribution transfer) measured a 15% gap and fails.
      EXPECT_LT(assigned, 1.05 * exact);
      EXPECT_LT(residual, 0.03 * exact);
      EXPECT_NEAR(displacement, exact, 0.05 * exact);
    }
  }
}

TEST(TilingTransport, SlicedTransportToTheGaussianReachesItsMoments) {
  const ImageF exemplar = structured_exemplar(64, 3, 6);
  std::vector<float> colours(exemplar.pixels().begin(), exemplar.pixels().end());
  const std::vector<float> gaussian = sliced_transport_to_gaussian(colours, 3, 64, 1);
  const std::size_t count = gaussian.size() / 3;
  double mean[3] = {0, 0, 0};
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) mean[c] += gaussian[i * 3 + c];
  for (double& m : mean) m /= static_cast<double>(count);
  double covariance[3][3] = {};
  for (std::size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        covariance[a][b] += (gaussian[i * 3 + a] - mean[a]) * (gaussian[i * 3 + b] - mean[b]);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean[a], 0.5, 1e-3);
    for (int b = 0; b < 3; ++b)
      EXPECT_NEAR(covariance[a][b] / static_cast<double>(count), a == b ? 1.0 / 36.0 : 0.0, 5e-4);
  }
}

// The analysis of the exemplar as given (make_tileable off unless asked: structured_exemplar does
// not tile, and these tests check the transport and the blend against it).
Model analyse(const ImageF& exemplar, const ParamValues& params = {}) {
  ParamValues all = params;
  all.try_emplace("iterations", 24);
  all.try_emplace("make_tileable", 0);
  return analyze("tiling", exemplar.view(), all, 3);
}

ImageF render_model(const Model& model, const Grid& grid, std::uint32_t seed, int threads = 1,
                    int tile = 64) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.threads = threads;
  options.tile_size = tile;
  render(model, grid, seed, out.view(), options);
  return out;
}

TEST(TilingModelFile, RoundTripIsExactForEveryLayout) {
  const Grid grid{{3.0, -7.0}, 1.5, 24, 20};
  for (const int channels : {1, 2, 3, 4})
    for (const double transport : {0.0, 1.0})
      for (const double blend : {0.0, 1.0, 2.0}) {
        const Model model = analyse(
            structured_exemplar(32, channels, 7),
            {{"transport", transport}, {"blend", blend}, {"lut_size", 8}, {"table_size", 64}});
        const Model loaded = deserialize_model(serialize_model(model), "round.stx");
        EXPECT_EQ(loaded.method(), "tiling");
        EXPECT_EQ(serialize_model(loaded), serialize_model(model));
        EXPECT_TRUE(same_bytes(render_model(model, grid, 5), render_model(loaded, grid, 5)))
            << channels << " channels, transport " << transport << ", blend " << blend;
      }
}

constexpr auto expect_rejected = &test_support::expect_record_rejected<TilingModel>;

void check_threads_tiles_and_regions(const Model& model);

// A model without the 3-D table stores its prefiltered and calibrated level tables, so that a load
// need not rebuild them (issue 39): the file holds the tables the model built, a record without
// them loads a model that builds the same, and tables of the wrong shape are refused. With the
// 3-D table none are stored (its levels would make the file several times larger).
TEST(TilingModelFile, LevelTablesAreStoredAsBuilt) {
  const auto level_tables = [](const TilingModel& tiling) {
    std::vector<float> tables;
    for (int l = 0; l < tiling.level_count(); ++l)
      tables.insert(tables.end(), tiling.level_tables(l).begin(), tiling.level_tables(l).end());
    return tables;
  };
  const auto stored = [](auto& record) {
    return std::find_if(record.arrays.begin(), record.arrays.end(),
                        [](const NamedArray& array) { return array.name == "level_tables"; });
  };
  for (const int channels : {1, 3, 4}) {
    const Model model =
        analyse(structured_exemplar(32, channels, 7), {{"transport", 1}, {"table_size", 64}});
    const TilingModel& tiling = tiling_of(model);
    const ModelRecord record = tiling.to_record(model.params());
    const auto found = stored(record);
    ASSERT_NE(found, record.arrays.end()) << channels << " channels";
    EXPECT_EQ(found->values, level_tables(tiling)) << channels << " channels";
    ModelRecord without = record;
    without.arrays.erase(stored(without));
    EXPECT_EQ(level_tables(TilingModel::from_record(without, "without.stx")), level_tables(tiling))
        << channels << " channels";
    // `info --export` shows the exemplar, not the tables (three dimensions, not an image).
    std::vector<std::string> images;
    for (const NamedImage& image : model_images(model)) images.push_back(image.name);
    EXPECT_EQ(images, std::vector<std::string>{"gaussian"}) << channels << " channels";
    ModelRecord wrong = record;
    const auto tables = stored(wrong);
    tables->shape[0] -= 1;
    tables->values.resize(tables->values.size() / 2);
    expect_rejected(wrong, "level tables of the wrong shape");
  }
  const Model sliced = analyse(structured_exemplar(32, 3, 7), {{"transport", 0}, {"lut_size", 8}});
  const ModelRecord record = tiling_of(sliced).to_record(sliced.params());
  EXPECT_EQ(stored(record), record.arrays.end());
  // An srgb colour model's tables are calibrated after decoding (calibrate_decoded): a file
  // without them loads tables calibrated to the same values.
  const Model srgb = with_colour_space(
      analyse(structured_exemplar(32, 3, 7), {{"transport", 1}, {"table_size", 64}}),
      ColourSpace::srgb);
  const std::vector<std::uint8_t> bytes = serialize_model(srgb);
  ModelRecord without = read_model_record(bytes, "srgb.stx");
  without.arrays.erase(stored(without));
  const Model rebuilt = deserialize_model(write_model_record(without), "without.stx");
  EXPECT_EQ(level_tables(tiling_of(rebuilt)), level_tables(tiling_of(srgb)));
  // Assembled again with its colour space, it is not calibrated twice.
  EXPECT_EQ(level_tables(tiling_of(with_colour_space(srgb, ColourSpace::srgb))),
            level_tables(tiling_of(srgb)));
  EXPECT_NE(level_tables(tiling_of(srgb)),
            level_tables(tiling_of(
                analyse(structured_exemplar(32, 3, 7), {{"transport", 1}, {"table_size", 64}}))));
}

// `record` with the scalar `name` set to `value`.
ModelRecord scalar_edited(ModelRecord record, const std::string& name, double value) {
  record.scalars[name] = value;
  return record;
}

TEST(TilingModelFile, CorruptRecordsAreRejectedWithAFormatError) {
  const Model model = analyse(structured_exemplar(16, 4, 8), {{"transport", 0}, {"lut_size", 4}});
  const ModelRecord good = tiling_of(model).to_record(model.params());
  EXPECT_NO_THROW(TilingModel::from_record(good, "good.stx"));
  const auto with_scalar = [&](const std::string& name, double value) {
    return scalar_edited(good, name, value);
  };
  expect_rejected(with_scalar("channels", 5), "5 channels");
  expect_rejected(with_scalar("channels", 3), "channel count that disagrees with the arrays");
  expect_rejected(with_scalar("width", 1), "1-pixel width");
  expect_rejected(with_scalar("width", 1e12), "huge width");
  expect_rejected(with_scalar("tile_radius", 1e9), "tile_radius out of range");
  expect_rejected(with_scalar("tile_radius", std::nan("")), "NaN tile_radius");
  expect_rejected(with_scalar("lut_size", 65), "lut_size out of range");
  expect_rejected(with_scalar("lut_size", 5), "lut_size that disagrees with the table");
  expect_rejected(with_scalar("table_size", 3.5), "fractional table_size");
  expect_rejected(with_scalar("transport", 2), "unknown transport");
  expect_rejected(with_scalar("transport", 1), "transport without its tables");
  expect_rejected(with_scalar("blend", 0.5), "fractional blend");
  expect_rejected(with_scalar("blend", 3), "unknown blend");
  ModelRecord missing = good;
  missing.scalars.erase("height");
  expect_rejected(missing, "missing height");
  for (const std::string name : {"gaussian", "blend_mean", "lut", "tables"}) {
    ModelRecord record = good;
    for (auto& array : record.arrays)
      if (array.name == name) array.values[0] = std::numeric_limits<float>::infinity();
    expect_rejected(record, "non-finite " + name);
    record = good;
    std::erase_if(record.arrays, [&](const NamedArray& a) { return a.name == name; });
    expect_rejected(record, "missing " + name);
    record = good;
    for (auto& array : record.arrays)
      if (array.name == name) {
        array.shape[0] += 1;
        array.values.resize(array.values.size() * 2);
      }
    expect_rejected(record, "wrong shape of " + name);
  }
}

TEST(TilingChannels, AlphaIsCarriedAndNeverEntersTheColour) {
  // An RGBA exemplar's colour renders exactly like the RGB exemplar alone (alpha has its own 1-D
  // transport and table); its alpha keeps the alpha histogram (only values of the exemplar's
  // alpha range, both modes present).
  const ImageF rgba = structured_exemplar(48, 4, 9);
  ImageF rgb(48, 48, 3);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = rgba.at(x, y, c);
  const Grid grid{{0.0, 0.0}, 1.0, 64, 64};
  for (const double transport : {0.0, 1.0}) {
    const ImageF with_alpha = render_model(analyse(rgba, {{"transport", transport}}), grid, 2);
    const ImageF without = render_model(analyse(rgb, {{"transport", transport}}), grid, 2);
    int low = 0;
    int high = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(with_alpha.at(x, y, c), without.at(x, y, c));
        const float alpha = with_alpha.at(x, y, 3);
        EXPECT_GE(alpha, 0.1f);  // the exemplar's alpha lies in [0.3, 0.5] and [0.85, 0.95]
        EXPECT_LE(alpha, 0.96f);
        low += alpha < 0.6f;
        high += alpha >= 0.6f;
      }
    EXPECT_GT(low, 200);
    EXPECT_GT(high, 200);
  }
}

TEST(TilingEvaluate, GaussianFastPathIsTheVarianceBlendOfTheExemplar) {
  // Section 6.1: no tables; the output is eq. (8) on three periodic bilinear patches.
  const ImageF exemplar = structured_exemplar(40, 3, 10);
  const Model model = analyse(exemplar, {{"blend", 1}});
  const TilingModel& tiling = tiling_of(model);
  EXPECT_TRUE(tiling.data().lut.empty());
  EXPECT_TRUE(tiling.data().tables.empty());
  double mean[3] = {0, 0, 0};
  for (std::size_t i = 0; i < exemplar.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c)
      mean[c] += exemplar.pixels()[i * 3 + c] / static_cast<double>(exemplar.pixel_count());
  const MipLevel level{40, 40, 1.0f, 1.0f, exemplar.pixels().data()};
  std::mt19937 engine(4);
  std::uniform_real_distribution<double> position(-1000.0, 1000.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2d p{position(engine), position(engine)};
    float out[3];
    evaluate(model, std::span<const Vec2d>(&p, 1), {}, 9, ImageView<float>{out, 1, 1, 3, 3});
    const LatticePoint lattice = triangle_lattice(p, tiling.lattice_edge());
    float acc[3] = {0, 0, 0};
    float squares = 0.0f;
    for (int v = 0; v < 3; ++v) {
      const Point2f offset = vertex_offset(lattice.vertex_x[v], lattice.vertex_y[v], 9, 40, 40);
      const Point2f wrapped = wrap_position(p, 40, 40);
      fetch_bilinear(level, 3, wrapped.x + offset.x, wrapped.y + offset.y, lattice.weight[v], acc);
      squares += lattice.weight[v] * lattice.weight[v];
    }
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out[c], (acc[c] - mean[c]) / std::sqrt(squares) + mean[c], 1e-4);
  }
}

TEST(TilingTables, OneDimensionalTablesInvertTheTransport) {
  // With 1-D tables (grey, alpha, the per-channel transport) T^-1(T(x)) = x up to the table's
  // interpolation: a patch at a vertex (weight 1) reproduces the exemplar. Measured rms 5.3e-3
  // here (1024 quantiles of 2304 pixels with gaps in the histogram), 6e-4 on water_caustics_256 and
  // 1.1e-3 on moss_ground_512 (the 3-D table of the sliced transport: 0.05 and 0.02, see
  // analysis.cpp); a table indexed without the erf mapping of eq. (22) fails by far.
  for (const int channels : {1, 3, 4}) {
    const ImageF exemplar = structured_exemplar(48, channels, 16);
    const Model model = analyse(exemplar, {{"transport", 1}});
    const TilingModel& tiling = tiling_of(model);
    double squares = 0.0;
    for (std::size_t i = 0; i < exemplar.pixel_count(); ++i) {
      float out[4];
      tiling.inverse_transform(&tiling.data().gaussian[i * channels], {}, out);
      for (int c = 0; c < channels; ++c) {
        const double d = out[c] - exemplar.pixels()[i * channels + c];
        squares += d * d;
      }
    }
    EXPECT_LT(std::sqrt(squares / static_cast<double>(exemplar.pixel_count() * channels)), 1e-2)
        << channels << " channels";
  }
}

TEST(TilingTables, ColourTableIsFetchedAtTheErfParameterisation) {
  // At the Gaussian value of a cell centre (eq. 20) the 3-D table returns that cell (eq. 22).
  const Model model = analyse(structured_exemplar(32, 3, 11), {{"transport", 0}, {"lut_size", 8}});
  const TilingModel& tiling = tiling_of(model);
  const std::vector<float>& lut = tiling.data().lut;
  for (const auto& [x, y, z] : {std::tuple{0, 0, 0}, std::tuple{3, 5, 1}, std::tuple{7, 2, 6}}) {
    const auto centre = [](int i) {
      return static_cast<float>(kGaussianMean +
                                kGaussianDeviation * normal_quantile((i + 0.5) / 8));
    };
    const float g[3] = {centre(x), centre(y), centre(z)};
    float out[3];
    tiling.inverse_transform(g, {}, out);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out[c], lut[((static_cast<std::size_t>(z) * 8 + y) * 8 + x) * 3 + c], 1e-4);
  }
}

TEST(TilingFiltering, ConstantMinifiedFetchIsTheMeanNotTheMedian) {
  // The follow-up's point: T^-1(1/2) is the exemplar's median; a fully minified sample must be
  // its mean. A skewed exemplar makes the two differ by ~0.1.
  std::mt19937 engine(12);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const int channels : {1, 3}) {
    ImageF exemplar(64, 64, channels);
    for (float& v : exemplar.pixels()) {
      const float u = uniform(engine);
      v = u * u * u * u;  // mean 0.2, median 0.0625
    }
    for (const double transport : {0.0, 1.0}) {
      const Model model = analyse(exemplar, {{"transport", transport}});
      ImageF out(8, 8, channels);
      RenderOptions options;
      render(model, Grid{{0.0, 0.0}, 4096.0, 8, 8}, 1, out.view(), options);
      for (int c = 0; c < channels; ++c) {
        double mean = 0.0;
        for (std::size_t i = 0; i < exemplar.pixel_count(); ++i)
          mean += exemplar.pixels()[i * channels + c];
        mean /= static_cast<double>(exemplar.pixel_count());
        for (int y = 0; y < 8; ++y)
          for (int x = 0; x < 8; ++x)
            EXPECT_NEAR(out.at(x, y, c), mean, 0.01)
                << channels << " channels, transport " << transport;
      }
    }
  }
}

TEST(TilingAnalysis, StationarityPreprocessingRemovesPeriodsLongerThanATile) {
  // Section 5.3, figure 9: an exemplar whose variations are longer than a tile (a cosine of period
  // 4 tile edges under fine noise) makes a render whose large-scale mean wanders with each
  // patch. The preprocessing removes 88% of that cosine, so the variance of 32 x 32 block means of
  // the render drops by about 1 / 0.12^2 = 70 (measured 72x; bound 10x).
  std::mt19937 engine(17);
  std::normal_distribution<float> noise(0.0f, 0.05f);
  ImageF exemplar(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      exemplar.at(x, y, 0) =
          0.5f + 0.25f * std::cos(6.2831853f * static_cast<float>(x) / 64.0f) + noise(engine);
  const auto block_mean_variance = [&](double stationarity) {
    const Model model = analyse(exemplar, {{"tile_radius", 0.25}, {"stationarity", stationarity}});
    const ImageF image = render_model(model, Grid{{0.0, 0.0}, 1.0, 256, 256}, 5);
    std::vector<double> means;
    for (int by = 0; by < 8; ++by)
      for (int bx = 0; bx < 8; ++bx) {
        double sum = 0.0;
        for (int y = 0; y < 32; ++y)
          for (int x = 0; x < 32; ++x) sum += image.at(bx * 32 + x, by * 32 + y, 0);
        means.push_back(sum / 1024.0);
      }
    double mean = 0.0;
    for (const double m : means) mean += m / 64.0;
    double variance = 0.0;
    for (const double m : means) variance += (m - mean) * (m - mean) / 63.0;
    return variance;
  };
  const double without = block_mean_variance(0);
  const double with = block_mean_variance(1);
  std::cout << "block-mean variance without preprocessing " << without << ", with " << with << "\n";
  EXPECT_GT(without, 10.0 * with);
}

TEST(TilingAnalysis, ANonTileableExemplarIsMadeTileableWithItsHistogram) {
  // A photo cut from a larger scene: fine noise over a ramp along x and a cosine along y of
  // period 1.5 sides, so that a repeat steps at both wraps. Algorithm 1 reads the exemplar
  // periodically, so that step is a seam inside every patch that crosses the border (issue 37:
  // rectangles on water_caustics_256).
  std::mt19937 engine(31);
  std::normal_distribution<float> noise(0.0f, 0.03f);
  ImageF photo(48, 40, 3);
  for (int y = 0; y < photo.height(); ++y)
    for (int x = 0; x < photo.width(); ++x)
      for (int c = 0; c < 3; ++c)
        photo.at(x, y, c) = 0.2f + 0.5f * static_cast<float>(x) / 47.0f +
                            0.1f * std::cos(4.18879f * static_cast<float>(y) / 40.0f) +
                            0.05f * static_cast<float>(c) + noise(engine);
  const WrapSteps given = wrap_steps(photo.view());
  ASSERT_GT(given.x, 10.0);
  ASSERT_GT(given.y, kTileableWrapStep);
  // The exemplar made tileable keeps every channel's values exactly (sorted, the same), and a
  // repeat of it steps no more at its wrap than inside.
  const ImageF tileable = periodic_keeping_histogram(photo.view());
  for (int c = 0; c < 3; ++c) {
    std::vector<float> before, after;
    for (int y = 0; y < photo.height(); ++y)
      for (int x = 0; x < photo.width(); ++x) {
        before.push_back(photo.at(x, y, c));
        after.push_back(tileable.at(x, y, c));
      }
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    EXPECT_EQ(before, after) << "channel " << c;
  }
  // By default (auto) the analysis makes it tileable: a repeat of the Gaussianised exemplar G that
  // the patches read steps at its wrap no more than inside it (measured x 0.52, y 0.58: the
  // smooth component takes some of the border's noise with it), where the exemplar as is
  // keeps the step (off: x 2.1, y 1.2, G's Gaussian marginals compress the ramp's). The model
  // file keeps the choice made and the given exemplar's steps.
  const auto g_wrap = [](const Model& model) {
    const TilingData& data = tiling_of(model).data();
    return wrap_steps({data.gaussian.data(), data.width, data.height, data.channels,
                       static_cast<std::ptrdiff_t>(data.width) * data.channels});
  };
  const Model made = analyse(photo, {{"make_tileable", 2}});
  const Model as_is = analyse(photo, {{"make_tileable", 0}});
  std::cout << "G's wrap steps: made tileable x " << g_wrap(made).x << ", y " << g_wrap(made).y
            << "; as is x " << g_wrap(as_is).x << ", y " << g_wrap(as_is).y << "\n";
  EXPECT_LT(g_wrap(made).largest(), 1.0);
  EXPECT_GT(g_wrap(as_is).x, kTileableWrapStep);
  ASSERT_TRUE(made.exemplar_wrap().has_value());
  EXPECT_EQ(made.exemplar_wrap()->x, given.x);
  EXPECT_EQ(made.exemplar_wrap()->y, given.y);
  const Model loaded = deserialize_model(serialize_model(made), "made.stx");
  EXPECT_EQ(serialize_model(loaded), serialize_model(made));
  EXPECT_EQ(loaded.exemplar_wrap()->y, given.y);
  EXPECT_EQ(loaded.params().at("make_tileable"), 1.0);
  EXPECT_EQ(deserialize_model(serialize_model(as_is), "as_is.stx").params().at("make_tileable"),
            0.0);
  // A tileable exemplar (white noise: its wrap is one more pair of independent pixels) is left
  // as is: auto gives the model of off, byte for byte.
  ImageF periodic(32, 32, 3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& value : periodic.pixels()) value = uniform(engine);
  ASSERT_LT(wrap_steps(periodic.view()).largest(), kTileableWrapStep);
  EXPECT_EQ(serialize_model(analyse(periodic, {{"make_tileable", 2}})),
            serialize_model(analyse(periodic, {{"make_tileable", 0}})));
}

TEST(TilingAnalysis, AutomaticTileRadiusFollowsTheExemplarsLargestPeriods) {
  // tile_radius = 0 (the default) chooses the radius from the spectrum. Fine white noise spreads
  // its power evenly over the frequencies, so the lowest 0.5% lie below about 0.04 cycles per
  // pixel: a diameter of 25 pixels, radius 0.1 of a side of 128, raised to the floor of 1/4. A
  // cosine of period side (60% of the power) needs a tile as wide as the exemplar: radius 1/2.
  std::mt19937 engine(5);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  ImageF fine(128, 128, 3);
  ImageF large(128, 128, 3);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      for (int c = 0; c < 3; ++c) {
        fine.at(x, y, c) = 0.5f + noise(engine);
        large.at(x, y, c) =
            fine.at(x, y, c) + 0.15f * std::cos(6.2831853f * static_cast<float>(x) / 128.0f);
      }
  EXPECT_EQ(auto_tile_radius(fine.view()), kAutoTileRadiusMin);
  EXPECT_EQ(auto_tile_radius(large.view()), 0.5);
  // Between the two: a diagonal cosine of frequency (1, 1) / side and nothing lower needs a
  // diameter of side / sqrt(2), radius 1 / (2 sqrt(2)).
  ImageF diagonal(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      diagonal.at(x, y, 0) = 0.5f +
                             0.3f * std::cos(6.2831853f * static_cast<float>(x + y) / 64.0f) +
                             0.02f * std::cos(6.2831853f * static_cast<float>(x + 2 * y) / 5.0f);
  EXPECT_NEAR(auto_tile_radius(diagonal.view()), 0.5 / std::sqrt(2.0), 1e-12);
  // The model uses and its file names the radius chosen; an explicit radius is kept, and one
  // below 0.05 other than 0 is refused with the parameters.
  const Model chosen = analyse(large);
  EXPECT_EQ(tiling_of(chosen).data().tile_radius, 0.5);
  EXPECT_EQ(deserialize_model(serialize_model(chosen), "chosen.stx").params().at("tile_radius"),
            0.5);
  const Model given = analyse(fine, {{"tile_radius", 0.8}});
  EXPECT_EQ(tiling_of(given).data().tile_radius, 0.8);
  EXPECT_THROW(analyse(fine, {{"tile_radius", 0.01}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("tiling", ParamValues{{"tile_radius", 0.01}}), std::invalid_argument);
  EXPECT_EQ(resolve_params("tiling", ParamValues{{"tile_radius", 0}}).at("tile_radius"), 0.0);
}

TEST(TilingTriplanar, AnAxisNormalIsThePlanarNoiseAndABlendKeepsTheRange) {
  const Model model = analyse(structured_exemplar(48, 3, 13));
  const TilingModel& tiling = tiling_of(model);
  const std::uint32_t seed = 21;
  std::vector<SurfacePoint> axis;
  std::vector<SurfacePoint> blended;
  for (int k = 0; k < 50; ++k) {
    const Vec3d position{3.7 * k, -2.1 * k + 5.0, 0.9 * k};
    // A footprint of 2.5 pixels along x: the (x, y) plane reads level 1 of the pyramid.
    axis.push_back({position, {0.0, 0.0, -1.0}, {1.0, 0.0, 0.0}, {2.5, 0.0, 0.0}, {}});
    blended.push_back({position, {0.5, 0.6, 0.6244998}, {0.0, 0.7211103, -0.6928203}, {}, {}});
  }
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar;
  ImageF out(50, 1, 3);
  evaluate_surface(model, axis, options, seed, out.view());
  for (int k = 0; k < 50; ++k) {
    const Footprint footprint{{2.5, 0.0}, {0.0, 0.0}};
    float g[3];
    float planar[3];
    const LevelOfDetail lod = tiling.blended_gaussian({axis[k].position.x, axis[k].position.y},
                                                      TilingModel::footprint_width(&footprint),
                                                      TilingModel::triplanar_seed(2, seed), g);
    tiling.inverse_transform(g, lod, planar);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.at(k, 0, c), planar[c], 1e-5);
  }
  evaluate_surface(model, blended, options, seed, out.view());
  for (const float value : out.pixels()) {
    EXPECT_TRUE(std::isfinite(value));
    EXPECT_GE(value, -0.05f);
    EXPECT_LE(value, 1.05f);
  }
}

// Footprints far wider than the exemplar (a mesh seen at a grazing angle): every plane reads the
// top level, and so must the one look-up at their w^2-weighted mean level, which can round past
// the top (this read beyond the pyramid: render-mesh crashed on a torus with sharpness 8).
TEST(TilingTriplanar, FootprintsBeyondThePyramidReadTheTopLevel) {
  const Model model = analyse(structured_exemplar(48, 3, 13));
  const std::vector<SurfacePoint> points = test_support::sphere_points(3000, 50.0, 3e4, 2e4, 6);
  SurfaceOptions options;
  options.mapping = SurfaceMapping::triplanar;
  ImageF out(3000, 1, 3);
  for (const double sharpness : {1.0, 4.0, 8.0, 40.0}) {
    options.triplanar_sharpness = sharpness;
    evaluate_surface(model, points, options, 5, out.view());
    for (const float value : out.pixels()) {
      ASSERT_TRUE(std::isfinite(value));
      ASSERT_GE(value, -0.05f);
      ASSERT_LE(value, 1.05f);
    }
  }
}

TEST(TilingRender, OutputIsIndependentOfThreadsTilesAndRegions) {
  // The paper's operator, and the artist controls (each patch rotated and scaled, at its own
  // level of detail, sharpened weights).
  for (const ParamValues& params :
       {ParamValues{}, ParamValues{{"rotation", 180}, {"scale_jitter", 0.5}, {"sharpness", 4}}}) {
    check_threads_tiles_and_regions(analyse(structured_exemplar(40, 3, 14), params));
  }
}

TEST(TilingControls, DefaultsAreThePapersOperatorAndOldFilesLoad) {
  const ImageF exemplar = structured_exemplar(32, 3, 21);
  const Grid grid{{3.0, -7.0}, 1.5, 24, 20};
  const Model model = analyse(exemplar);
  const Model explicit_defaults =
      analyse(exemplar, {{"rotation", 0}, {"scale_jitter", 0}, {"sharpness", 1}});
  // A model with the defaults is the file of a model from before the controls: its file names
  // none of them (so such an older file loads, with the defaults).
  const std::vector<std::uint8_t> bytes = serialize_model(model);
  EXPECT_EQ(bytes, serialize_model(explicit_defaults));
  const std::string text(bytes.begin(), bytes.end());
  for (std::size_t i = kFirstControl; i < kParams.size(); ++i)
    EXPECT_EQ(text.find(std::string(kParams[i].name)), std::string::npos) << kParams[i].name;
  const Model old_file = deserialize_model(bytes, "old.stx");
  const TilingData& loaded = tiling_of(old_file).data();
  EXPECT_EQ(loaded.rotation, 0.0);
  EXPECT_EQ(loaded.scale_jitter, 0.0);
  EXPECT_EQ(loaded.sharpness, 1.0);
  // Each control of an image is stored, read back, and changes the render (height_blend, which
  // needs a height map: TilingControls.HeightBlend*).
  const ImageF reference = render_model(model, grid, 5);
  for (std::size_t i = kFirstControl; i < kParams.size(); ++i) {
    const std::string name(kParams[i].name);
    if (name == "height_blend") continue;
    const Model controlled = analyse(exemplar, {{name, kParams[i].max_value / 2}});
    const Model round = deserialize_model(serialize_model(controlled), "round.stx");
    EXPECT_EQ(round.params().at(name), kParams[i].max_value / 2) << name;
    EXPECT_EQ(serialize_model(round), serialize_model(controlled)) << name;
    const ImageF image = render_model(controlled, grid, 5);
    EXPECT_TRUE(same_bytes(image, render_model(round, grid, 5))) << name;
    EXPECT_FALSE(same_bytes(image, reference)) << name;
  }
}

TEST(TilingControls, SharpenedWeightsSumToOneAndFavourTheNearestVertex) {
  float weight[3] = {0.5f, 0.3f, 0.2f};
  sharpen_weights(weight, 4.0f);
  EXPECT_NEAR(weight[0] + weight[1] + weight[2], 1.0f, 1e-6f);
  EXPECT_NEAR(weight[0], 0.0625f / (0.0625f + 0.0081f + 0.0016f), 1e-6f);
  float unchanged[3] = {0.5f, 0.3f, 0.2f};
  sharpen_weights(unchanged, 1.0f);
  EXPECT_EQ(unchanged[1], 0.3f);
}

TEST(TilingControls, HeightBlendWeightsFavourTheHigherPatchAndKeepAVertexAlone) {
  // The weights go as w exp((h + w) / depth): with equal weights, a patch higher by depth
  // weighs e times more.
  const float heights[3] = {0.5f, 0.6f, 0.4f};
  float weights[3] = {0.25f, 0.25f, 0.5f};
  height_blend_weights(weights, heights, 0.1f);
  EXPECT_NEAR(weights[0] + weights[1] + weights[2], 1.0f, 1e-6f);
  EXPECT_NEAR(weights[1] / weights[0], std::exp(1.0f), 1e-4f);
  EXPECT_NEAR(weights[2] / weights[0], 2.0f * std::exp(1.5f), 1e-3f);
  // A weight of 0 stays 0 however high its patch (the blend is continuous across triangle
  // edges), and a vanishing depth leaves the highest patch of weight > 0 alone, without NaN.
  float edge[3] = {0.7f, 0.3f, 0.0f};
  const float high_third[3] = {0.5f, 0.2f, 2.0f};
  height_blend_weights(edge, high_third, 1e-30f);
  EXPECT_EQ(edge[0], 1.0f);
  EXPECT_EQ(edge[1], 0.0f);
  EXPECT_EQ(edge[2], 0.0f);
}

// A two-map material (albedo, height: structured_exemplar's two channels) analysed with `params`.
Model height_material(const ParamValues& params, const std::string& height_kind = "height") {
  const ImageF both = structured_exemplar(32, 2, 23);
  ImageF albedo(32, 32, 1), height(32, 32, 1);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      albedo.at(x, y, 0) = both.at(x, y, 0);
      height.at(x, y, 0) = both.at(x, y, 1);
    }
  ParamValues all = params;
  all.try_emplace("iterations", 24);
  return analyze_material("tiling",
                          std::vector<MaterialMap>{{"albedo", {}, albedo.view(), "albedo.png"},
                                                   {height_kind, {}, height.view(), "h.png"}},
                          all, 3);
}

TEST(TilingControls, HeightBlendIsStoredOnlyWhenOnAndNeedsAHeightMap) {
  const Grid grid{{3.0, -7.0}, 1.5, 24, 20};
  // Off: the file of a material made before the control, which loads with it off.
  const Model plain = height_material({});
  const std::vector<std::uint8_t> bytes = serialize_model(plain);
  EXPECT_EQ(bytes, serialize_model(height_material({{"height_blend", 0}})));
  const std::string text(bytes.begin(), bytes.end());
  EXPECT_EQ(text.find("height_blend"), std::string::npos);
  EXPECT_EQ(text.find("height_channel"), std::string::npos);
  EXPECT_EQ(tiling_of(deserialize_model(bytes, "old.stx")).data().height_channel, -1);
  // On: the height map's channel is stored; the file round-trips and the render changes.
  const Model blended = height_material({{"height_blend", 0.05}});
  EXPECT_EQ(tiling_of(blended).data().height_channel, 1);
  const Model round = deserialize_model(serialize_model(blended), "round.stx");
  EXPECT_EQ(serialize_model(round), serialize_model(blended));
  EXPECT_EQ(tiling_of(round).data().height_channel, 1);
  const ImageF image = render_model(blended, grid, 5);
  EXPECT_TRUE(same_bytes(image, render_model(round, grid, 5)));
  EXPECT_FALSE(same_bytes(image, render_model(plain, grid, 5)));
  // Refused by the analysis with one sentence: no height map (an image, or a material whose second
  // map is a scalar map), or a blend without Gaussianised heights.
  const auto refusal = [](const auto& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  };
  const std::string no_map = "has no height map";
  EXPECT_NE(refusal([] {
              analyse(structured_exemplar(16, 1, 2), {{"height_blend", 0.1}});
            }).find(no_map),
            std::string::npos);
  EXPECT_NE(refusal([] {
              height_material({{"height_blend", 0.1}}, "roughness");
            }).find(no_map),
            std::string::npos);
  EXPECT_NE(refusal([] {
              height_material({{"height_blend", 0.1}, {"blend", 1}});
            }).find("histogram blend"),
            std::string::npos);
}

TEST(TilingControls, HostileHeightBlendRecordsAreRejected) {
  const Model model = height_material({{"height_blend", 0.1}, {"lut_size", 4}});
  const ModelRecord good = tiling_of(model).to_record(model.params());
  EXPECT_NO_THROW(TilingModel::from_record(good, "good.stx"));
  for (const double channel : {-1.0, 2.0, 0.5, 1e12, std::nan("")})
    expect_rejected(scalar_edited(good, "height_channel", channel),
                    "height_channel " + std::to_string(channel));
  for (const double blend : {-0.1, 1.5, std::nan("")})
    expect_rejected(scalar_edited(good, "height_blend", blend),
                    "height_blend " + std::to_string(blend));
  ModelRecord missing = good;
  missing.scalars.erase("height_channel");
  expect_rejected(missing, "height_blend without its channel");
  // The variance blend has no Gaussianised heights: its data with the control on is refused.
  TilingData variance = tiling_of(height_material({{"blend", 1}})).data();
  EXPECT_NO_THROW(TilingModel{variance});
  variance.height_blend = 0.1;
  variance.height_channel = 1;
  EXPECT_THROW(TilingModel{variance}, std::invalid_argument);
  // A stored channel is ignored with the control off (the file of a model without it).
  ModelRecord off = good;
  off.scalars.erase("height_blend");
  EXPECT_EQ(TilingModel::from_record(off, "off.stx").data().height_channel, -1);
}

TEST(TilingControls, PatchTransformRotatesAboutTheVertexWithinTheRange) {
  // On the vertex the shift is zero (rotation about the tile's centre); the matrix is a rotation
  // by at most the range, scaled within 2^+-jitter.
  const float max_angle = 0.5f;
  for (std::int64_t v = 0; v < 200; ++v) {
    const PatchTransform m = patch_transform(v, -v, 3, max_angle, 0.5f);
    const double scale = std::hypot(m.xx, m.yx);
    EXPECT_NEAR(scale, m.scale, 1e-5);
    EXPECT_GE(m.scale, std::exp2(-0.5f) - 1e-6f);
    EXPECT_LE(m.scale, std::exp2(0.5f) + 1e-6f);
    EXPECT_LE(std::abs(std::atan2(m.yx, m.xx)), max_angle + 1e-5);
    const Point2f on_vertex = patch_shift(m, 0.0f, 0.0f, 64.0f);
    EXPECT_EQ(on_vertex.x, 0.0f);
    EXPECT_EQ(on_vertex.y, 0.0f);
  }
  const PatchTransform identity = patch_transform(5, 7, 3, 0.0f, 0.0f);
  const Point2f none = patch_shift(identity, 0.3f, -0.4f, 64.0f);
  EXPECT_EQ(none.x, 0.0f);
  EXPECT_EQ(none.y, 0.0f);
}

// Anisotropic slopes: a skewed, correlated pair with a heavier tail along one diagonal.
std::vector<float> skewed_slopes(std::size_t count) {
  std::mt19937 generator(11);
  std::normal_distribution<float> normal;
  std::vector<float> slopes(count * 2);
  for (std::size_t i = 0; i < count; ++i) {
    const float a = normal(generator);
    const float b = normal(generator);
    slopes[2 * i] = 0.6f * a + 0.2f * b * std::abs(b);
    slopes[2 * i + 1] = 0.3f * a - 0.15f * b;
  }
  return slopes;
}

TEST(TilingTables, RadialTransformInvertsItselfAndTurnsWithTheSlopes) {
  constexpr std::size_t kCount = 4000;
  constexpr int kSize = 512;
  const std::vector<float> slopes = skewed_slopes(kCount);
  std::vector<float> gaussian(kCount * 2);
  std::vector<float> table(kSize);
  tiling::gaussianise_radial(slopes, gaussian, table);
  // T keeps each direction; T^-1's table gives the magnitude back up to its interpolation within
  // its range (the top 1/1024 of the ranks lie beyond its last cell centre and are clamped there),
  // and the radii are the 2-D Gaussian's: E[rho^2] = 2 sigma^2. Measured rms 1.6e-3 (6e-4 over the
  // lower 99 %) of a mean |s| of 0.64; a table read at the erf parameter of eq. (22) instead of the
  // Rayleigh CDF: 0.6.
  double squares = 0.0, radius_squares = 0.0;
  int inside = 0;
  for (std::size_t i = 0; i < kCount; ++i) {
    const float dx = gaussian[2 * i] - tiling::kGaussianMean;
    const float dy = gaussian[2 * i + 1] - tiling::kGaussianMean;
    const float rho = std::hypot(dx, dy);
    radius_squares += rho * rho;
    EXPECT_NEAR(dx * slopes[2 * i + 1] - dy * slopes[2 * i], 0.0f, 1e-6f);
    EXPECT_GT(dx * slopes[2 * i] + dy * slopes[2 * i + 1], 0.0f);
    const double magnitude = std::hypot(slopes[2 * i], slopes[2 * i + 1]);
    if (magnitude <= table[kSize - 1]) {
      const double error = tiling::radial_lookup(table.data(), kSize, rho) - magnitude;
      squares += error * error;
      ++inside;
    }
    // radial_inverse undoes radial_lookup inside the table's range.
    if (rho > 0.05f && rho < 0.5f) {
      EXPECT_NEAR(tiling::radial_inverse(table.data(), kSize,
                                         tiling::radial_lookup(table.data(), kSize, rho)),
                  rho, 1e-4f);
    }
  }
  EXPECT_LT(std::sqrt(squares / inside), 3e-3);
  EXPECT_NEAR(radius_squares / kCount,
              2.0 * tiling::kGaussianDeviation * tiling::kGaussianDeviation, 2e-3);
  // T commutes with rotation: the turned slopes' T is the turned T, with the same table.
  const double angle = 1.1;
  std::vector<float> turned(kCount * 2);
  for (std::size_t i = 0; i < kCount; ++i) {
    turned[2 * i] =
        static_cast<float>(std::cos(angle) * slopes[2 * i] - std::sin(angle) * slopes[2 * i + 1]);
    turned[2 * i + 1] =
        static_cast<float>(std::sin(angle) * slopes[2 * i] + std::cos(angle) * slopes[2 * i + 1]);
  }
  std::vector<float> turned_gaussian(kCount * 2);
  std::vector<float> turned_table(kSize);
  tiling::gaussianise_radial(turned, turned_gaussian, turned_table);
  for (int k = 0; k < kSize; ++k) EXPECT_NEAR(turned_table[k], table[k], 1e-6f);
  // turn_slopes is that rotation in Gaussian space, and with a scale its magnitude follows:
  // |T^-1(turn(T(s)))| = scale |s| within the table's range.
  for (const float scale : {1.0f, 1.3f}) {
    const PatchTransform m{static_cast<float>(scale * std::cos(angle)),
                           static_cast<float>(-scale * std::sin(angle)),
                           static_cast<float>(scale * std::sin(angle)),
                           static_cast<float>(scale * std::cos(angle)), scale};
    for (std::size_t i = 0; i < kCount; i += 7) {
      float g[2] = {gaussian[2 * i], gaussian[2 * i + 1]};
      tiling::turn_slopes(m, table.data(), kSize, g);
      if (scale == 1.0f) {
        EXPECT_NEAR(g[0], turned_gaussian[2 * i], 1e-5f);
        EXPECT_NEAR(g[1], turned_gaussian[2 * i + 1], 1e-5f);
      }
      const float magnitude = std::hypot(slopes[2 * i], slopes[2 * i + 1]);
      if (scale * magnitude < 0.9f * table[kSize - 1] && magnitude > table[0]) {
        EXPECT_NEAR(tiling::radial_lookup(
                        table.data(), kSize,
                        std::hypot(g[0] - tiling::kGaussianMean, g[1] - tiling::kGaussianMean)),
                    scale * magnitude, 0.02f * scale * magnitude + 5e-3f);
      }
    }
  }
}

TEST(TilingControls, ANormalMapTurnsOnlyWhenThePatchesDo) {
  // Without rotation or scale jitter the slopes keep their principal axes (the files of
  // materials made before the radial group); with either, the radial group; its file round-trips
  // and its renders do not depend on threads, tiles or regions.
  const ImageF both = structured_exemplar(32, 3, 29);
  ImageF normal(32, 32, 3), height(32, 32, 1);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const double sx = 0.8 * (both.at(x, y, 0) - 0.5), sy = 0.8 * (both.at(x, y, 1) - 0.5);
      const double length = std::sqrt(1.0 + sx * sx + sy * sy);
      normal.at(x, y, 0) = static_cast<float>(0.5 - 0.5 * sx / length);
      normal.at(x, y, 1) = static_cast<float>(0.5 - 0.5 * sy / length);
      normal.at(x, y, 2) = static_cast<float>(0.5 + 0.5 / length);
      height.at(x, y, 0) = both.at(x, y, 2);
    }
  const auto material = [&](const ParamValues& params) {
    ParamValues all = params;
    all.try_emplace("iterations", 24);
    return analyze_material("tiling",
                            std::vector<MaterialMap>{{"normal", {}, normal.view(), "n.png"},
                                                     {"height", {}, height.view(), "h.png"}},
                            all, 3);
  };
  const auto slope_transform = [](const Model& model) {
    return tiling_of(model).layout().groups.front().transform;
  };
  EXPECT_EQ(slope_transform(material({})), GroupTransform::decorrelated);
  for (const ParamValues& params :
       {ParamValues{{"rotation", 90.0}}, ParamValues{{"scale_jitter", 0.3}}}) {
    const Model turned = material(params);
    EXPECT_EQ(slope_transform(turned), GroupTransform::radial);
    const Model round = deserialize_model(serialize_model(turned), "round.stx");
    EXPECT_EQ(serialize_model(round), serialize_model(turned));
    const Grid grid{{3.0, -7.0}, 1.5, 24, 20};
    EXPECT_TRUE(same_bytes(render_model(turned, grid, 5), render_model(round, grid, 5)));
    check_threads_tiles_and_regions(turned);
  }
}

void check_threads_tiles_and_regions(const Model& model) {
  const Grid grid{{-13.0, 4.0}, 0.75, 70, 50};
  const ImageF reference = render_model(model, grid, 3, 1, 64);
  EXPECT_TRUE(same_bytes(reference, render_model(model, grid, 3, 2, 16)));
  EXPECT_TRUE(same_bytes(reference, render_model(model, grid, 3, 2, 7)));
  Grid right = grid;
  right.first_pixel_x = 30;
  right.width = 40;
  const ImageF part = render_model(model, right, 3);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(part.at(x, y, c), reference.at(30 + x, y, c));
  EXPECT_FALSE(same_bytes(reference, render_model(model, grid, 4)));
}

TEST(TilingRender, FarFromTheOriginLooksLikeNearIt) {
  // Zoomed in 4x, neighbouring pixels differ: with float positions at p = 1e7 (resolution 1) four
  // neighbours would share one value.
  const Model model = analyse(structured_exemplar(40, 1, 15));
  for (const double origin : {0.0, 1e7}) {
    const ImageF image = render_model(model, Grid{{origin, origin}, 0.25, 64, 8}, 1);
    int equal = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 1; x < 64; ++x) equal += image.at(x, y, 0) == image.at(x - 1, y, 0);
    EXPECT_LT(equal, 20) << origin;
  }
}

TEST(TilingParams, RegistryDescribesTheMethod) {
  const MethodInfo& info = method_info("tiling");
  EXPECT_EQ(info.params.size(), kParams.size());
  EXPECT_THROW(resolve_params("tiling", ParamValues{{"transport", 2}}), std::invalid_argument);
  EXPECT_THROW(resolve_params("tiling", ParamValues{{"lut_size", 1}}), std::invalid_argument);
  EXPECT_EQ(resolve_params("tiling", ParamValues{}).at("lut_size"), 32);
}

}  // namespace
}  // namespace stochtex::tiling::tiling_test
