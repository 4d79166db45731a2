#include "methods/lrp/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/colour_statistics.hpp"
#include "core/hash.hpp"
#include "methods/lrp/params.hpp"
#include "methods/lrp/structure_analysis.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "spectral/kmeans.hpp"
#include "spectral/principal_components.hpp"
#include "spectral/torus_masks.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp {
namespace {

// Section 4.3: S is shrunk until the disc of radius delta around each kept frequency holds 75% of
// the window's spectral energy inside S ("the 75% threshold is empirical").
constexpr double kErosionEnergy = 0.75;
// The weakest frequencies holding this fraction of the energy belong to no stratum: keeping them
// would spread the last stratum over the whole plane (e.g. the empty plane around a ring target),
// making Delta_S tiny and leaking the stratum's energy everywhere. Their energy is given back to
// the strata in proportion, so the variance is kept.
constexpr double kNegligibleEnergy = 1e-3;
// Lloyd iterations of the k-means that breaks a stratum into sub-strata (spectral/kmeans.hpp).
constexpr int kKmeansIterations = 50;
constexpr int kMinWelchSize = 8;

struct Bin {
  int index = 0;  // ky * size + kx
  int sx = 0;     // signed frequency coordinates in bins, upper half-plane
  int sy = 0;
  double power = 0.0;  // power(k) + power(-k), or power(k) when k == -k
  bool self_paired = false;
};

// Our addition (docs/methods/lrp.md, parameter `amplitudes`): an amplitude per frequency, so that
// the expected spectrum of n_S follows the target inside the stratum instead of being flat at A_S
// (section 4.3 targets a constant A_S because "S contains homogeneous amplitudes", which only
// holds for many strata; with L = 4 the flat strata are the error floor). Each frequency f of
// the stratum, eroded or not, gives its power to the nearest sub-stratum centre (ties split
// equally), so sub-stratum k carries E_k; inside k the drawable frequencies share E_k in
// proportion to their own power. A frequency drawn with probability 1 / n_k at amplitude
// A_S w_f has expected power A_S^2 w_f^2 / n_k (in units where J_S cosines of weight 1 carry E_S),
// so w_f^2 = n_k J_S P'(f) / E_S with P'(f) = E_k P(f) / sum_{g in k} P(g). Weights of 1 give the
// paper's constant A_S back.
std::vector<std::vector<float>> frequency_weights(
    const std::vector<const Bin*>& stratum,
    const std::vector<std::vector<std::array<int, 2>>>& substrata,
    const std::vector<double>& pair_power, int size) {
  const std::size_t count = substrata.size();
  std::vector<std::array<double, 2>> centres(count, {0.0, 0.0});
  for (std::size_t k = 0; k < count; ++k) {
    for (const auto& point : substrata[k]) {
      centres[k][0] += point[0];
      centres[k][1] += point[1];
    }
    centres[k][0] /= double(substrata[k].size());
    centres[k][1] /= double(substrata[k].size());
  }
  double stratum_energy = 0.0;
  std::vector<double> energy(count, 0.0);
  std::vector<std::size_t> nearest;
  for (const Bin* bin : stratum) {
    stratum_energy += bin->power;
    double best = std::numeric_limits<double>::infinity();
    nearest.clear();
    for (std::size_t k = 0; k < count; ++k) {
      const double dx = bin->sx - centres[k][0];
      const double dy = bin->sy - centres[k][1];
      const double distance = dx * dx + dy * dy;
      if (distance < best) {
        best = distance;
        nearest.clear();
      }
      if (distance == best) nearest.push_back(k);
    }
    for (const std::size_t k : nearest) energy[k] += bin->power / double(nearest.size());
  }
  const auto power_of = [&](const std::array<int, 2>& point) {
    const int kx = point[0] < 0 ? point[0] + size : point[0];
    return pair_power[static_cast<std::size_t>(point[1]) * size + kx];
  };
  std::vector<std::vector<float>> weights(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto n = static_cast<double>(substrata[k].size());
    double drawable = 0.0;
    for (const auto& point : substrata[k]) drawable += power_of(point);
    for (const auto& point : substrata[k]) {
      if (!(stratum_energy > 0.0)) {
        weights[k].push_back(1.0f);
        continue;
      }
      const double share = drawable > 0.0 ? power_of(point) / drawable : 1.0 / n;
      weights[k].push_back(
          static_cast<float>(std::sqrt(n * double(count) * energy[k] * share / stratum_energy)));
    }
  }
  return weights;
}

// Drawn uniformly, a sub-stratum's shaped weights put its strongest frequencies into rare, heavy
// cosines: concrete_cement_512's strongest sub-stratum held DC at weight 6.0 beside 13 frequencies
// near 1, so one node in 14 carried a blob 6 times the others', seen zoomed out, where frequency
// clamping has removed the dense high frequencies around them, as isolated light and dark dots
// (docs/methods/lrp.md, "Dots, streaks and swirl"). Each frequency is therefore listed ceil(w_f^2 /
// mean w^2) times and its weight divided by the square root of its share of the list against
// 1 / n_k: the expected spectrum is the same, each cosine's amplitude stays within about
// sqrt(2) of the sub-stratum's mean, and the table at most doubles. The paper's constant A_S
// (weights of 1) is left as it is.
void draw_in_proportion_to_power(std::vector<std::vector<std::array<int, 2>>>& substrata,
                                 std::vector<std::vector<float>>& weights) {
  for (std::size_t k = 0; k < substrata.size(); ++k) {
    const auto& points = substrata[k];
    const auto& shaped = weights[k];
    double mean_power = 0.0;
    for (const float w : shaped) mean_power += double(w) * w;
    mean_power /= double(shaped.size());
    if (!(mean_power > 0.0)) continue;
    std::vector<std::size_t> copies(points.size());
    std::size_t listed = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double power = double(shaped[i]) * shaped[i];
      copies[i] = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(power / mean_power)));
      listed += copies[i];
    }
    std::vector<std::array<int, 2>> listed_points;
    std::vector<float> listed_weights;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double weight =
          shaped[i] * std::sqrt(double(listed) / (double(points.size()) * double(copies[i])));
      listed_points.insert(listed_points.end(), copies[i], points[i]);
      listed_weights.insert(listed_weights.end(), copies[i], static_cast<float>(weight));
    }
    substrata[k] = std::move(listed_points);
    weights[k] = std::move(listed_weights);
  }
}

void append_channel(LrpData& data, const std::vector<StratumPlan>& plans) {
  for (const StratumPlan& plan : plans) {
    data.strata_table.push_back(plan.sampling);
    for (std::size_t k = 0; k < plan.substrata.size(); ++k) {
      const auto& substratum = plan.substrata[k];
      data.substratum_first.push_back(static_cast<std::uint32_t>(data.frequencies.size() / 2));
      data.substratum_count.push_back(static_cast<std::uint32_t>(substratum.size()));
      for (const auto& bin : substratum) {
        data.frequencies.push_back(static_cast<float>(bin[0]));
        data.frequencies.push_back(static_cast<float>(bin[1]));
      }
      data.weights.insert(data.weights.end(), plan.weights[k].begin(), plan.weights[k].end());
    }
  }
}

void check_spectrum_size(int size) {
  if (size < kMinWelchSize || size % 2 != 0)
    throw std::invalid_argument("lrp: a target spectrum must be an even size of at least 8, not " +
                                std::to_string(size));
}

void check_spectrum(std::span<const double> power, int size) {
  check_spectrum_size(size);
  if (power.size() != static_cast<std::size_t>(size) * size)
    throw std::invalid_argument("lrp: the power spectrum does not have size x size values");
}

// The size x size target whose power at the signed frequency (f_x, f_y) (cycles per pixel) is
// shape(f_x, f_y), zero at DC, scaled to sum to `variance`.
template <typename Shape>
SpectrumTarget sampled_target(int size, double variance, Shape shape) {
  SpectrumTarget target{size, std::vector<double>(static_cast<std::size_t>(size) * size), 0.0};
  double sum = 0.0;
  for (int ky = 0; ky < size; ++ky)
    for (int kx = 0; kx < size; ++kx) {
      const double fx = double(kx > size / 2 ? kx - size : kx) / size;
      const double fy = double(ky > size / 2 ? ky - size : ky) / size;
      const double value = (kx == 0 && ky == 0) ? 0.0 : shape(fx, fy);
      target.power[static_cast<std::size_t>(ky) * size + kx] = value;
      sum += value;
    }
  for (double& value : target.power) value *= sum > 0.0 ? variance / sum : 0.0;
  return target;
}

}  // namespace

std::vector<double> deblur_welch(std::span<const double> power, int size) {
  check_spectrum(power, size);
  // Per axis, periodic: [1, -6, 26, -6, 1] / 16, two Jacobi sweeps of [1, 4, 1] / 6 x = y from
  // x = y. Its gain is the inverse's 1 / (2/3 + cos(w) / 3) at w = 0 and pi / 2, 2.5 instead of 3
  // at w = pi (bin-to-bin speckle, which the exact inverse amplified: docs/methods/lrp.md).
  constexpr std::array<double, 5> taps{1.0 / 16, -6.0 / 16, 26.0 / 16, -6.0 / 16, 1.0 / 16};
  const auto at = [size](int x, int y) { return static_cast<std::size_t>(y) * size + x; };
  // One periodic pass of the taps along x or along y.
  const auto pass = [&](std::span<const double> in, bool along_x) {
    std::vector<double> out(in.size(), 0.0);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int t = -2; t <= 2; ++t)
          out[at(x, y)] +=
              taps[static_cast<std::size_t>(t + 2)] *
              in[along_x ? at((x + t + size) % size, y) : at(x, (y + t + size) % size)];
    return out;
  };
  std::vector<double> result = pass(pass(power, true), false);
  for (double& value : result) value = std::max(0.0, value);
  result[0] = 0.0;
  return result;
}

int welch_size(int width, int height) {
  const int side = std::min(width, height);
  int size = 1;
  while (size * 2 < side) size *= 2;
  return size;
}

double window_energy_radius(double fraction) {
  // W-hat(rho) = 2 pi int_0^1.5 r w(r) J_0(2 pi rho r) dr (Simpson, 256 intervals), and the
  // energy inside radius rho, int_0^rho 2 pi t W-hat(t)^2 dt (trapezoids of 1/1000), is compared
  // with the total 2 pi int r w^2 (Parseval).
  constexpr int intervals = 256;
  const double h = kWindowRadius / intervals;
  std::vector<double> weighted(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    const double r = i * h;
    const double simpson = (i == 0 || i == intervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    weighted[static_cast<std::size_t>(i)] = simpson * h / 3.0 * r * kaiser_bessel_window(r);
  }
  const auto transform = [&](double rho) {
    double sum = 0.0;
    for (int i = 0; i <= intervals; ++i)
      sum += weighted[static_cast<std::size_t>(i)] *
             std::cyl_bessel_j(0.0, 2.0 * std::numbers::pi * rho * i * h);
    return 2.0 * std::numbers::pi * sum;
  };
  const double total = 2.0 * std::numbers::pi * window_radial_energy();
  constexpr double step = 1e-3;
  double energy = 0.0;
  double previous = 0.0;  // rho W-hat(rho)^2 at the previous step
  for (int i = 1; i < 20000; ++i) {
    const double rho = i * step;
    const double value = transform(rho);
    const double current = rho * value * value;
    const double next = energy + std::numbers::pi * step * (previous + current);
    if (next >= fraction * total)
      return rho - step + step * (fraction * total - energy) / (next - energy);
    energy = next;
    previous = current;
  }
  throw Error(ErrorCode::numerical, "lrp: the window's spectral energy did not converge");
}

std::vector<StratumPlan> plan_strata(std::span<const double> power, int size, int strata,
                                     int cosines, bool shaped, SpacingRule spacing,
                                     std::uint32_t key) {
  check_spectrum(power, size);
  if (strata < 1 || cosines < 1)
    throw std::invalid_argument("lrp: strata and cosines must be positive");
  const auto at = [size](int x, int y) { return static_cast<std::size_t>(y) * size + x; };

  // The upper half-plane (section 4.3: "the spectrum is symmetric"): bin k is kept when its index
  // is not above that of -k, with the power of both.
  std::vector<Bin> bins;
  std::vector<double> pair_power(power.size(), 0.0);
  double total = 0.0;
  for (int ky = 0; ky < size; ++ky)
    for (int kx = 0; kx < size; ++kx) {
      const int nx = (size - kx) % size;
      const int ny = (size - ky) % size;
      const auto index = at(kx, ky);
      const auto negative = at(nx, ny);
      if (index == 0 || index > negative) continue;
      Bin bin;
      bin.index = static_cast<int>(index);
      bin.self_paired = index == negative;
      bin.power = bin.self_paired ? power[index] : power[index] + power[negative];
      if (!(bin.power >= 0.0) || !std::isfinite(bin.power))
        throw Error(ErrorCode::numerical,
                    "lrp: the power spectrum has a negative or non-finite value");
      // Signed coordinates in the upper half-plane, x in (-size/2, size/2].
      bin.sx = kx > size / 2 ? kx - size : kx;
      bin.sy = ky;
      pair_power[index] = bin.power;
      total += bin.power;
      bins.push_back(bin);
    }

  // Section 4.2: strata are intervals of the power, of equal energy. Sorting by decreasing power
  // and cutting the cumulated energy at multiples of E / L gives exactly those intervals; a single
  // frequency above E / L fills its stratum alone and the cut moves on.
  std::stable_sort(bins.begin(), bins.end(),
                   [](const Bin& a, const Bin& b) { return a.power > b.power; });
  std::size_t kept = bins.size();
  double tail = 0.0;
  while (kept > static_cast<std::size_t>(strata) &&
         tail + bins[kept - 1].power < kNegligibleEnergy * total)
    tail += bins[--kept].power;
  const double kept_energy = total - tail;
  const double energy_scale = kept_energy > 0.0 ? total / kept_energy : 0.0;
  const auto stratum_count = std::min<std::size_t>(static_cast<std::size_t>(strata), kept);

  std::vector<StratumPlan> plans(static_cast<std::size_t>(strata));
  std::vector<std::vector<const Bin*>> members(static_cast<std::size_t>(strata));
  {
    std::size_t s = 0;
    double cumulated = 0.0;
    for (std::size_t i = 0; i < kept; ++i) {
      members[s].push_back(&bins[i]);
      cumulated += bins[i].power;
      const std::size_t bins_left = kept - i - 1;
      const std::size_t strata_left = stratum_count - s - 1;
      if (strata_left > 0 && (cumulated >= double(s + 1) * kept_energy / double(stratum_count) ||
                              bins_left == strata_left))
        ++s;
    }
  }

  // With shaped amplitudes, DC's power (variance below the estimate's resolution, see analyze)
  // joins the strongest stratum as one more frequency: its weight carries that power, and a
  // cosine of frequency 0 with a random phase is a random offset per lattice node.
  Bin dc;
  dc.self_paired = true;
  dc.power = power[0];
  if (shaped && dc.power > 0.0 && std::isfinite(dc.power) && stratum_count > 0) {
    pair_power[0] = dc.power;
    auto& strongest = members[0];
    strongest.insert(std::find_if(strongest.begin(), strongest.end(),
                                  [&](const Bin* bin) { return bin->power < dc.power; }),
                     &dc);
  }
  const double radial_energy = window_radial_energy();
  const double unit_radius = window_energy_radius(kErosionEnergy);
  std::vector<char> inside(static_cast<std::size_t>(size) * size);
  const auto mark = [&](const Bin& bin) {
    const int kx = bin.index % size;
    const int ky = bin.index / size;
    inside[at(kx, ky)] = 1;
    inside[at((size - kx) % size, (size - ky) % size)] = 1;
  };
  // With shaped amplitudes, the erosion keeps energy inside the target's support (the union of
  // the strata) rather than inside each stratum: a neighbouring stratum's power is close to this
  // one's, so leaking into it is what the window does to any spectrum, while eroding each
  // stratum's boundary concentrates the draws on a few inner frequencies (docs/methods/lrp.md).
  // The support is closed before it is eroded: DC (zero in the estimate only because each crop's
  // mean is removed) and the isolated weakest frequencies left out of every stratum (speckle of a
  // noisy Welch estimate: about 4% of the bins of a flat one) are holes, not gaps of the target,
  // and eroding around each of them swept out nearly the whole plane (docs/methods/lrp.md,
  // issue 20). A closing by delta fills the holes narrower than 2 delta and keeps the outside of
  // a ring target: `support_gap_squared` is each bin's squared distance to the support.
  std::vector<double> support_gap_squared;
  if (shaped) {
    for (std::size_t i = 0; i < kept; ++i) mark(bins[i]);
    inside[0] = 1;
    for (char& bin : inside) bin = bin ? 0 : 1;
    support_gap_squared = periodic_distance_squared(inside, size);
  }
  for (int s = 0; s < strata; ++s) {
    StratumPlan& plan = plans[static_cast<std::size_t>(s)];
    const auto& stratum = members[static_cast<std::size_t>(s)];
    // J_S = J / L, the remainder going to the first strata, at least one cosine each.
    plan.sampling.cosines = std::max(1, cosines / strata + (s < cosines % strata ? 1 : 0));
    const auto j_s = static_cast<double>(plan.sampling.cosines);
    if (stratum.empty()) {
      // Fewer non-negligible frequencies than strata (a pure tone, a zero spectrum): the stratum
      // is silent; its sub-strata point at the strongest frequency (or at 1/size when none).
      const std::array<int, 2> any =
          bins.empty() ? std::array<int, 2>{1, 0} : std::array<int, 2>{bins[0].sx, bins[0].sy};
      plan.sampling.spacing = static_cast<float>(size);
      plan.substrata.assign(static_cast<std::size_t>(plan.sampling.cosines), {any});
      plan.weights.assign(plan.substrata.size(), {1.0f});
      continue;
    }
    for (const Bin* bin : stratum) {
      plan.energy += bin->power * (bin == &dc ? 1.0 : energy_scale);
      plan.bins += bin->self_paired ? 1 : 2;
    }
    plan.highest_power = stratum.front()->power;
    plan.lowest_power = stratum.back()->power;
    // Delta_S = T sqrt(J_S) / sqrt(2 |S|) (section 4.3): J_S spectral footprints of radius
    // 1 / Delta_S cover the stratum's area |S| / T^2 "with a slight overlap", in fact 2 pi times.
    // Both of our changes (docs/methods/lrp.md) widen the spacing, which a sample does not pay
    // for (9 J_S cosines whatever Delta_S), only fewer nodes per area: the factor `widen` (1 by
    // default) narrows every footprint, which blurs narrow spectra such as a brushed metal's line,
    // since each node draws its own frequency and the draws, not the footprints, cover the
    // stratum; the floor `spacing` keeps a wide stratum of the weak, high frequencies (Delta_S of
    // 3-6 pixels, a footprint of a sixth of the plane) from leaking far outside the target.
    plan.sampling.spacing = static_cast<float>(
        std::max(spacing.floor, spacing.widen * size * std::sqrt(j_s / (2.0 * plan.bins))));
    // Equation (3) with the energy per unit area: the variance of n_S, averaged over a lattice
    // cell, is A_S^2 J_S / 2 * 2 pi int r w^2 (the mean of sum_i w^2(|x - x_i| / Delta_S)); the
    // paper's Delta_S^2 converts its per-window energy and cancels here.
    plan.sampling.amplitude =
        static_cast<float>(std::sqrt(plan.energy / (j_s * std::numbers::pi * radial_energy)));

    // Erosion (section 4.3) by delta = unit_radius / Delta_S cycles per pixel, in bins.
    plan.erosion_radius = unit_radius * size / plan.sampling.spacing;
    std::vector<double> distance_squared;
    if (shaped) {
      // Depth in the closed support: the distance to the outside of the support dilated by delta,
      // less delta.
      const double reach = plan.erosion_radius * plan.erosion_radius;
      for (std::size_t i = 0; i < inside.size(); ++i)
        inside[i] = support_gap_squared[i] <= reach ? 1 : 0;
      distance_squared = periodic_distance_squared(inside, size);
      for (double& value : distance_squared) {
        const double depth = std::max(0.0, std::sqrt(value) - plan.erosion_radius);
        value = depth * depth;
      }
    }
    std::fill(inside.begin(), inside.end(), char{0});
    for (const Bin* bin : stratum) mark(*bin);
    if (!shaped) distance_squared = periodic_distance_squared(inside, size);
    std::vector<std::pair<double, const Bin*>> by_depth;
    for (const Bin* bin : stratum)
      by_depth.emplace_back(std::sqrt(distance_squared[static_cast<std::size_t>(bin->index)]), bin);
    std::stable_sort(by_depth.begin(), by_depth.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    // Keep the frequencies deeper than delta inside S, "modified so that strata smaller than
    // delta are not completely swept out": our reading is per connected part of S (8-connected on
    // the torus). A part thinner than delta keeps its deepest frequencies instead of vanishing, so
    // the speckled strata of a noisy Welch estimate keep their coverage; then, when fewer than J_S
    // frequencies remain in all, the J_S deepest are kept.
    const std::vector<int> part = connected_parts(inside, size);
    std::vector<double> part_depth(static_cast<std::size_t>(size) * size, 0.0);
    for (const auto& [depth, bin] : by_depth) {
      double& deepest =
          part_depth[static_cast<std::size_t>(part[static_cast<std::size_t>(bin->index)])];
      deepest = std::max(deepest, depth);
    }
    const std::size_t needed = std::min(by_depth.size(), static_cast<std::size_t>(j_s));
    std::vector<char> kept_bin(by_depth.size(), 0);
    std::size_t keep_count = 0;
    for (std::size_t i = 0; i < by_depth.size(); ++i) {
      const auto& [depth, bin] = by_depth[i];
      const double deepest =
          part_depth[static_cast<std::size_t>(part[static_cast<std::size_t>(bin->index)])];
      if (depth > plan.erosion_radius || (deepest <= plan.erosion_radius && depth == deepest)) {
        kept_bin[i] = 1;
        ++keep_count;
        plan.eroded_radius = std::max(plan.eroded_radius, std::min(depth, plan.erosion_radius));
      }
    }
    for (std::size_t i = 0; i < by_depth.size() && keep_count < needed; ++i)
      if (!kept_bin[i]) {
        kept_bin[i] = 1;
        ++keep_count;
      }
    std::vector<std::array<int, 2>> points;
    for (std::size_t i = 0; i < by_depth.size(); ++i)
      if (kept_bin[i]) points.push_back({by_depth[i].second->sx, by_depth[i].second->sy});
    // k-means with a seeded random initialisation (section 4.3: "k-means with random seeding"), one
    // stream per stratum. With fewer frequencies than cosines each cosine gets one, cyclically
    // (duplicates carry independent phases, so they still add power).
    CounterRng rng(cell_key(s, 0, key, Stream::analysis));
    plan.substrata = kmeans(points, plan.sampling.cosines, kKmeansIterations, rng);
    if (shaped) {
      plan.weights = frequency_weights(stratum, plan.substrata, pair_power, size);
      draw_in_proportion_to_power(plan.substrata, plan.weights);
    } else {
      plan.weights.clear();
      for (const auto& substratum : plan.substrata)
        plan.weights.emplace_back(substratum.size(), 1.0f);
    }
  }
  return plans;
}

SpectrumTarget ring_spectrum(int size, double radius, double width, double variance) {
  check_spectrum_size(size);
  if (!(radius >= 0.0 && radius <= 0.5) || !(width > 0.0) || !(variance >= 0.0))
    throw std::invalid_argument("lrp: a ring needs 0 <= radius <= 1/2, width > 0, variance >= 0");
  return sampled_target(size, variance, [&](double fx, double fy) {
    const double offset = (std::hypot(fx, fy) - radius) / width;
    return std::exp(-0.5 * offset * offset);
  });
}

SpectrumTarget gaussian_spectrum(int size, double centre_x, double centre_y, double along,
                                 double across, double variance) {
  check_spectrum_size(size);
  if (!(along > 0.0) || !(across > 0.0) || !(variance >= 0.0))
    throw std::invalid_argument("lrp: a Gaussian target needs positive widths and variance >= 0");
  const double length = std::hypot(centre_x, centre_y);
  const double ux = length > 0.0 ? centre_x / length : 1.0;
  const double uy = length > 0.0 ? centre_y / length : 0.0;
  return sampled_target(size, variance, [&](double fx, double fy) {
    double value = 0.0;
    for (const double sign : {1.0, -1.0}) {
      const double dx = fx - sign * centre_x;
      const double dy = fy - sign * centre_y;
      const double a = (dx * ux + dy * uy) / along;
      const double b = (-dx * uy + dy * ux) / across;
      value += std::exp(-0.5 * (a * a + b * b));
    }
    return value;
  });
}

LrpModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed) {
  const int width = exemplar.width;
  const int height = exemplar.height;
  const int channels = exemplar.channels;
  const int size = welch_size(width, height);
  if (size < kMinWelchSize)
    throw Error(ErrorCode::invalid_input,
                "lrp needs an exemplar of at least 9x9 pixels (its Welch crops are the largest "
                "power of two below its side, at least 8), not " +
                    std::to_string(width) + "x" + std::to_string(height));
  const int strata = params.strata;
  const int cosines = params.cosines;
  const bool shaped = params.amplitudes;
  // Section 5.3: J_R = rJ cosines for the fixed-phase region R, (1 - r)J for the random strata.
  const double ratio = params.ratio;
  const int fixed_cosines = structure_cosines(ratio, cosines);
  std::vector<FixedPhaseRegion> regions;
  std::vector<double> turbulence_power;

  // Colour (section 6 defers it to a decorrelated space): PCA of the colour channels, so the
  // per-channel noises, independent, keep the exemplar's colour covariance. Alpha (channel 2 of
  // 2 or 4 of 4) is its own channel and never mixes with colour (docs/design.md §1). A material
  // (more than 4 channels, its maps side by side) has no alpha: one PCA over all its channels, so
  // the zero-lag covariance between maps is kept (docs/methods/lrp.md, "Materials").
  const int colour_channels = channels > 4 ? channels : (channels >= 3 ? 3 : 1);
  const std::vector<double> mean = channel_means(exemplar);
  std::vector<double> covariance = channel_covariance(exemplar, mean);
  // Block-diagonal, so the eigenvectors do not mix colour and alpha.
  for (int i = 0; i < channels; ++i)
    for (int j = 0; j < channels; ++j)
      if ((i < colour_channels) != (j < colour_channels))
        covariance[static_cast<std::size_t>(i) * channels + j] = 0.0;
  const PrincipalComponents components = principal_components(covariance, channels);
  const auto basis = [&](int c, int k) {
    return components.axes[static_cast<std::size_t>(c) * channels + k];
  };
  const Eigen::VectorXd variances =
      Eigen::Map<const Eigen::VectorXd>(components.variances.data(), channels).cwiseMax(0.0);

  LrpData data;
  data.channels = channels;
  data.strata = strata;
  data.normalise_envelope = params.envelope;
  for (int c = 0; c < channels; ++c) {
    data.mean.push_back(static_cast<float>(mean[c]));
    for (int k = 0; k < channels; ++k) data.colour_basis.push_back(static_cast<float>(basis(c, k)));
  }
  ImageF component(width, height, 1);
  for (int k = 0; k < channels; ++k) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        double value = 0.0;
        for (int c = 0; c < channels; ++c) value += basis(c, k) * (exemplar.at(x, y, c) - mean[c]);
        component.at(x, y, 0) = static_cast<float>(value);
      }
    // Section 4.4: Welch's power spectrum on crops of side T; the DC term is the mean, not noise.
    std::vector<double> power = welch_power_spectrum(component.view(), size);
    power[0] = 0.0;
    const double welch_sum = std::accumulate(power.begin(), power.end(), 0.0);
    // Our `deblur` (docs/methods/lrp.md): each bin becomes a frequency of the model, so the
    // window's blur already in the estimate would show twice in a render's own estimate.
    if (params.deblur) power = deblur_welch(power, size);
    const double sum = std::accumulate(power.begin(), power.end(), 0.0);
    // Welch's estimate has the variance of the Hann-weighted pixels; the noise gets the
    // component's exact variance. A component without variance (grey exemplar stored as RGB)
    // gets a zero spectrum, hence silent strata.
    const bool silent = !(sum > 0.0 && variances[k] > 1e-12 * variances.sum());
    // The estimate's own variance is its mean power (metrics.hpp), taken before `deblur`, which
    // keeps the sum but for the values it clamps. With shaped amplitudes, the
    // variance it misses (below its resolution 1 / T, removed with each crop's mean: two thirds of
    // wood_planks_256's) goes to DC, which plan_strata gives to the strongest stratum, instead of
    // raising every frequency (docs/methods/lrp.md, issue 20).
    const double estimated = welch_sum / (static_cast<double>(size) * size);
    // Not with fixed phases: R is measured at the estimate's resolution too (section 5.1), and at
    // r = 1 the random strata must stay silent.
    const bool below_resolution =
        shaped && fixed_cosines == 0 && !silent && variances[k] > estimated;
    const double scale = silent ? 0.0 : below_resolution ? estimated / sum : variances[k] / sum;
    for (double& value : power) value *= scale;
    if (below_resolution) power[0] = variances[k] - estimated;
    if (fixed_cosines > 0) {
      // Turbulence follows the whole spectrum of the strongest channel (section 5.2).
      if (variances[k] == variances.maxCoeff()) turbulence_power = power;
      regions.push_back(fixed_phase_region(component.view(), size, ratio));
      remove_region(power, regions.back());
    }
    append_channel(data, plan_strata(power, size, strata, std::max(1, cosines - fixed_cosines),
                                     shaped, {params.widen, params.spacing},
                                     cell_key(channel_stream(k), 0, seed, Stream::analysis)));
  }
  if (fixed_cosines > 0) {
    data.structure = reduce_structure(regions, fixed_cosines, data.colour_basis);
    data.structure.placement = params.placement;
    plan_turbulence(turbulence_power, size, params.turbulence,
                    cell_key(kTurbulenceStreamBase, 0, seed, Stream::analysis), data.structure);
  }
  // Frequencies were stored in bins; the model holds cycles per pixel.
  for (float& f : data.frequencies) f /= static_cast<float>(size);
  return LrpModel(std::move(data));
}

LrpModel analyze_spectrum(const SpectrumTarget& target, const Params& params, std::uint32_t seed) {
  check_spectrum_size(target.size);
  if (!std::isfinite(target.mean))
    throw std::invalid_argument("lrp: the target's mean must be finite");
  if (params.ratio > 0.0)
    throw std::invalid_argument(
        "lrp: a continuous target has no phases to keep; the energy ratio r needs an exemplar");
  LrpData data;
  data.channels = 1;
  data.strata = params.strata;
  data.normalise_envelope = params.envelope;
  data.mean = {static_cast<float>(target.mean)};
  data.colour_basis = {1.0f};
  append_channel(
      data, plan_strata(target.power, target.size, data.strata, params.cosines, params.amplitudes,
                        {params.widen, params.spacing}, cell_key(0, 0, seed, Stream::analysis)));
  for (float& f : data.frequencies) f /= static_cast<float>(target.size);
  return LrpModel(std::move(data));
}

Model spectrum_model(const SpectrumTarget& target, const ParamValues& params, std::uint32_t seed) {
  ParamValues resolved = resolve_params(LrpModel::kMethodName, params);
  LrpModel model = analyze_spectrum(target, params_from_values(kFields, resolved), seed);
  return assemble_model(std::move(resolved), MethodModel(std::move(model)), {}, {});
}

}  // namespace stochtex::lrp
