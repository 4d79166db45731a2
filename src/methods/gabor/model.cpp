#include "methods/gabor/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/cpu_target.hpp"
#include "core/hash.hpp"
#include "core/periodic.hpp"
#include "core/surface_process.hpp"
#include "methods/gabor/alias.hpp"
#include "methods/gabor/evaluate.hpp"
#include "methods/gabor/params.hpp"
#include "methods/gabor/simd.hpp"
#include "methods/texton/evaluate.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::gabor {
namespace {

// The kernel is truncated where its envelope exp(-pi a^2 |x|^2) falls to e^-pi, at r = 1/a
// (section 6.1), and tapered before that (kTaperScale). With u = pi a^2 |x|^2 its energy is
// (1 / a^2) times the integral over [0, pi) of e^-2u w(u)^2, against 1 / (2 a^2) untruncated; the
// amplitude is raised by the square root of the ratio so the noise keeps the fitted variance.
// Below pi - h (h = 1 / kTaperScale) w = 1; above, with u = pi - h t, the integral is
// h e^-2pi times that of e^(2 h t) (t^2 (3 - 2t))^2 over t in [0, 1], by Simpson's rule (its
// error, below 1e-12 with 1024 intervals, is far below float rounding).
double truncation_gain() {
  const double h = 1.0 / kTaperScale;
  constexpr int kIntervals = 1024;
  const auto f = [&](double t) {
    const double w = t * t * (3.0 - 2.0 * t);
    return std::exp(2.0 * h * t) * w * w;
  };
  double simpson = f(0.0) + f(1.0);
  for (int i = 1; i < kIntervals; ++i)
    simpson += (i % 2 == 1 ? 4.0 : 2.0) * f(static_cast<double>(i) / kIntervals);
  const double taper = h * std::exp(-2.0 * kPi) * simpson / (3.0 * kIntervals);
  const double energy = 0.5 * (1.0 - std::exp(-2.0 * (kPi - h))) + taper;
  return std::sqrt(0.5 / energy);
}
const double kTruncationGain = truncation_gain();
// Cells hold about this many impulses on average: denser grids visit fewer empty margins, sparser
// ones fewer cells. The cell side stays within [r/4, 2r].
constexpr double kPointsPerCell = 64.0;
static_assert(kParams[1].name == "impulses", "the evaluator reads the impulse budget's range");
constexpr std::array<const char*, 5> kReportNames = {"sparseness", "fit_error",
                                                     "offdiagonality_independent",
                                                     "offdiagonality_pca", "offdiagonality_rgb"};

KernelFilter kernel_filter(const GaborModel::Grid& grid, const Footprint* footprint) {
  const double a2 = static_cast<double>(grid.bandwidth) * grid.bandwidth;
  KernelFilter k{kPi * a2, 0.0, kPi * a2};
  k.reach = grid.radius;
  if (footprint != nullptr) {
    const Footprint& fp = *footprint;
    // Filtering (Lagae et al. 2009, as the paper inherits in section 9.1): a Gabor kernel
    // convolved with a Gaussian stays a Gabor kernel. The pixel filter is the Gaussian with
    // the covariance of the footprint's box, Sigma_f = (dpdx dpdx^T + dpdy dpdy^T) / 12. In
    // frequency the kernel is exp(-(xi - omega)^T P (xi - omega)) with P = (pi / a^2) I and
    // the filter exp(-xi^T Q xi) with Q = 2 pi^2 Sigma_f. Their product is a Gaussian of
    // precision S = P + Q centred at omega' = S^-1 P omega, scaled by exp(-omega^T D omega)
    // with D = P - P S^-1 P; in space the envelope becomes exp(-pi^2 x^T S^-1 x) and the
    // amplitude gains sqrt(det P / det S).
    // The fitted spectrum already describes exemplar pixels, i.e. the field integrated over
    // one pixel: the filter adds only the footprint's covariance beyond that pixel's I / 12
    // (eigenvalues clipped at 0), so a scale-1 render is unfiltered and matches point
    // samples, and a scale-s render matches the average of s x s point samples.
    double q00 = (fp.dpdx.x * fp.dpdx.x + fp.dpdy.x * fp.dpdy.x) / 12.0;
    double q01 = (fp.dpdx.x * fp.dpdx.y + fp.dpdy.x * fp.dpdy.y) / 12.0;
    double q11 = (fp.dpdx.y * fp.dpdx.y + fp.dpdy.y * fp.dpdy.y) / 12.0;
    const double centre = 0.5 * (q00 + q11);
    const double radius = std::sqrt(0.25 * (q00 - q11) * (q00 - q11) + q01 * q01);
    const double major = centre + radius - kPixelVariance;
    const double minor = centre - radius - kPixelVariance;
    if (major <= 0.0) {
      q00 = q01 = q11 = 0.0;
    } else if (minor < 0.0) {
      // Only the major axis is wider than a pixel: keep (major) v v^T, v v^T read from
      // (Sigma - lambda_min I) / (lambda_max - lambda_min).
      const double lambda_min = centre - radius;
      const double scale = major / (2.0 * radius);
      q00 = scale * (q00 - lambda_min);
      q01 = scale * q01;
      q11 = scale * (q11 - lambda_min);
    } else {
      q00 -= kPixelVariance;
      q11 -= kPixelVariance;
    }
    q00 *= 2.0 * kPi * kPi;
    q01 *= 2.0 * kPi * kPi;
    q11 *= 2.0 * kPi * kPi;
    if (q00 + q11 > 0.0 && std::isfinite(q00 + q11 + q01)) {
      k.filtered = true;
      const double pp = kPi / a2;
      const double s00 = pp + q00, s01 = q01, s11 = pp + q11;
      const double det = s00 * s11 - s01 * s01;
      const double i00 = s11 / det, i01 = -s01 / det, i11 = s00 / det;
      k.e00 = kPi * kPi * i00;
      k.e01 = kPi * kPi * i01;
      k.e11 = kPi * kPi * i11;
      k.f00 = pp * i00;
      k.f01 = pp * i01;
      k.f11 = pp * i11;
      k.d00 = pp - pp * pp * i00;
      k.d01 = -pp * pp * i01;
      k.d11 = pp - pp * pp * i11;
      k.gain = pp / std::sqrt(det);
      // The envelope reaches e^-pi where x^T S^-1 x = 1 / pi: at most sqrt(lmax(S) / pi).
      const double half_trace = 0.5 * (s00 + s11);
      const double spread = std::sqrt(0.25 * (s00 - s11) * (s00 - s11) + s01 * s01);
      k.reach = std::sqrt((half_trace + spread) / kPi);
      const double d_half_trace = 0.5 * (k.d00 + k.d11);
      const double d_spread = std::sqrt(0.25 * (k.d00 - k.d11) * (k.d00 - k.d11) + k.d01 * k.d01);
      if ((d_half_trace - d_spread) * grid.min_frequency_squared > kNegligibleAttenuation) return k;
    }
  }
  if (k.filtered && k.reach > grid.radius) {
    const double wanted = std::ceil(std::log2(k.reach / grid.radius));
    // Beyond the last level the kernel's amplitude gain (r / reach)^2 is below 4^-40: the
    // filtered grid is zero to float precision, and skipping it bounds the cells visited.
    if (!(wanted <= kMaxLevels)) return k;
    k.level = static_cast<int>(wanted);
  }
  k.skip = false;
  return k;
}

GridKernels grid_kernels(const GaborModel& model, const GaborModel::Grid& grid) {
  return {model.frequency_x().data() + grid.first, model.frequency_y().data() + grid.first,
          model.alias_probability().data() + grid.first, model.alias_index().data() + grid.first,
          grid.count};
}

// Channel c of the index-th point of a batch, whose output is row-major (docs/design.md §4).
float& batch_pixel(ImageView<float> out, std::size_t index, int c) {
  const auto width = static_cast<std::size_t>(out.width);
  return out.at(static_cast<int>(index % width), static_cast<int>(index / width), c);
}

}  // namespace

double bandwidth(int band) {
  return std::ldexp(std::sqrt(kPi / (2.0 * std::numbers::ln2)), -band);
}

GaborModel::GaborModel(int channels, double impulses, int colour_space,
                       std::vector<GaussianComponent> gaussians, std::vector<float> mixing,
                       std::vector<float> mean, const FitReport& report)
    : channels_(channels),
      impulses_(impulses),
      colour_space_(colour_space),
      gaussians_(std::move(gaussians)),
      mixing_(std::move(mixing)),
      mean_(std::move(mean)),
      report_(report) {
  if (channels_ < 1 || channels_ > kMaxChannels)
    throw std::invalid_argument("gabor: channels must be 1 to " + std::to_string(kMaxChannels));
  if (!(impulses_ >= kParams[1].min_value && impulses_ <= kParams[1].max_value) ||
      impulses_ != std::floor(impulses_))
    throw std::invalid_argument("gabor: impulses must be an integer from 1 to 65536");
  if (colour_space_ < 0 || colour_space_ > 2)
    throw std::invalid_argument("gabor: colour_space must be 0, 1 or 2");
  if (mixing_.size() != static_cast<std::size_t>(channels_) * channels_ ||
      mean_.size() != static_cast<std::size_t>(channels_))
    throw std::invalid_argument("gabor: colour matrix or mean has the wrong size");
  if (gaussians_.size() > kMaxGaussians) throw std::invalid_argument("gabor: too many Gaussians");
  if (!within_model_range(mixing_) || !within_model_range(mean_))
    throw std::invalid_argument(
        "gabor: a colour matrix or mean value is not finite or beyond +-1e12");
  for (const GaussianComponent& g : gaussians_) {
    if (g.channel < 0 || g.channel >= channels_ || g.band < 0 || g.band >= kMaxBands)
      throw std::invalid_argument("gabor: a Gaussian has an invalid channel or bandwidth index");
    if (!(std::abs(g.frequency_x) <= 0.5f) || !(std::abs(g.frequency_y) <= 0.5f))
      throw std::invalid_argument("gabor: a Gaussian frequency is beyond the Nyquist limit");
    if (!(g.variance > 0.0f && g.variance <= kMaxModelValue))
      throw std::invalid_argument("gabor: a Gaussian variance is not a positive number up to 1e12");
  }
  for (const double value :
       {report_.sparseness, report_.fit_error, report_.offdiagonality_independent,
        report_.offdiagonality_pca, report_.offdiagonality_rgb})
    if (!(value >= 0.0) || !std::isfinite(value))
      throw std::invalid_argument("gabor: the fit report holds an invalid value");

  // Group the Gaussians by (channel, band): one grid each (section 6.1).
  std::vector<std::size_t> order(gaussians_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const GaussianComponent& ga = gaussians_[a];
    const GaussianComponent& gb = gaussians_[b];
    return ga.channel != gb.channel ? ga.channel < gb.channel : ga.band < gb.band;
  });
  frequency_x_.resize(order.size());
  frequency_y_.resize(order.size());
  alias_probability_.resize(order.size());
  alias_index_.resize(order.size());
  std::vector<double> grid_variance;
  for (std::size_t begin = 0; begin < order.size();) {
    const GaussianComponent& head = gaussians_[order[begin]];
    std::size_t end = begin;
    double variance = 0.0;
    Grid grid;
    grid.channel = head.channel;
    grid.band = head.band;
    grid.first = static_cast<std::uint32_t>(begin);
    grid.min_frequency_squared = 1.0f;
    std::vector<double> weights;
    for (; end < order.size() && gaussians_[order[end]].channel == head.channel &&
           gaussians_[order[end]].band == head.band;
         ++end) {
      const GaussianComponent& g = gaussians_[order[end]];
      frequency_x_[end] = g.frequency_x;
      frequency_y_[end] = g.frequency_y;
      weights.push_back(g.variance);
      variance += g.variance;
      grid.min_frequency_squared =
          std::min(grid.min_frequency_squared,
                   g.frequency_x * g.frequency_x + g.frequency_y * g.frequency_y);
    }
    grid.count = static_cast<std::uint32_t>(end - begin);
    // p_{b,g} = sigma_{b,g}^2 / sigma_b^2 (section 6.2).
    build_alias_table(weights, std::span(alias_probability_).subspan(begin, grid.count),
                      std::span(alias_index_).subspan(begin, grid.count));
    grids_.push_back(grid);
    grid_variance.push_back(variance);
    begin = end;
  }

  // The impulse budget is split over the grids by the variance each adds to the output colour,
  // N_b = (sigma_b^2 / sigma^2) N (section 6.2); in colour, the channel's variance counts through
  // the mixing column that spreads it over the exemplar's channels.
  std::vector<double> contribution(grids_.size());
  double total = 0.0;
  for (std::size_t i = 0; i < grids_.size(); ++i) {
    double column = 0.0;
    for (int c = 0; c < channels_; ++c) {
      const double m = mixing_[static_cast<std::size_t>(c) * channels_ + grids_[i].channel];
      column += m * m;
    }
    contribution[i] = grid_variance[i] * std::max(column, 1e-30);
    total += contribution[i];
  }
  for (std::size_t i = 0; i < grids_.size(); ++i) {
    Grid& grid = grids_[i];
    const double a = bandwidth(grid.band);
    grid.bandwidth = static_cast<float>(a);
    grid.radius = 1.0 / a;
    grid.impulses = impulses_ * contribution[i] / total;
    // lambda_b = N_b / (pi r_b^2) (section 6.2).
    const double intensity = grid.impulses / (kPi * grid.radius * grid.radius);
    grid.cell_size =
        grid.radius *
        std::clamp(std::sqrt(kPointsPerCell / (intensity * grid.radius * grid.radius)), 0.25, 2.0);
    grid.cell_count = CellCount::poisson(intensity * grid.cell_size * grid.cell_size);
    // With p = sigma_g^2 / sigma_b^2 and K_g = 2 a sigma_g, every kernel of eq. (5) has the same
    // weight K_g / sqrt(lambda_b p_g) = 2 a sigma_b / sqrt(lambda_b): its variance is then
    // lambda_b * E[K^2 / (lambda_b p)] / (4 a^2) = sigma_b^2.
    grid.amplitude =
        static_cast<float>(2.0 * a * std::sqrt(grid_variance[i] / intensity) * kTruncationGain);
  }
}

GaborModel GaborModel::from_record(const ModelRecord& record, const std::string& source) {
  const auto fail = [&](const std::string& what) {
    return Error(ErrorCode::format, "'" + source + "' is not a valid gabor model (" + what +
                                        "); re-run `stochtex analyze`");
  };
  const auto read = [&](const std::string& name, double low, double high, bool integer) {
    const double value = record.scalar(name, source);
    if ((integer && value != std::floor(value)) || value < low || value > high)
      throw fail("invalid " + name + " value");
    return value;
  };
  // Checked before any array is read or allocated: a hostile count is refused here.
  const int channels = static_cast<int>(read("channels", 1, kMaxChannels, true));
  const double impulses =
      read("impulses", kParams[1].min_value, kParams[1].max_value, kParams[1].integer);
  const int colour_space = static_cast<int>(read("colour_space", 0, 2, true));
  const double count = read("gaussians", 0, static_cast<double>(kMaxGaussians), true);
  FitReport report;
  double* const report_values[] = {&report.sparseness, &report.fit_error,
                                   &report.offdiagonality_independent, &report.offdiagonality_pca,
                                   &report.offdiagonality_rgb};
  for (std::size_t i = 0; i < kReportNames.size(); ++i)
    *report_values[i] = read(kReportNames[i], 0, 1e30, false);
  const NamedArray& table =
      record.array("gaussians", {static_cast<std::int64_t>(count), 5}, source);
  const NamedArray& mixing = record.array("colour", {channels, channels}, source);
  const NamedArray& mean = record.array("mean", {channels}, source);
  std::vector<GaussianComponent> gaussians(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < gaussians.size(); ++i) {
    const float* row = &table.values[5 * i];
    // Indices are stored as floats: exact integers below 2^24, checked before the conversion
    // (the constructor checks the channel against `channels`).
    constexpr auto kIndexBound = static_cast<float>(std::max(kMaxChannels, kMaxBands));
    for (int k = 0; k < 2; ++k)
      if (!(row[k] >= 0.0f && row[k] < kIndexBound) || row[k] != std::floor(row[k]))
        throw fail("a Gaussian has an invalid channel or bandwidth index");
    gaussians[i] = {static_cast<int>(row[0]), static_cast<int>(row[1]), row[2], row[3], row[4]};
  }
  try {
    return GaborModel(channels, impulses, colour_space, std::move(gaussians), mixing.values,
                      mean.values, report);
  } catch (const std::invalid_argument& e) {
    std::string what = e.what();
    throw fail(what.substr(what.find(':') + 2));
  }
}

ModelRecord GaborModel::to_record(const ParamValues& params) const {
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  record.scalars = {{"channels", channels_},
                    {"impulses", impulses_},
                    {"colour_space", colour_space_},
                    {"gaussians", static_cast<double>(gaussians_.size())}};
  const double report_values[] = {report_.sparseness, report_.fit_error,
                                  report_.offdiagonality_independent, report_.offdiagonality_pca,
                                  report_.offdiagonality_rgb};
  for (std::size_t i = 0; i < kReportNames.size(); ++i)
    record.scalars[kReportNames[i]] = report_values[i];
  std::vector<float> table;
  table.reserve(5 * gaussians_.size());
  for (const GaussianComponent& g : gaussians_)
    table.insert(table.end(), {static_cast<float>(g.channel), static_cast<float>(g.band),
                               g.frequency_x, g.frequency_y, g.variance});
  record.arrays.push_back(
      {"gaussians", {static_cast<std::int64_t>(gaussians_.size()), 5}, std::move(table)});
  record.arrays.push_back({"colour", {channels_, channels_}, mixing_});
  record.arrays.push_back({"mean", {channels_}, mean_});
  record.arrays.push_back(
      {"spectrum", {kPreviewSide, kPreviewSide, channels_}, spectrum_preview()});
  return record;
}

std::vector<float> GaborModel::spectrum_preview() const {
  // Eq. (6) sampled at frequencies (i - side / 2) / side, each Gaussian splatted within 4
  // standard deviations (periodically: the pixel grid aliases beyond Nyquist). The fourth root
  // compresses the dynamic range as the paper's insets do (figures 1, 4, 5).
  std::vector<double> power(static_cast<std::size_t>(kPreviewSide) * kPreviewSide * channels_, 0.0);
  constexpr double kSide = kPreviewSide;
  for (const GaussianComponent& g : gaussians_) {
    const double sigma = bandwidth(g.band) / (2.0 * std::sqrt(kPi));
    const double peak = g.variance / (2.0 * 2.0 * kPi * sigma * sigma);  // sigma^2 / 2 per lobe
    const int reach = std::min(kPreviewSide / 2, static_cast<int>(std::ceil(4.0 * sigma * kSide)));
    for (const double sign : {1.0, -1.0}) {
      const double centre_x = sign * g.frequency_x * kSide + kSide / 2;
      const double centre_y = sign * g.frequency_y * kSide + kSide / 2;
      const int first_x = static_cast<int>(std::floor(centre_x)) - reach;
      const int first_y = static_cast<int>(std::floor(centre_y)) - reach;
      for (int y = first_y; y <= first_y + 2 * reach + 1; ++y)
        for (int x = first_x; x <= first_x + 2 * reach + 1; ++x) {
          const double fx = (x - centre_x) / kSide;
          const double fy = (y - centre_y) / kSide;
          const int wx = ((x % kPreviewSide) + kPreviewSide) % kPreviewSide;
          const int wy = ((y % kPreviewSide) + kPreviewSide) % kPreviewSide;
          power[(static_cast<std::size_t>(wy) * kPreviewSide + wx) * channels_ + g.channel] +=
              peak * std::exp(-(fx * fx + fy * fy) / (2.0 * sigma * sigma));
        }
    }
  }
  double peak = 0.0;
  for (double& value : power) {
    value = std::sqrt(std::sqrt(value));
    peak = std::max(peak, value);
  }
  std::vector<float> preview(power.size());
  for (std::size_t i = 0; i < power.size(); ++i)
    preview[i] = static_cast<float>(peak > 0.0 ? 2.0 * power[i] / peak - 1.0 : -1.0);
  return preview;
}

void GaborModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                          std::uint32_t seed, ImageView<float> out) const noexcept {
  const auto pixel = [&](std::size_t index, int c) -> float& { return batch_pixel(out, index, c); };
  // `out` accumulates the noise of each synthesis channel, then is mixed back to colour.
  for (std::size_t index = 0; index < positions.size(); ++index)
    for (int c = 0; c < channels_; ++c) pixel(index, c) = 0.0f;

  // Grid-major: all samples of the batch visit one grid before the next, so one cell cache serves
  // them and the sum per sample runs over grids, cells and impulses in a fixed order (the output
  // does not depend on the batch or on the order of its samples). The vectorised twin (simd.hpp)
  // returns the same sums; it takes a batch of rows (a render tile) in strips as narrow as its cell
  // cache needs for the grid, top to bottom, so each cell is drawn about once.
  ImpulseCache impulses;
  const bool simd = simd_enabled() && impulses.reserve();
  std::size_t row = 1;
  while (row < positions.size() && positions[row].y == positions[0].y) ++row;
  if (positions.size() % row != 0) row = positions.size();
  const double step = row > 1 ? std::abs(positions[1].x - positions[0].x) : 0.0;
  for (std::size_t grid_index = 0; grid_index < grids_.size(); ++grid_index) {
    const Grid& grid = grids_[grid_index];
    const GridKernels kernels = grid_kernels(*this, grid);
    std::optional<texton::CellCache> cells;
    int cached_level = -1;
    std::uint32_t level_seed = 0;
    // A render's samples share one footprint: the filter is derived again only when the footprint
    // changes (bit for bit, so the result is the same).
    KernelFilter filter = kernel_filter(grid, footprints.empty() ? nullptr : &footprints[0]);
    const Footprint* filter_footprint = footprints.empty() ? nullptr : &footprints[0];
    const std::size_t strip =
        simd ? strip_width(step, filter.reach, std::ldexp(grid.cell_size, filter.level)) : row;
    const auto sample = [&](std::size_t index) {
      const Vec2d p = positions[index];
      if (filter_footprint != nullptr &&
          std::memcmp(&footprints[index], filter_footprint, sizeof(Footprint)) != 0) {
        filter_footprint = &footprints[index];
        filter = kernel_filter(grid, filter_footprint);
      }
      if (filter.skip) return;
      const int level = filter.level;
      const double cell_size = std::ldexp(grid.cell_size, level);
      const auto cell_size_f = static_cast<float>(cell_size);
      if (level != cached_level) {
        cached_level = level;
        level_seed = cell_key(static_cast<std::int64_t>(grid_index), level, seed, Stream::kernels);
        if (simd)
          impulses.start(kernels, grid.cell_count, level_seed, cell_size_f);
        else
          cells.emplace(level_seed, grid.cell_count);
      }
      const KernelShape shape(filter);
      const CellRange range = cell_range(p, filter.reach, cell_size);
      float sum = 0.0f;
      if (simd) {
        sum = impulse_sum(impulses, shape, range, p, cell_size);
      } else {
        for (std::int64_t cell_y = range.first_y; cell_y <= range.last_y; ++cell_y) {
          const float offset_y = cell_offset(p.y, cell_y, cell_size);
          for (std::int64_t cell_x = range.first_x; cell_x <= range.last_x; ++cell_x) {
            const float offset_x = cell_offset(p.x, cell_x, cell_size);
            // The kernel parameters of the cell's impulses come in the impulses' order from their
            // own stream, so cached positions and fresh parameters stay paired.
            CounterRng kernel_rng(cell_key(cell_x, cell_y, level_seed, Stream::kernels));
            cells->for_each_point(cell_x, cell_y, [&](float u, float v, float) {
              float wx, wy, phase;
              kernels.draw(kernel_rng, wx, wy, phase);
              float value;
              if (shape.at(wx, wy, phase, offset_x - u * cell_size_f, offset_y - v * cell_size_f,
                           value))
                sum += value;
            });
          }
        }
      }
      pixel(index, grid.channel) +=
          static_cast<float>(std::ldexp(grid.amplitude * filter.gain, level)) * sum;
    };
    for (std::size_t first = 0; first < row; first += strip)
      for (std::size_t start = 0; start < positions.size(); start += row)
        for (std::size_t i = first; i < std::min(first + strip, row); ++i) sample(start + i);
  }

  mix_to_colour(positions.size(), out);
}

void GaborModel::evaluate_periodic(std::span<const Vec2d> positions,
                                   std::span<const Footprint> footprints, std::uint32_t seed,
                                   ImageView<float> out, Vec2d period) const noexcept {
  const auto pixel = [&](std::size_t index, int c) -> float& { return batch_pixel(out, index, c); };
  for (std::size_t index = 0; index < positions.size(); ++index)
    for (int c = 0; c < channels_; ++c) pixel(index, c) = 0.0f;
  // evaluate()'s scalar loop, grid-major, with the cells of each level dividing the period.
  for (std::size_t grid_index = 0; grid_index < grids_.size(); ++grid_index) {
    const Grid& grid = grids_[grid_index];
    const GridKernels kernels = grid_kernels(*this, grid);
    std::optional<CellCount> count;
    std::optional<texton::CellCache> cells;
    PeriodicAxis axis_x;
    PeriodicAxis axis_y;
    int cached_level = -1;
    std::uint32_t level_seed = 0;
    // Derived again only when the footprint changes, as in evaluate().
    KernelFilter filter = kernel_filter(grid, footprints.empty() ? nullptr : &footprints[0]);
    const Footprint* filter_footprint = footprints.empty() ? nullptr : &footprints[0];
    for (std::size_t index = 0; index < positions.size(); ++index) {
      if (filter_footprint != nullptr &&
          std::memcmp(&footprints[index], filter_footprint, sizeof(Footprint)) != 0) {
        filter_footprint = &footprints[index];
        filter = kernel_filter(grid, filter_footprint);
      }
      if (filter.skip) continue;
      const int level = filter.level;
      if (level != cached_level) {
        cached_level = level;
        level_seed = cell_key(static_cast<std::int64_t>(grid_index), level, seed, Stream::kernels);
        const double side = std::ldexp(grid.cell_size, level);
        axis_x = periodic_axis(period.x, side);
        axis_y = periodic_axis(period.y, side);
        // The level's intensity (its count per side^2 cell) in cells of another area.
        count.emplace(
            CellCount::poisson(grid.cell_count.mean() * axis_x.size * axis_y.size / (side * side)));
        cells.emplace(level_seed, *count);
      }
      const Vec2d p = reduce_position(positions[index], period);
      const KernelShape shape(filter);
      const auto size_x = static_cast<float>(axis_x.size);
      const auto size_y = static_cast<float>(axis_y.size);
      const auto first_x =
          static_cast<std::int64_t>(std::floor((p.x - filter.reach) / axis_x.size));
      const auto last_x = static_cast<std::int64_t>(std::floor((p.x + filter.reach) / axis_x.size));
      const auto first_y =
          static_cast<std::int64_t>(std::floor((p.y - filter.reach) / axis_y.size));
      const auto last_y = static_cast<std::int64_t>(std::floor((p.y + filter.reach) / axis_y.size));
      float sum = 0.0f;
      for (std::int64_t cell_y = first_y; cell_y <= last_y; ++cell_y) {
        const float offset_y = cell_offset(p.y, cell_y, axis_y.size);
        for (std::int64_t cell_x = first_x; cell_x <= last_x; ++cell_x) {
          const float offset_x = cell_offset(p.x, cell_x, axis_x.size);
          const std::int64_t key_x = axis_x.wrap(cell_x);
          const std::int64_t key_y = axis_y.wrap(cell_y);
          CounterRng kernel_rng(cell_key(key_x, key_y, level_seed, Stream::kernels));
          cells->for_each_point(key_x, key_y, [&](float u, float v, float) {
            float wx, wy, phase;
            kernels.draw(kernel_rng, wx, wy, phase);
            float value;
            if (shape.at(wx, wy, phase, offset_x - u * size_x, offset_y - v * size_y, value))
              sum += value;
          });
        }
      }
      pixel(index, grid.channel) +=
          static_cast<float>(std::ldexp(grid.amplitude * filter.gain, level)) * sum;
    }
  }
  mix_to_colour(positions.size(), out);
}

void GaborModel::mix_to_colour(std::size_t count, ImageView<float> out) const noexcept {
  const auto pixel = [&](std::size_t index, int c) -> float& { return batch_pixel(out, index, c); };
  // Back to the exemplar's colours: colour = mean + mixing * noise (section 7).
  for (std::size_t index = 0; index < count; ++index) {
    std::array<float, kMaxChannels> noise{};
    for (int c = 0; c < channels_; ++c) noise[static_cast<std::size_t>(c)] = pixel(index, c);
    for (int c = 0; c < channels_; ++c) {
      float value = mean_[static_cast<std::size_t>(c)];
      for (int k = 0; k < channels_; ++k)
        value += mixing_[static_cast<std::size_t>(c) * channels_ + k] *
                 noise[static_cast<std::size_t>(k)];
      pixel(index, c) = value;
    }
  }
}

GaborModel::SurfaceGrid GaborModel::surface_grid(const Grid& grid, double surface_mni) {
  const double planar_intensity = grid.impulses / (kPi * grid.radius * grid.radius);
  const double intensity = planar_intensity * surface_mni / (kSurfaceMniReference * grid.radius);
  // Cubic cells holding about kPointsPerCell impulses, side within [r/4, 2r]. A footprint of
  // thinning level l scales the whole process by 2^l (cells, depth; intensity / 8^l, so the
  // count per cell stays), and the amplitude by 2^l keeps the variance, as in the plane.
  SurfaceGrid surface;
  surface.cell_size =
      grid.radius *
      std::clamp(std::cbrt(kPointsPerCell / (intensity * grid.radius * grid.radius * grid.radius)),
                 0.25, 2.0);
  surface.count =
      CellCount::poisson(intensity * surface.cell_size * surface.cell_size * surface.cell_size);
  return surface;
}

double GaborModel::surface_amplitude_gain(double surface_mni) {
  return std::sqrt(1.5 * kSurfaceMniReference / surface_mni);
}

void GaborModel::evaluate_surface(std::span<const SurfacePoint> points, double surface_mni,
                                  std::uint32_t seed, ImageView<float> out) const noexcept {
  const auto pixel = [&](std::size_t index, int c) -> float& { return batch_pixel(out, index, c); };
  for (std::size_t index = 0; index < points.size(); ++index)
    for (int c = 0; c < channels_; ++c) pixel(index, c) = 0.0f;

  // Surface Gabor noise (section 9.1, after Lagae et al. 2009) on the impulse process of texton
  // surface noise (texton paper section 6): per grid, a 3-D Poisson process whose impulses within
  // the kernel radius r_b of the tangent plane are weighted by (1 - |t| / r_b)+ and carry their
  // Gabor kernel in the frame (u1, u2). Its intensity is lambda_3 = lambda_2 surface_mni /
  // (kSurfaceMniReference r_b): at the reference the weights sum on average to the planar noise's
  // impulse count, as texton surface noise at MNI 60 against planar texton noise at 30 (the
  // paper's figures). By Campbell's theorem the variance is lambda_3 (2 r_b / 3) integral(h^2)
  // against lambda_2 integral(h^2) in the plane: the amplitude gains
  // sqrt(lambda_2 / (lambda_3 2 r_b / 3)) = sqrt(1.5 kSurfaceMniReference / surface_mni), and the
  // noise keeps the planar noise's variance (and zero mean, the phases being uniform).
  const double amplitude_gain = surface_amplitude_gain(surface_mni);
  const bool simd = simd_enabled();
  for (std::size_t grid_index = 0; grid_index < grids_.size(); ++grid_index) {
    const Grid& grid = grids_[grid_index];
    const GridKernels kernels = grid_kernels(*this, grid);
    const SurfaceGrid surface = surface_grid(grid, surface_mni);
    for (std::size_t index = 0; index < points.size(); ++index) {
      const SurfacePoint& p = points[index];
      const SurfaceFrame frame = surface_frame(p);
      const Footprint footprint = tangent_footprint(p, frame);
      const KernelFilter filter = kernel_filter(grid, &footprint);
      if (filter.skip) continue;
      const KernelShape shape(filter);
      const double depth = std::ldexp(grid.radius, filter.level);
      const auto inverse_depth = static_cast<float>(1.0 / depth);
      const std::uint32_t level_seed =
          cell_key(static_cast<std::int64_t>(grid_index), filter.level, seed, Stream::kernels);
      const double cell_size = std::ldexp(surface.cell_size, filter.level);
      float sum = 0.0f;
      if (simd) {
        sum = surface_impulse_sum(kernels, shape, p, frame, filter.reach, depth, cell_size,
                                  surface.count, level_seed);
      } else {
        for_each_surface_impulse(p, frame, filter.reach, depth, cell_size, surface.count,
                                 level_seed, [&](CounterRng& rng, float t, float z1, float z2) {
                                   // An impulse outside the tent or the kernel's support is
                                   // rejected before its kernel, whose draws are skipped.
                                   const float weight = 1.0f - std::abs(t) * inverse_depth;
                                   const float envelope =
                                       weight > 0.0f ? shape.envelope(z1, z2) : kPiF;
                                   if (envelope >= kPiF) {
                                     rng.skip(GridKernels::kDraws);
                                     return;
                                   }
                                   float wx, wy, phase;
                                   kernels.draw(rng, wx, wy, phase);
                                   sum += weight * shape.value(envelope, wx, wy, phase, z1, z2);
                                 });
      }
      pixel(index, grid.channel) +=
          static_cast<float>(std::ldexp(grid.amplitude * filter.gain, filter.level) *
                             amplitude_gain) *
          sum;
    }
  }
  mix_to_colour(points.size(), out);
}

}  // namespace stochtex::gabor
