#include "model/model_colour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "core/srgb.hpp"

namespace stochtex {
namespace {

constexpr int kLegendrePoints = 48;
constexpr double kNormalReach = 8.0;  // Z beyond +-8 carries 1e-15 of the probability

// Nodes and weights of Gauss-Legendre quadrature on [-1, 1] of `kLegendrePoints` points: the
// roots of P_n by Newton's method from cos(pi (i + 3/4) / (n + 1/2)), each weight
// 2 / ((1 - x^2) P_n'(x)^2).
struct Legendre {
  std::array<double, kLegendrePoints> x{};
  std::array<double, kLegendrePoints> w{};
};

Legendre legendre_rule() {
  constexpr int n = kLegendrePoints;
  const double pi = std::acos(-1.0);
  Legendre rule;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p1 = 1.0;
      double p2 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
      }
      derivative = n * (z * p1 - p2) / (z * z - 1.0);
      const double step = p1 / derivative;
      z -= step;
      if (std::abs(step) < 1e-15) break;
    }
    rule.x[static_cast<std::size_t>(i)] = z;
    rule.w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * derivative * derivative);
  }
  return rule;
}

// E[srgb_decode(mean + deviation Z)], deviation > 0: the decoding is linear up to 0.04045, which
// integrates in closed form against the normal density, and a smooth power beyond, integrated by
// Gauss-Legendre quadrature over the Z that reach it (within +-kNormalReach).
double expectation(double mean, double deviation, const Legendre& rule) {
  constexpr double kKnee = 0.04045;
  const double inverse_sqrt_2pi = 1.0 / std::sqrt(2.0 * std::acos(-1.0));
  const double z0 = (kKnee - mean) / deviation;  // where the power begins
  const double below = 0.5 * std::erfc(-z0 / std::sqrt(2.0));
  const double density = inverse_sqrt_2pi * std::exp(-0.5 * z0 * z0);
  double sum = (mean * below - deviation * density) / 12.92;
  const double low = std::max(z0, -kNormalReach);
  if (low >= kNormalReach) return sum;
  const double half = 0.5 * (kNormalReach - low);
  const double centre = 0.5 * (kNormalReach + low);
  for (int q = 0; q < kLegendrePoints; ++q) {
    const double z = centre + half * rule.x[static_cast<std::size_t>(q)];
    sum += half * rule.w[static_cast<std::size_t>(q)] * inverse_sqrt_2pi * std::exp(-0.5 * z * z) *
           std::pow((mean + deviation * z + 0.055) / 1.055, 2.4);
  }
  return sum;
}

// (kExpectationDeviationCells + 1) x (kExpectationMeanCells + 1) values of D, row by deviation.
std::vector<float> make_expectation_table() {
  const Legendre rule = legendre_rule();
  std::vector<float> table(static_cast<std::size_t>(kExpectationDeviationCells + 1) *
                           (kExpectationMeanCells + 1));
  for (int s = 0; s <= kExpectationDeviationCells; ++s) {
    const double step = static_cast<double>(s) / kExpectationDeviationCells;
    const double deviation = kExpectationDeviationHigh * step * step;
    for (int m = 0; m <= kExpectationMeanCells; ++m) {
      const double mean =
          kExpectationMeanLow + static_cast<double>(kExpectationMeanHigh - kExpectationMeanLow) *
                                    m / kExpectationMeanCells;
      table[static_cast<std::size_t>(s) * (kExpectationMeanCells + 1) +
            static_cast<std::size_t>(m)] =
          static_cast<float>(s == 0 ? srgb_decode(mean) : expectation(mean, deviation, rule));
    }
  }
  return table;
}

}  // namespace

const std::vector<float>& expectation_table() {
  static const std::vector<float> table = make_expectation_table();
  return table;
}

bool ModelColour::decodes() const {
  return std::find(spaces.begin(), spaces.end(), ColourSpace::srgb) != spaces.end();
}

bool ModelColour::expects_any() const {
  for (std::size_t c = 0; c < spaces.size(); ++c)
    if (expects(static_cast<int>(c))) return true;
  return false;
}

std::vector<ColourSpace> image_channel_spaces(ColourSpace space, int channels) {
  std::vector<ColourSpace> spaces;
  for (int c = 0; c < channels; ++c)
    spaces.push_back(is_colour_channel(c, channels) ? space : ColourSpace::data);
  return spaces;
}

std::vector<ColourSpace> map_channel_spaces(std::span<const MapInfo> maps) {
  std::vector<ColourSpace> spaces;
  for (const MapInfo& map : maps) spaces.insert(spaces.end(), map.channels, map.colour_space);
  return spaces;
}

ColourSpace image_colour_space(const ModelColour& colour) {
  return colour.spaces.empty() ? ColourSpace::data : colour.spaces.front();
}

float expected_decoded(float mean, float deviation) noexcept {
  if (!(deviation > 0.0f)) return srgb_decode(mean);
  const std::vector<float>& table = expectation_table();
  const float u =
      (std::clamp(mean, kExpectationMeanLow, kExpectationMeanHigh) - kExpectationMeanLow) *
      (static_cast<float>(kExpectationMeanCells) / (kExpectationMeanHigh - kExpectationMeanLow));
  const float v = std::sqrt(std::min(deviation, kExpectationDeviationHigh) *
                            (1.0f / kExpectationDeviationHigh)) *
                  kExpectationDeviationCells;
  const int m = std::min(static_cast<int>(u), kExpectationMeanCells - 1);
  const int s = std::min(static_cast<int>(v), kExpectationDeviationCells - 1);
  const float fu = u - static_cast<float>(m);
  const float fv = v - static_cast<float>(s);
  const float* row = table.data() + static_cast<std::size_t>(s) * (kExpectationMeanCells + 1) + m;
  const float* next = row + (kExpectationMeanCells + 1);
  const float low = row[0] + fu * (row[1] - row[0]);
  const float high = next[0] + fu * (next[1] - next[0]);
  return low + fv * (high - low);
}

float removed_deviation(const ModelColour& colour, int channels, int channel,
                        double width) noexcept {
  if (colour.removed_deviation.empty() || !(width > 1.0)) return 0.0f;
  const double step =
      std::min(std::log2(width) * kRemovedStepsPerOctave, static_cast<double>(kRemovedSteps - 1));
  const int k = std::min(static_cast<int>(step), kRemovedSteps - 2);
  const auto t = static_cast<float>(step - k);
  const float* table = colour.removed_deviation.data() + channel;
  const float low = table[static_cast<std::size_t>(k) * channels];
  const float high = table[static_cast<std::size_t>(k + 1) * channels];
  return low + t * (high - low);
}

std::vector<Vec2d> spread_positions(std::size_t count, std::uint64_t seed) {
  std::vector<Vec2d> positions(count);
  std::uint64_t state = seed;
  const auto next = [&] {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 44);  // 0 to 2^20 - 1
  };
  for (Vec2d& p : positions) p = {next(), next()};
  return positions;
}

double footprint_area_width(const Footprint& footprint) noexcept {
  return std::sqrt(
      std::abs(footprint.dpdx.x * footprint.dpdy.y - footprint.dpdx.y * footprint.dpdy.x));
}

}  // namespace stochtex
