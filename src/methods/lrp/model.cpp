#include "methods/lrp/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/hash.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/params.hpp"
#include "stochtex/error.hpp"

namespace stochtex::lrp {
namespace {

// Limits on what a model may ask of the evaluator; beyond them a model file is rejected.
constexpr int kMaxChannels = 4;
constexpr double kMinSpacing = 0.25;  // Delta_S = T sqrt(J_S / (2 |S|)) >= 1/2 for any stratum
constexpr double kMaxSpacing = 1e6;
constexpr double kMaxAmplitude = 1e6;
// w_f^2 = n_k J_S P'(f) / E_S <= 2^20 * 2000 (analysis.cpp, frequency_weights).
constexpr double kMaxWeight = 1e5;
// A frequency is picked by multiply-shift on 20 random bits (model.cpp, evaluate_typed), so a
// sub-stratum holds at most 2^20 frequencies; analysis builds at most T^2 / 2 (T <= 1024).
constexpr std::uint32_t kMaxSubstratumSize = 1u << 20;

const ParamInfo& param(std::string_view name) {
  return *std::find_if(kParams.begin(), kParams.end(),
                       [&](const ParamInfo& p) { return p.name == name; });
}

bool finite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

}  // namespace

LrpModel::LrpModel(LrpData data) : data_(std::move(data)) {
  const int channels = data_.channels;
  const int strata = data_.strata;
  if (channels < 1 || channels > kMaxChannels)
    throw std::invalid_argument("lrp: channels must be 1 to 4");
  if (strata < param("strata").min_value || strata > param("strata").max_value)
    throw std::invalid_argument("lrp: the number of strata is out of range");
  const auto channel_count = static_cast<std::size_t>(channels);
  if (data_.mean.size() != channel_count || data_.colour_basis.size() != channel_count * channels)
    throw std::invalid_argument("lrp: the mean or colour basis has the wrong size");
  if (!finite(data_.mean) || !finite(data_.colour_basis) || !finite(data_.frequencies))
    throw std::invalid_argument("lrp: non-finite mean, colour basis or frequency");
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
  for (std::size_t k = 0; k < substrata; ++k) {
    const std::uint32_t first = data_.substratum_first[k];
    const std::uint32_t count = data_.substratum_count[k];
    if (count < 1 || count > kMaxSubstratumSize || first >= frequency_count ||
        count > frequency_count - first)
      throw std::invalid_argument("lrp: a sub-stratum lies outside the frequency table");
  }
  for (const float f : data_.frequencies)
    if (std::abs(f) > 0.5f)
      throw std::invalid_argument("lrp: a frequency lies above the Nyquist limit 1/2");
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
  const auto frequencies = read("frequencies", 1, kMaxSubstratumSize * 4.0);
  const NamedArray& mean = record.array("mean", {channels}, source);
  const NamedArray& basis = record.array("colour_basis", {channels, channels}, source);
  const NamedArray& table = record.array("strata", {channels * strata, 3}, source);
  const NamedArray& ranges = record.array("substrata", {substrata, 2}, source);
  const NamedArray& frequency = record.array("frequencies", {frequencies, 2}, source);
  const NamedArray& weights = record.array("weights", {frequencies}, source);
  if (!finite(table.values) || !finite(ranges.values)) throw invalid("strata table");

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
  for (std::size_t k = 0; k < ranges.values.size(); k += 2) {
    const float first = ranges.values[k];
    const float count = ranges.values[k + 1];
    // Integers below 2^24 are exact in float32.
    if (first != std::floor(first) || count != std::floor(count) || first < 0 || count < 0 ||
        first >= 16777216.0f || count >= 16777216.0f)
      throw invalid("sub-stratum range");
    data.substratum_first.push_back(static_cast<std::uint32_t>(first));
    data.substratum_count.push_back(static_cast<std::uint32_t>(count));
  }
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

void LrpModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                        std::uint32_t seed, ImageView<float> out) const noexcept {
  // One concrete loop per (channel count, filtering): accumulators stay in registers and the
  // point-sample loop carries no footprint work. Dispatch happens once per batch.
  const auto with_channels = [&]<int Channels>() {
    if (footprints.empty())
      return evaluate_typed<Channels, false>(positions, footprints, seed, out);
    return evaluate_typed<Channels, true>(positions, footprints, seed, out);
  };
  switch (data_.channels) {
    case 1:
      return with_channels.template operator()<1>();
    case 2:
      return with_channels.template operator()<2>();
    case 3:
      return with_channels.template operator()<3>();
    default:
      return with_channels.template operator()<4>();
  }
}

template <int Channels, bool Filtered>
void LrpModel::evaluate_typed(std::span<const Vec2d> positions,
                              std::span<const Footprint> footprints, std::uint32_t seed,
                              ImageView<float> out) const noexcept {
  // Each stratum of each channel has its own random stream, so strata and channels are
  // independent noises (equation 2; independent channels in the decorrelated colour space).
  constexpr std::size_t kMaxStrata = 4 * 16;
  std::array<std::uint32_t, kMaxStrata> stratum_seeds{};
  for (std::size_t s = 0; s < runtime_strata_.size(); ++s)
    stratum_seeds[s] = cell_key(runtime_strata_[s].channel,
                                static_cast<std::int64_t>(s) % data_.strata, seed, Stream::phases);
  const float mean_envelope = static_cast<float>(mean_envelope_);
  const bool normalise = data_.normalise_envelope;
  const std::uint32_t* substratum_first = data_.substratum_first.data();
  const std::uint32_t* substratum_count = data_.substratum_count.data();
  const float* frequencies = data_.frequencies.data();
  const float* weights = data_.weights.data();

  for (std::size_t index = 0; index < positions.size(); ++index) {
    const Vec2d p = positions[index];
    float axis_a_x = 0.0f, axis_a_y = 0.0f, axis_b_x = 0.0f, axis_b_y = 0.0f;
    if constexpr (Filtered) {
      axis_a_x = static_cast<float>(footprints[index].dpdx.x);
      axis_a_y = static_cast<float>(footprints[index].dpdx.y);
      axis_b_x = static_cast<float>(footprints[index].dpdy.x);
      axis_b_y = static_cast<float>(footprints[index].dpdy.y);
    }
    float noise[Channels] = {};
    for (std::size_t s = 0; s < runtime_strata_.size(); ++s) {
      const RuntimeStratum& stratum = runtime_strata_[s];
      if (stratum.amplitude == 0.0f) continue;
      // Lattice nodes on the integer multiples of Delta_S (section 3.4). The nearest node is a
      // 64-bit integer and the offset from it is taken in double before going to float, so
      // p = 1e7 is as precise as p = 0 (DESIGN.md section 4). With |offset| <= 1/2 per axis, the
      // window (radius 1.5) reaches the 3 x 3 nodes around it only: I = 9 in equation (1).
      const double u = p.x * stratum.inverse_spacing;
      const double v = p.y * stratum.inverse_spacing;
      const double node_x = std::floor(u + 0.5);
      const double node_y = std::floor(v + 0.5);
      const auto cell_x = static_cast<std::int64_t>(node_x);
      const auto cell_y = static_cast<std::int64_t>(node_y);
      const auto offset_x = static_cast<float>(u - node_x);
      const auto offset_y = static_cast<float>(v - node_y);
      float sum = 0.0f;
      float window_square = 0.0f;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const float rx = offset_x - static_cast<float>(dx);
          const float ry = offset_y - static_cast<float>(dy);
          const float r2 = rx * rx + ry * ry;
          const float w = window_from_square(window_coefficients_, r2);
          if (w <= 0.0f) continue;
          // Phases are taken relative to the node, cos(2 pi f.(x - x_i) + phi): with phi
          // uniform this is the same random field as cos(2 pi f.x + phi) (section 3.2's Gabor
          // convention), and x - x_i stays small wherever x is.
          const float px = rx * stratum.spacing_float;
          const float py = ry * stratum.spacing_float;
          CounterRng rng(cell_key(cell_x + dx, cell_y + dy, stratum_seeds[s], Stream::phases));
          float local = 0.0f;
          for (std::uint32_t j = 0; j < stratum.cosines; ++j) {
            // One draw per cosine, in its own statement (hash.hpp): its top 12 bits are the
            // phase (a 1/4096 turn grid), its low 20 bits pick one frequency of sub-stratum j
            // uniformly by multiply-shift (section 4.3; bias <= count / 2^20).
            const std::uint32_t draw = rng.next();
            const std::uint32_t k = stratum.first_substratum + j;
            const std::uint32_t pick =
                substratum_first[k] +
                static_cast<std::uint32_t>(
                    (static_cast<std::uint64_t>(draw & 0xfffffu) * substratum_count[k]) >> 20u);
            const float fx = frequencies[2 * pick];
            const float fy = frequencies[2 * pick + 1];
            const float phase = static_cast<float>(draw >> 20u) * (1.0f / 4096.0f);
            float c = cos_turns(fx * px + fy * py + phase);
            if constexpr (Filtered) {
              const float along_a = std::abs(fx * axis_a_x + fy * axis_a_y);
              const float along_b = std::abs(fx * axis_b_x + fy * axis_b_y);
              c *= clamp_weight(along_a > along_b ? along_a : along_b);
            }
            local += weights[pick] * c;
          }
          sum += w * local;
          window_square += w * w;
        }
      }
      float scale = stratum.amplitude;
      // The variance of equation (1) at x is A_S^2 J_S / 2 sum_i w_i(x)^2, which varies over a
      // lattice cell (measured in docs/methods/lrp.md); dividing by sqrt(sum_i w_i^2) over its
      // mean makes it constant without changing its mean. The nearest node is within 0.71 of x,
      // so window_square >= w(0.71)^2 > 0.
      if (normalise) scale *= std::sqrt(mean_envelope / window_square);
      noise[stratum.channel] += scale * sum;
    }
    if (!data_.structure.empty())
      add_structure(data_.structure, window_coefficients_, mean_envelope, p,
                    Filtered ? &footprints[index] : nullptr, seed, Channels, noise);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    for (int c = 0; c < Channels; ++c) {
      float value = data_.mean[static_cast<std::size_t>(c)];
      for (int k = 0; k < Channels; ++k)
        value += data_.colour_basis[static_cast<std::size_t>(c * Channels + k)] * noise[k];
      out.at(x, y, c) = value;
    }
  }
}

}  // namespace stochtex::lrp
