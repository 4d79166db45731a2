#include "methods/lrp/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/cpu_target.hpp"
#include "core/hash.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/params.hpp"
#include "methods/lrp/simd.hpp"
#include "methods/lrp/tables.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp {
namespace {

// Limits on what a model may ask of the evaluator; beyond them a model file is rejected. Channels:
// 1 to kMaxChannels (stochtex.hpp; a material's maps side by side); strata per channel: 1 to
// kMaxStrataPerChannel (model.hpp).
static_assert(kParams[1].name == "strata" && kParams[1].max_value == kMaxStrataPerChannel);
// w_f^2 = n_k J_S P'(f) / E_S <= 2^20 * 2000 (analysis.cpp, frequency_weights).
constexpr double kMaxWeight = 1e5;

const ParamInfo& param(std::string_view name) {
  return *std::find_if(kParams.begin(), kParams.end(),
                       [&](const ParamInfo& p) { return p.name == name; });
}

}  // namespace

LrpModel::LrpModel(LrpData data) : data_(std::move(data)) {
  const int channels = data_.channels;
  const int strata = data_.strata;
  if (channels < 1 || channels > kMaxChannels)
    throw std::invalid_argument("lrp: channels must be 1 to " + std::to_string(kMaxChannels));
  if (strata < param("strata").min_value || strata > param("strata").max_value)
    throw std::invalid_argument("lrp: the number of strata is out of range");
  const auto channel_count = static_cast<std::size_t>(channels);
  if (data_.mean.size() != channel_count || data_.colour_basis.size() != channel_count * channels)
    throw std::invalid_argument("lrp: the mean or colour basis has the wrong size");
  if (!within_model_range(data_.mean) || !within_model_range(data_.colour_basis) ||
      !within_model_range(data_.frequencies))
    throw std::invalid_argument(
        "lrp: a mean, colour basis or frequency value is not finite or beyond +-1e12");
  if (data_.strata_table.size() != channel_count * strata)
    throw std::invalid_argument("lrp: the strata table has the wrong size");
  std::size_t substrata = 0;
  for (const Stratum& stratum : data_.strata_table) {
    if (stratum.cosines < 1 || stratum.cosines > param("cosines").max_value)
      throw std::invalid_argument("lrp: a stratum's cosine count is out of range");
    if (!(stratum.spacing >= kMinSpacing && stratum.spacing <= kMaxSpacing))
      throw std::invalid_argument("lrp: a stratum's lattice spacing is out of range");
    if (!(stratum.amplitude >= 0.0 && stratum.amplitude <= kMaxAmplitude))
      throw std::invalid_argument("lrp: a stratum's amplitude is out of range");
    substrata += static_cast<std::size_t>(stratum.cosines);
  }
  if (data_.substratum_first.size() != substrata || data_.substratum_count.size() != substrata)
    throw std::invalid_argument("lrp: the sub-strata tables do not match the strata");
  if (data_.frequencies.size() % 2 != 0)
    throw std::invalid_argument("lrp: the frequency table has an odd size");
  const std::size_t frequency_count = data_.frequencies.size() / 2;
  if (data_.weights.size() != frequency_count ||
      !std::all_of(data_.weights.begin(), data_.weights.end(),
                   [](float w) { return w >= 0.0f && w <= kMaxWeight; }))
    throw std::invalid_argument("lrp: the frequency weights are missing or out of range");
  check_substrata(data_.substratum_first, data_.substratum_count, data_.frequencies, "noise");
  validate_structure(data_.structure, channels);

  window_coefficients_ = window_coefficients();
  mean_envelope_ = 2.0 * std::numbers::pi * window_radial_energy();
  std::uint32_t first_substratum = 0;
  for (int c = 0; c < channels; ++c)
    for (int s = 0; s < strata; ++s) {
      const Stratum& stratum = data_.strata_table[static_cast<std::size_t>(c * strata + s)];
      runtime_strata_.push_back({stratum.spacing, 1.0 / stratum.spacing, stratum.spacing,
                                 stratum.amplitude, first_substratum,
                                 static_cast<std::uint32_t>(stratum.cosines), c});
      first_substratum += static_cast<std::uint32_t>(stratum.cosines);
    }
}

LrpModel LrpModel::from_record(const ModelRecord& record, const std::string& source) {
  // Scalars are checked against the parameter ranges (params.hpp) and the counts against the
  // limits above before any array is read: a file must not ask for more work or memory than
  // `stochtex analyze` could produce.
  const auto invalid = [&](const std::string& what) {
    return Error(ErrorCode::format,
                 "'" + source + "' has an invalid lrp " + what + "; re-run `stochtex analyze`");
  };
  const auto read = [&](std::string_view name, double low, double high) {
    const double value = record.scalar(std::string(name), source);
    if (value != std::floor(value) || value < low || value > high) throw invalid(std::string(name));
    return static_cast<std::int64_t>(value);
  };
  const auto channels = read("channels", 1, kMaxChannels);
  const auto strata = read("strata", param("strata").min_value, param("strata").max_value);
  const auto envelope = read("envelope", 0, 1);
  const auto substrata =
      read("substrata", 1, param("cosines").max_value * static_cast<double>(channels * strata));
  // 2^22 frequencies, or 2^20 per channel from 5 channels on.
  const auto frequencies =
      read("frequencies", 1, kMaxSubstratumSize * std::max(4.0, static_cast<double>(channels)));
  const NamedArray& mean = record.array("mean", {channels}, source);
  const NamedArray& basis = record.array("colour_basis", {channels, channels}, source);
  const NamedArray& table = record.array("strata", {channels * strata, 3}, source);
  const NamedArray& ranges = record.array("substrata", {substrata, 2}, source);
  const NamedArray& frequency = record.array("frequencies", {frequencies, 2}, source);
  const NamedArray& weights = record.array("weights", {frequencies}, source);
  if (!within_model_range(table.values) || !within_model_range(ranges.values))
    throw invalid("strata table");

  LrpData data;
  data.channels = static_cast<int>(channels);
  data.strata = static_cast<int>(strata);
  data.normalise_envelope = envelope == 1;
  data.mean = mean.values;
  data.colour_basis = basis.values;
  data.frequencies = frequency.values;
  data.weights = weights.values;
  data.structure = read_structure(record, static_cast<int>(channels), source);
  for (std::size_t s = 0; s < table.values.size(); s += 3) {
    const float cosines = table.values[s];
    if (cosines != std::floor(cosines) || cosines < 1 || cosines > param("cosines").max_value)
      throw invalid("stratum cosine count");
    data.strata_table.push_back(
        {static_cast<int>(cosines), table.values[s + 1], table.values[s + 2]});
  }
  if (!read_substratum_ranges(ranges.values, data.substratum_first, data.substratum_count))
    throw invalid("sub-stratum range");
  try {
    return LrpModel(std::move(data));
  } catch (const std::invalid_argument& e) {
    throw Error(ErrorCode::format, "'" + source + "' is not a valid lrp model (" + e.what() +
                                       "); re-run `stochtex analyze`");
  }
}

ModelRecord LrpModel::to_record(const ParamValues& params) const {
  const std::int64_t channels = data_.channels;
  const std::int64_t strata = data_.strata;
  const auto substrata = static_cast<std::int64_t>(data_.substratum_first.size());
  const auto frequencies = static_cast<std::int64_t>(data_.frequencies.size() / 2);
  ModelRecord record;
  record.method = std::string(kMethodName);
  record.params = params;
  record.scalars = {{"channels", static_cast<double>(channels)},
                    {"strata", static_cast<double>(strata)},
                    {"envelope", data_.normalise_envelope ? 1.0 : 0.0},
                    {"substrata", static_cast<double>(substrata)},
                    {"frequencies", static_cast<double>(frequencies)}};
  std::vector<float> table;
  for (const Stratum& stratum : data_.strata_table) {
    table.push_back(static_cast<float>(stratum.cosines));
    table.push_back(stratum.spacing);
    table.push_back(stratum.amplitude);
  }
  std::vector<float> ranges;
  for (std::size_t k = 0; k < data_.substratum_first.size(); ++k) {
    ranges.push_back(static_cast<float>(data_.substratum_first[k]));
    ranges.push_back(static_cast<float>(data_.substratum_count[k]));
  }
  record.arrays.push_back({"mean", {channels}, data_.mean});
  record.arrays.push_back({"colour_basis", {channels, channels}, data_.colour_basis});
  record.arrays.push_back({"strata", {channels * strata, 3}, std::move(table)});
  record.arrays.push_back({"substrata", {substrata, 2}, std::move(ranges)});
  record.arrays.push_back({"frequencies", {frequencies, 2}, data_.frequencies});
  record.arrays.push_back({"weights", {frequencies}, data_.weights});
  write_structure(data_.structure, record);
  return record;
}

template <class Typed>
void LrpModel::with_channel_count(Typed&& typed) const {
  switch (data_.channels) {
    case 1:
      return typed.template operator()<1>();
    case 2:
      return typed.template operator()<2>();
    case 3:
      return typed.template operator()<3>();
    case 4:
      return typed.template operator()<4>();
    default:
      // A material (5 to kMaxChannels channels): one loop whose accumulators hold kMaxChannels,
      // the channel count read at run time.
      return typed.template operator()<kMaxChannels>();
  }
}

void LrpModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                        std::uint32_t seed, ImageView<float> out) const noexcept {
  // One concrete loop per (channel count, filtering): accumulators stay in registers and the
  // point-sample loop carries no footprint work. Dispatch happens once per batch.
  with_channel_count([&]<int Channels>() {
    if (footprints.empty()) {
      if (simd_enabled() && evaluate_simd<Channels, false>(positions, footprints, seed, out))
        return;
      return evaluate_typed<Channels, false, false>(positions, footprints, seed, out, {});
    }
    if (simd_enabled() && evaluate_simd<Channels, true>(positions, footprints, seed, out)) return;
    return evaluate_typed<Channels, true, false>(positions, footprints, seed, out, {});
  });
}

void LrpModel::evaluate_periodic(std::span<const Vec2d> positions,
                                 std::span<const Footprint> footprints, std::uint32_t seed,
                                 ImageView<float> out, Vec2d period) const noexcept {
  with_channel_count([&]<int Channels>() {
    if (footprints.empty())
      return evaluate_typed<Channels, false, true>(positions, footprints, seed, out, period);
    return evaluate_typed<Channels, true, true>(positions, footprints, seed, out, period);
  });
}

std::array<std::uint32_t, kMaxChannels * kMaxStrataPerChannel> LrpModel::stratum_seeds(
    std::uint32_t seed) const noexcept {
  // Each stratum of each channel has its own random stream, so strata and channels are
  // independent noises (equation 2; independent channels in the decorrelated colour space).
  std::array<std::uint32_t, kMaxChannels * kMaxStrataPerChannel> seeds{};
  for (std::size_t s = 0; s < runtime_strata_.size(); ++s)
    seeds[s] = cell_key(channel_stream(runtime_strata_[s].channel),
                        static_cast<std::int64_t>(s) % data_.strata, seed, Stream::phases);
  return seeds;
}

template <int Channels, bool Filtered>
void LrpModel::finish_sample(float (&noise)[Channels], std::span<const Vec2d> positions,
                             std::span<const Footprint> footprints, std::size_t index,
                             std::uint32_t seed, ImageView<float> out) const noexcept {
  const int channels = Channels <= 4 ? Channels : data_.channels;
  if (!data_.structure.empty())
    add_structure(data_.structure, window_coefficients_, static_cast<float>(mean_envelope_),
                  positions[index], Filtered ? &footprints[index] : nullptr, seed, channels, noise);
  const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
  const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
  for (int c = 0; c < channels; ++c) {
    float value = data_.mean[static_cast<std::size_t>(c)];
    for (int k = 0; k < channels; ++k)
      value += data_.colour_basis[static_cast<std::size_t>(c * channels + k)] * noise[k];
    out.at(x, y, c) = value;
  }
}

template <int Channels, bool Filtered, bool Periodic>
void LrpModel::evaluate_typed(std::span<const Vec2d> positions,
                              std::span<const Footprint> footprints, std::uint32_t seed,
                              ImageView<float> out, Vec2d period) const noexcept {
  const auto seeds = stratum_seeds(seed);
  const float mean_envelope = static_cast<float>(mean_envelope_);
  const bool normalise = data_.normalise_envelope;
  const StratumTables tables{data_.substratum_first.data(), data_.substratum_count.data(),
                             data_.frequencies.data(), data_.weights.data()};
  // Periodic: each stratum's lattice in the period (core/periodic.hpp), once per batch.
  constexpr std::size_t kPeriodicStrata = Periodic ? kMaxChannels * kMaxStrataPerChannel : 0;
  std::array<PeriodicAxis, kPeriodicStrata> axes_x{};
  std::array<PeriodicAxis, kPeriodicStrata> axes_y{};
  if constexpr (Periodic)
    for (std::size_t s = 0; s < runtime_strata_.size(); ++s) {
      axes_x[s] = periodic_axis(period.x, runtime_strata_[s].spacing);
      axes_y[s] = periodic_axis(period.y, runtime_strata_[s].spacing);
    }

  for (std::size_t index = 0; index < positions.size(); ++index) {
    const Vec2d p = Periodic ? reduce_position(positions[index], period) : positions[index];
    std::array<float, 4> axes{};
    if constexpr (Filtered)
      axes = {static_cast<float>(footprints[index].dpdx.x),
              static_cast<float>(footprints[index].dpdx.y),
              static_cast<float>(footprints[index].dpdy.x),
              static_cast<float>(footprints[index].dpdy.y)};
    float noise[Channels] = {};
    for (std::size_t s = 0; s < runtime_strata_.size(); ++s) {
      const RuntimeStratum& stratum = runtime_strata_[s];
      if (stratum.amplitude == 0.0f) continue;
      const StratumDraw draw{stratum.inverse_spacing, stratum.spacing_float,
                             stratum.first_substratum, stratum.cosines, seeds[s]};
      StratumSum sum;
      if constexpr (Periodic)
        sum = stratum_sum_periodic<Filtered>(tables, draw, axes_x[s], axes_y[s],
                                             window_coefficients_, p, axes);
      else
        sum = stratum_sum<Filtered>(tables, draw, window_coefficients_, p, axes);
      // The variance of equation (1) at x is A_S^2 J_S / 2 sum_i w_i(x)^2, which varies over a
      // lattice cell (measured in docs/methods/lrp.md); dividing by sqrt(sum_i w_i^2) over its
      // mean makes it constant without changing its mean. The nearest node is within 0.71 of x,
      // so window_square >= w(0.71)^2 > 0.
      noise[stratum.channel] += stratum_term(ScalarOps{}, stratum.amplitude, normalise,
                                             mean_envelope, sum.window_square, sum.sum);
    }
    finish_sample<Channels, Filtered>(noise, positions, footprints, index, seed, out);
  }
}

template <int Channels, bool Filtered>
bool LrpModel::evaluate_simd(std::span<const Vec2d> positions,
                             std::span<const Footprint> footprints, std::uint32_t seed,
                             ImageView<float> out) const noexcept {
  const auto seeds = stratum_seeds(seed);
  std::array<SimdStratum, kMaxChannels * kMaxStrataPerChannel> strata;
  std::size_t count = 0;
  for (std::size_t s = 0; s < runtime_strata_.size(); ++s) {
    const RuntimeStratum& stratum = runtime_strata_[s];
    if (stratum.amplitude == 0.0f) continue;
    strata[count++] = {{stratum.inverse_spacing, stratum.spacing_float, stratum.first_substratum,
                        stratum.cosines, seeds[s]},
                       stratum.amplitude,
                       stratum.channel};
  }
  const RandomStrata random{std::span(strata.data(), count),
                            {data_.substratum_first.data(), data_.substratum_count.data(),
                             data_.frequencies.data(), data_.weights.data()},
                            &window_coefficients_,
                            static_cast<float>(mean_envelope_),
                            data_.normalise_envelope};
  const std::unique_ptr<NodeCache> cache = NodeCache::make(random.strata);
  if (!cache) return false;
  const int channels = Channels <= 4 ? Channels : data_.channels;
  float batch[kSimdBatch * kMaxChannels];
  const auto run = [&](std::size_t first, std::size_t size) {
    random_strata_noise(random, channels, positions.subspan(first, size),
                        Filtered ? footprints.subspan(first, size) : footprints, *cache, batch);
    for (std::size_t i = 0; i < size; ++i) {
      float noise[Channels] = {};
      for (int c = 0; c < channels; ++c)
        noise[c] = batch[i * kMaxChannels + static_cast<std::size_t>(c)];
      finish_sample<Channels, Filtered>(noise, positions, footprints, first + i, seed, out);
    }
  };
  // A grid's samples (a render tile: row-major, out.width per row) are taken in strips
  // kSimdStrip wide, top to bottom, so the nodes a strip sees stay in the cache from row to row
  // even zoomed out; any other batch in chunks. Samples are independent: the order changes no
  // value.
  const auto width = static_cast<std::size_t>(out.width);
  if (width >= 2 * kSimdStrip && positions.size() % width == 0) {
    for (std::size_t x = 0; x < width; x += kSimdStrip)
      for (std::size_t row = 0; row < positions.size(); row += width)
        run(row + x, std::min(kSimdStrip, width - x));
  } else {
    for (std::size_t first = 0; first < positions.size(); first += kSimdBatch)
      run(first, std::min(kSimdBatch, positions.size() - first));
  }
  return true;
}

}  // namespace stochtex::lrp
