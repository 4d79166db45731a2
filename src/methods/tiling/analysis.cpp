#include "methods/tiling/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

#include "core/colour_statistics.hpp"
#include "core/hash.hpp"
#include "hwy/contrib/sort/vqsort.h"
#include "methods/tiling/evaluate.hpp"
#include "metrics/metrics.hpp"
#include "metrics/structure.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"
#include "spectral/principal_components.hpp"

namespace stochtex::tiling {
namespace {

// make_tileable=auto leaves an exemplar with more than this share of its power in spectral peaks
// (spectral_peak_fraction) as it is. Averaged spectral error over 4 seeds, as is -> made tileable
// (scripts/make_tileable.sh): plaid_fabric_256 (peaks 0.78) 0.414 -> 0.534 and wool_knit_blue_256
// (0.29) 0.314 -> 0.339 rise; wood_planks_256 (0.175, its grain's ridge) 0.986 -> 0.905 falls, and
// bricks_stone_wall_512 (0.127) 0.212 -> 0.244 rises but loses its straight seams through bricks.
constexpr double kRepeatedPatternPeaks = 0.25;

// Interleaved pixel values (width x height x channels, row-major) seen as an image.
ImageView<const float> interleaved(const std::vector<float>& values, int width, int height,
                                   int channels) {
  return {values.data(), width, height, channels, static_cast<std::ptrdiff_t>(width) * channels};
}

// An order-preserving uint32 image of a float (-0 before +0), and its inverse.
std::uint32_t sortable_bits(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return (bits & 0x80000000u) != 0u ? ~bits : (bits | 0x80000000u);
}

float from_sortable_bits(std::uint32_t bits) {
  bits = (bits & 0x80000000u) != 0u ? (bits & 0x7fffffffu) : ~bits;
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// Sort keys of (value, index) pairs: sortable_bits of the value in the high half, the index in the
// low half.
std::uint64_t sort_key(float value, std::size_t index) {
  return (static_cast<std::uint64_t>(sortable_bits(value)) << 32) |
         static_cast<std::uint64_t>(index);
}

// Indices of `values` in ascending order (ties by index), as the keys of sort_key sorted. The keys
// are distinct, so every sort puts them in the same order: the sliced transport sorts millions of
// projections with Highway's vectorised quicksort (VQSort, docs/methods/tiling.md), or with a
// 4-pass LSD radix sort where VQSort has no 64-bit lanes.
void argsort(std::span<const float> values, std::vector<std::uint64_t>& keys,
             std::vector<std::uint64_t>& scratch) {
  const std::size_t count = values.size();
  keys.resize(count);
  for (std::size_t i = 0; i < count; ++i) keys[i] = sort_key(values[i], i);
  if (hwy::Sorter::HaveFloat64()) {
    hwy::Sorter()(keys.data(), count, hwy::SortAscending());
    return;
  }
  scratch.resize(count);
  for (int pass = 0; pass < 4; ++pass) {
    const int shift = 32 + 8 * pass;
    std::size_t offsets[257] = {};
    for (const std::uint64_t key : keys) ++offsets[((key >> shift) & 0xffu) + 1];
    for (int b = 0; b < 256; ++b) offsets[b + 1] += offsets[b];
    for (const std::uint64_t key : keys) scratch[offsets[(key >> shift) & 0xffu]++] = key;
    keys.swap(scratch);
  }
}

// `values` in ascending order (-0 before +0), as argsort orders them, through their sortable_bits:
// for the target side of a transport, which needs the values and not their indices.
void sort_values(std::span<const float> values, std::vector<std::uint32_t>& keys,
                 std::span<float> sorted) {
  keys.resize(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) keys[i] = sortable_bits(values[i]);
  if (hwy::Sorter::HaveFloat64())
    hwy::Sorter()(keys.data(), keys.size(), hwy::SortAscending());
  else
    std::sort(keys.begin(), keys.end());
  for (std::size_t k = 0; k < keys.size(); ++k) sorted[k] = from_sortable_bits(keys[k]);
}

std::size_t index_of(std::uint64_t key) {
  return static_cast<std::size_t>(key & 0xffffffffu);
}

// A standard normal draw by Box-Muller from two counter-based uniforms, each its own statement.
double standard_normal(CounterRng& rng) {
  const double u1 = (static_cast<double>(rng.next() >> 8u) + 0.5) / 16777216.0;
  const double u2 = (static_cast<double>(rng.next() >> 8u) + 0.5) / 16777216.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// A random orthonormal basis of R^dims (Gram-Schmidt on a Gaussian matrix, uniform on O(dims)),
// rows interleaved.
std::vector<double> random_basis(int dims, std::uint32_t key) {
  CounterRng rng(key);
  std::vector<double> basis(static_cast<std::size_t>(dims) * dims);
  for (int row = 0; row < dims; ++row) {
    double* v = &basis[static_cast<std::size_t>(row) * dims];
    for (;;) {
      for (int c = 0; c < dims; ++c) v[c] = standard_normal(rng);
      for (int previous = 0; previous < row; ++previous) {
        const double* u = &basis[static_cast<std::size_t>(previous) * dims];
        double dot = 0.0;
        for (int c = 0; c < dims; ++c) dot += u[c] * v[c];
        for (int c = 0; c < dims; ++c) v[c] -= dot * u[c];
      }
      double norm = 0.0;
      for (int c = 0; c < dims; ++c) norm += v[c] * v[c];
      norm = std::sqrt(norm);
      if (norm > 1e-6) {
        for (int c = 0; c < dims; ++c) v[c] /= norm;
        break;
      }
    }
  }
  return basis;
}

// The target side of a sliced transport: fills `quantiles` (ascending) with the target's projection
// on `direction` at the levels (k + 1/2) / quantiles.size().
// Full steps (the 1-D optimal transport along each direction, Pitie et al.'s iterated
// distribution transfer) converge in a few iterations but along a displacement measured 15%
// costlier than the exact optimal assignment (tests/unit/tiling_test.cpp). Relaxed steps of 1/4
// follow the sliced-Wasserstein gradient flow instead (Bonneel et al. 2015), whose displacement is
// within ~2% of the optimum; the last iterations take full steps so the points land on the target.
constexpr double kRelaxedStep = 0.25;
constexpr int kFullSteps = 8;

using TargetQuantiles = std::function<void(const double* direction, std::span<float> quantiles)>;

std::vector<float> sliced_transport(std::span<const float> source, int dims, int iterations,
                                    std::uint32_t seed, const TargetQuantiles& target) {
  std::vector<float> points(source.begin(), source.end());
  const std::size_t count = points.size() / static_cast<std::size_t>(dims);
  std::vector<float> projection(count);
  std::vector<float> quantiles(count);
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> scratch;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const double step_size = iteration < iterations - kFullSteps ? kRelaxedStep : 1.0;
    const std::vector<double> basis =
        random_basis(dims, cell_key(iteration, 0, seed, Stream::analysis));
    for (int row = 0; row < dims; ++row) {
      const double* direction = &basis[static_cast<std::size_t>(row) * dims];
      for (std::size_t i = 0; i < count; ++i) {
        double dot = 0.0;
        for (int c = 0; c < dims; ++c) dot += direction[c] * points[i * dims + c];
        projection[i] = static_cast<float>(dot);
      }
      argsort(projection, keys, scratch);
      target(direction, quantiles);
      // The 1-D optimal transport along the direction is the monotone rearrangement: the point
      // of rank k moves to the target quantile of rank k.
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t i = index_of(keys[k]);
        const double step = step_size * (static_cast<double>(quantiles[k]) - projection[i]);
        for (int c = 0; c < dims; ++c)
          points[i * dims + c] = static_cast<float>(points[i * dims + c] + step * direction[c]);
      }
    }
  }
  return points;
}

// Phi^-1((k + 1/2) / count) for k < count: the exact quantiles of a standard normal sample of
// `count` equal-probability strata.
std::vector<float> standard_normal_quantiles(std::size_t count) {
  std::vector<float> quantiles(count);
  for (std::size_t k = 0; k < count; ++k)
    quantiles[k] = static_cast<float>(
        normal_quantile((static_cast<double>(k) + 0.5) / static_cast<double>(count)));
  return quantiles;
}

// The quantile of sorted values at level t in (0, 1), by linear interpolation between ranks.
float sorted_quantile(std::span<const float> sorted, double level) {
  const double position = level * static_cast<double>(sorted.size()) - 0.5;
  if (position <= 0.0) return sorted.front();
  const auto last = static_cast<double>(sorted.size() - 1);
  if (position >= last) return sorted.back();
  const auto lower = static_cast<std::size_t>(position);
  const auto t = static_cast<float>(position - static_cast<double>(lower));
  return sorted[lower] + t * (sorted[lower + 1] - sorted[lower]);
}

// Section 5.3 (figure 9): the tiles must capture all the exemplar's statistics, so variations of
// periods longer than a tile are removed: x - lowpass(x) + mean(x), with a periodic Gaussian
// low-pass of deviation `deviation` pixels (its response is exp(-2 pi^2 deviation^2 f^2): with
// deviation = edge / pi, 88% of a period of 4 edges goes, 14% of a period of one edge). The
// first `colour_channels` channels are filtered; alpha is left as is.
void remove_large_scales(std::vector<float>& pixels, int width, int height, int channels,
                         int colour_channels, double deviation) {
  std::vector<float> low(pixels);
  std::vector<float> scratch(pixels.size());
  const auto wrap = [](int i, int size) { return ((i % size) + size) % size; };
  for (int pass = 0; pass < 2; ++pass) {
    // Truncated at 3 deviations or half a period, whichever is shorter: a wider kernel would wrap
    // onto itself, and its periodic response is then almost flat anyway.
    const int size = pass == 0 ? width : height;
    const int radius = std::min(static_cast<int>(std::ceil(3.0 * deviation)), size / 2);
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    double total = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      kernel[k + radius] = std::exp(-0.5 * k * k / (deviation * deviation));
      total += kernel[k + radius];
    }
    for (double& k : kernel) k /= total;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < colour_channels; ++c) {
          double sum = 0.0;
          for (int k = -radius; k <= radius; ++k) {
            const int sx = pass == 0 ? wrap(x + k, width) : x;
            const int sy = pass == 0 ? y : wrap(y + k, height);
            sum += kernel[k + radius] *
                   low[(static_cast<std::size_t>(sy) * width + sx) * channels + c];
          }
          scratch[(static_cast<std::size_t>(y) * width + x) * channels + c] =
              static_cast<float>(sum);
        }
    for (std::size_t i = 0; i < low.size(); ++i)
      if (static_cast<int>(i % static_cast<std::size_t>(channels)) < colour_channels)
        low[i] = scratch[i];
  }
  const std::size_t count = static_cast<std::size_t>(width) * height;
  const std::vector<double> mean = channel_means(interleaved(low, width, height, channels));
  for (int c = 0; c < colour_channels; ++c)
    for (std::size_t i = 0; i < count; ++i)
      pixels[i * channels + c] =
          static_cast<float>(pixels[i * channels + c] - low[i * channels + c] + mean[c]);
}

}  // namespace

std::vector<float> sliced_transport_to_points(std::span<const float> source,
                                              std::span<const float> target, int dims,
                                              int iterations, std::uint32_t seed) {
  const std::size_t target_count = target.size() / static_cast<std::size_t>(dims);
  std::vector<float> projection(target_count);
  std::vector<float> sorted(target_count);
  std::vector<std::uint32_t> keys;
  return sliced_transport(
      source, dims, iterations, seed, [&](const double* direction, std::span<float> quantiles) {
        for (std::size_t i = 0; i < target_count; ++i) {
          double dot = 0.0;
          for (int c = 0; c < dims; ++c) dot += direction[c] * target[i * dims + c];
          projection[i] = static_cast<float>(dot);
        }
        sort_values(projection, keys, sorted);
        for (std::size_t k = 0; k < quantiles.size(); ++k)
          quantiles[k] = sorted_quantile(
              sorted, (static_cast<double>(k) + 0.5) / static_cast<double>(quantiles.size()));
      });
}

std::vector<float> sliced_transport_to_gaussian(std::span<const float> source, int dims,
                                                int iterations, std::uint32_t seed) {
  const std::vector<float> standard =
      standard_normal_quantiles(source.size() / static_cast<std::size_t>(dims));
  return sliced_transport(
      source, dims, iterations, seed, [&](const double* direction, std::span<float> quantiles) {
        double centre = 0.0;
        for (int c = 0; c < dims; ++c) centre += kGaussianMean * direction[c];
        for (std::size_t k = 0; k < quantiles.size(); ++k)
          quantiles[k] = static_cast<float>(centre + kGaussianDeviation * standard[k]);
      });
}

void gaussianise_radial(std::span<const float> slopes, std::span<float> gaussian,
                        std::span<float> table) {
  const std::size_t count = slopes.size() / 2;
  std::vector<float> magnitude(count);
  for (std::size_t i = 0; i < count; ++i)
    magnitude[i] = std::hypot(slopes[2 * i], slopes[2 * i + 1]);
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> scratch;
  argsort(magnitude, keys, scratch);
  std::vector<float> sorted(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = index_of(keys[k]);
    sorted[k] = magnitude[i];
    const auto rho = static_cast<float>(
        uniform_to_radius((static_cast<double>(k) + 0.5) / static_cast<double>(count)));
    // A flat pixel (s = 0) has no direction: it takes the x axis'.
    const float scale = magnitude[i] > 0.0f ? rho / magnitude[i] : 0.0f;
    gaussian[2 * i] = kGaussianMean + (magnitude[i] > 0.0f ? scale * slopes[2 * i] : rho);
    gaussian[2 * i + 1] = kGaussianMean + scale * slopes[2 * i + 1];
  }
  for (std::size_t k = 0; k < table.size(); ++k)
    table[k] =
        sorted_quantile(sorted, (static_cast<double>(k) + 0.5) / static_cast<double>(table.size()));
}

void gaussianise_1d(std::span<const float> values, std::span<float> gaussian,
                    std::span<float> table) {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> scratch;
  argsort(values, keys, scratch);
  const std::vector<float> standard = standard_normal_quantiles(values.size());
  std::vector<float> sorted(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::size_t i = index_of(keys[k]);
    sorted[k] = values[i];
    gaussian[i] = kGaussianMean + kGaussianDeviation * standard[k];
  }
  for (std::size_t k = 0; k < table.size(); ++k)
    table[k] =
        sorted_quantile(sorted, (static_cast<double>(k) + 0.5) / static_cast<double>(table.size()));
}

namespace {

// A material's groups of T (issue 18): each map of several channels (a colour map, the normal
// map's two slopes) on its principal axes, each one-channel map (height, scalar, grey colour)
// through its own 1-D table; none for an image (tiling_layout's colour and alpha) or without T
// (variance, linear). Not the 3-D table of section 4.3, even with sliced transport: its T^-1 is
// a second transport that inverts T only approximately, and on rock_sandstone it moved the
// rendered albedo-height correlation by 0.11 (1024² renders, 4 seeds), where 1-D tables on
// principal axes, exact inverses, kept every cross-map correlation within 0.03.
//
// With rotation or scale jitter, a normal map's slopes go through the radial transform instead
// (GroupTransform::radial, evaluate.hpp), whose Gaussian space turns with the patches.
std::vector<GroupSpec> material_groups(std::span<const MapInfo> maps, const Params& params) {
  std::vector<GroupSpec> groups;
  if (maps.empty() || params.blend != Blend::histogram) return groups;
  const bool turned = params.rotation > 0.0 || params.scale_jitter > 0.0;
  for (const MapInfo& map : maps)
    groups.push_back({map.kind == MapKind::normal && turned ? GroupTransform::radial
                      : map.channels > 1                    ? GroupTransform::decorrelated
                                                            : GroupTransform::direct,
                      map.channels});
  return groups;
}

}  // namespace

double auto_tile_radius(ImageView<const float> exemplar) {
  const ImageF periodic = periodic_component(exemplar);
  const int width = exemplar.width;
  const int height = exemplar.height;
  const Fft2d fft(width, height);
  const int half = fft.spectrum_width();
  // Power per half-plane frequency, each channel's power summed to 1 (the mean left out).
  std::vector<double> power(fft.spectrum_size(), 0.0);
  std::vector<float> plane(fft.image_size());
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  const std::vector<double> means = channel_means(periodic.view());
  for (int c = 0; c < exemplar.channels; ++c) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        plane[static_cast<std::size_t>(y) * width + x] =
            static_cast<float>(periodic.at(x, y, c) - means[c]);
    fft.forward(plane, spectrum);
    std::vector<double> channel_power(spectrum.size());
    double total = 0.0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < half; ++x) {
        // Columns 1 .. ceil(width / 2) - 1 stand for their Hermitian mirror too.
        const double weight = x == 0 || 2 * x == width ? 1.0 : 2.0;
        const std::size_t i = static_cast<std::size_t>(y) * half + x;
        channel_power[i] = i == 0 ? 0.0 : weight * std::norm(spectrum[i]);
        total += channel_power[i];
      }
    if (total > 0.0)
      for (std::size_t i = 0; i < power.size(); ++i) power[i] += channel_power[i] / total;
  }
  std::vector<std::pair<double, double>> by_frequency;  // (|f| in cycles per pixel, power)
  double total = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < half; ++x) {
      const double p = power[static_cast<std::size_t>(y) * half + x];
      if (p <= 0.0) continue;
      const double fy = static_cast<double>(std::min(y, height - y)) / height;
      by_frequency.emplace_back(std::hypot(static_cast<double>(x) / width, fy), p);
      total += p;
    }
  const double side = std::min(width, height);
  if (total <= 0.0) return 0.5;  // a constant exemplar: any tile captures it
  std::sort(by_frequency.begin(), by_frequency.end());
  // The lowest frequency f at which the power below and at f exceeds the leak: periods longer
  // than 1 / f hold at most kAutoTileLeak, and a tile of diameter 1 / f spans them.
  double below = 0.0;
  double frequency = by_frequency.back().first;
  for (const auto& [f, p] : by_frequency) {
    below += p;
    if (below > kAutoTileLeak * total) {
      frequency = f;
      break;
    }
  }
  return std::clamp(0.5 / (frequency * side), kAutoTileRadiusMin, 0.5);
}

TilingModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                    std::span<const MapInfo> maps) {
  const auto height_map = std::find_if(maps.begin(), maps.end(), [](const MapInfo& map) {
    return map.kind == MapKind::height && map.channels == 1;
  });
  if (params.height_blend > 0.0 && height_map == maps.end())
    throw std::invalid_argument(
        "tiling's height_blend compares the patches' heights and this exemplar has no height "
        "map: analyse a material with one (--map height=...) or leave height_blend at 0");
  if (params.height_blend > 0.0 && params.blend != Blend::histogram)
    throw std::invalid_argument(
        "tiling's height_blend compares the patches' Gaussianised heights, which only the "
        "histogram blend has: use blend=histogram or leave height_blend at 0");
  TilingData data;
  data.groups = material_groups(maps, params);
  data.channels = exemplar.channels;
  data.width = exemplar.width;
  data.height = exemplar.height;
  data.tile_radius = params.tile_radius == 0.0 ? auto_tile_radius(exemplar) : params.tile_radius;
  data.transport = params.transport;
  data.lut_size = params.lut_size;
  data.table_size = params.table_size;
  data.blend = params.blend;
  data.rotation = params.rotation;
  data.scale_jitter = params.scale_jitter;
  data.sharpness = params.sharpness;
  data.height_blend = params.height_blend;
  if (params.height_blend > 0.0) {
    // The maps are interleaved in their order: the height map's channel follows the others'.
    data.height_channel = 0;
    for (auto map = maps.begin(); map != height_map; ++map) data.height_channel += map->channels;
  }
  const int iterations = params.iterations;
  const int channels = data.channels;
  const std::size_t pixels = static_cast<std::size_t>(data.width) * data.height;
  // A photo cut from a larger scene steps at its border, and the lattice's patches read across it
  // (Algorithm 1 reads the exemplar periodically): the seam would show inside a patch. Not for a
  // strongly periodic pattern (kRepeatedPatternPeaks): there the pattern's phase does not meet
  // across the wrap, and the smooth component spreads that into a blurred band, which measured
  // worse than the seam (docs/inputs.md).
  data.made_tileable = params.make_tileable == MakeTileable::on ||
                       (params.make_tileable == MakeTileable::automatic &&
                        wrap_steps(exemplar).largest() > kTileableWrapStep &&
                        spectral_peak_fraction(exemplar) <= kRepeatedPatternPeaks);
  const ImageF tileable = data.made_tileable ? periodic_keeping_histogram(exemplar) : ImageF();
  const ImageView<const float> analysed = data.made_tileable ? tileable.view() : exemplar;
  std::vector<float> pixel_values(pixels * channels);
  for (int y = 0; y < data.height; ++y)
    for (int x = 0; x < data.width; ++x)
      for (int c = 0; c < channels; ++c)
        pixel_values[(static_cast<std::size_t>(y) * data.width + x) * channels + c] =
            analysed.at(x, y, c);
  const auto set_blend_mean = [&] {
    for (const double mean :
         channel_means(interleaved(data.gaussian, data.width, data.height, channels)))
      data.blend_mean.push_back(static_cast<float>(mean));
  };
  if (params.stationarity) {
    // An image's colour, not its alpha; every map of a material.
    const int colour_channels =
        maps.empty() ? tiling_layout(channels, data.transport, Blend::histogram).colour_channels
                     : channels;
    remove_large_scales(pixel_values, data.width, data.height, channels, colour_channels,
                        data.tile_radius * std::min(data.width, data.height) / std::numbers::pi);
  }

  if (data.blend != Blend::histogram) {
    // Section 6.1: a Gaussian exemplar is blended as is; eq. (8) needs only its mean.
    data.gaussian = std::move(pixel_values);
    set_blend_mean();
    return TilingModel(std::move(data));
  }

  const TilingLayout layout = tiling_layout(channels, data.transport, data.blend, data.groups);
  data.gaussian.assign(pixels * channels, 0.0f);
  data.tables.assign(static_cast<std::size_t>(layout.table_count) * data.table_size, 0.0f);
  std::vector<float> channel(pixels);
  std::vector<float> gaussian_channel(pixels);
  // 1-D transport of one channel of `values` (stride `stride`) into channel `target` of G and
  // 1-D table `table`.
  const auto transport_1d = [&](const std::vector<float>& values, int stride, int source,
                                int target, int table) {
    for (std::size_t i = 0; i < pixels; ++i) channel[i] = values[i * stride + source];
    gaussianise_1d(
        channel, gaussian_channel,
        std::span<float>(data.tables)
            .subspan(static_cast<std::size_t>(table) * data.table_size, data.table_size));
    for (std::size_t i = 0; i < pixels; ++i)
      data.gaussian[i * channels + target] = gaussian_channel[i];
  };

  for (const TableGroup& group : layout.groups) {
    if (group.transform == GroupTransform::direct) {
      transport_1d(pixel_values, channels, group.first, group.first, group.first_table);
      continue;
    }
    if (group.transform == GroupTransform::radial) {
      std::vector<float> slopes(pixels * 2);
      std::vector<float> gaussian(pixels * 2);
      for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 2; ++c)
          slopes[i * 2 + c] = pixel_values[i * channels + group.first + c];
      gaussianise_radial(slopes, gaussian,
                         std::span<float>(data.tables)
                             .subspan(static_cast<std::size_t>(group.first_table) * data.table_size,
                                      data.table_size));
      for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 2; ++c)
          data.gaussian[i * channels + group.first + c] = gaussian[i * 2 + c];
      continue;
    }
    const int cc = group.channels;
    std::vector<float> colours(pixels * cc);
    for (std::size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < cc; ++c)
        colours[i * cc + c] = pixel_values[i * channels + group.first + c];
    if (group.transform == GroupTransform::lut) {
      // Sections 4.1-4.2: T moves the colours to the Gaussian along a near-optimal displacement, so
      // G keeps the exemplar's structure (eq. 19).
      const std::vector<float> gaussian =
          sliced_transport_to_gaussian(colours, 3, iterations, seed);
      for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c)
          data.gaussian[i * channels + group.first + c] = gaussian[i * 3 + c];
      // Section 4.3: the table's cells, parameterised by eq. (20), are a stratified Gaussian point
      // set; transporting it onto the exemplar's colours gives T^-1 at each cell. Being a second,
      // independent transport it inverts T only approximately: measured rms |T^-1(T(x)) - x| of
      // 0.019 on moss_ground_512 and 0.052 on water_caustics_256 (a nearest-pixel table built from
      // T itself halved that but kept the histogram less well, sliced W2 0.009 against 0.003 on
      // water, with no gain in spectrum, so the paper's construction stays).
      const int n = data.lut_size;
      std::vector<float> grid(static_cast<std::size_t>(n) * n * n * 3);
      std::vector<float> axis(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i)
        axis[i] =
            static_cast<float>(kGaussianMean + kGaussianDeviation * normal_quantile((i + 0.5) / n));
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            float* cell = &grid[((static_cast<std::size_t>(z) * n + y) * n + x) * 3];
            cell[0] = axis[x];
            cell[1] = axis[y];
            cell[2] = axis[z];
          }
      data.lut = sliced_transport_to_points(grid, colours, 3, iterations, pcg_hash(seed));
    } else {
      // Per-channel transport (Deliot & Heitz 2019): decorrelate the colour by PCA (Heeger & Bergen
      // 1995), then an exact 1-D transport per principal axis. Grey needs no rotation.
      std::vector<double> basis = {1.0};
      std::vector<double> mean = {0.0};
      if (cc > 1) {
        const ImageView<const float> view = interleaved(colours, data.width, data.height, cc);
        mean = channel_means(view);
        basis = principal_components(channel_covariance(view, mean), cc).axes;
      }
      std::vector<float> decorrelated(pixels * cc);
      for (std::size_t i = 0; i < pixels; ++i)
        for (int k = 0; k < cc; ++k) {
          double dot = 0.0;
          for (int c = 0; c < cc; ++c) dot += basis[c * cc + k] * (colours[i * cc + c] - mean[c]);
          decorrelated[i * cc + k] = static_cast<float>(dot);
        }
      for (int k = 0; k < cc; ++k)
        transport_1d(decorrelated, cc, k, group.first + k, group.first_table + k);
      for (int c = 0; c < cc; ++c) {
        data.colour_mean.push_back(static_cast<float>(mean[c]));
        for (int k = 0; k < cc; ++k)
          data.colour_basis.push_back(static_cast<float>(basis[c * cc + k]));
      }
    }
  }
  set_blend_mean();
  return TilingModel(std::move(data));
}

}  // namespace stochtex::tiling
