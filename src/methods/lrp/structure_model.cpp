#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/hash.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/structure.hpp"
#include "methods/lrp/tables.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp {
namespace {

// Limits on what a model file may ask of the evaluator (beyond them it is refused).
constexpr int kMaxPeriod = 4096;
constexpr int kMaxStructureCosines = 2000;
constexpr double kMaxStructureValues = 1 << 24;  // floats of the cosine table (64 MiB)
constexpr double kMaxTurbulence = 256.0;
constexpr int kMaxTurbulenceStrata = 16;

bool power_of_two(std::int64_t n) {
  return n > 0 && (n & (n - 1)) == 0;
}

// Floor division and modulo of 64-bit lattice indices (blocks repeat every B nodes).
std::int64_t wrap(std::int64_t index, std::int64_t period) {
  const std::int64_t r = index % period;
  return r < 0 ? r + period : r;
}

// The weight of block i + 1 against block i along one axis of the placement blocks: 0 in the
// middle of block i, 1 in the middle of block i + 1, a smoothstep across a band of kPlacementBlend
// of a block on each side of their border (C1, so the blend adds no crease).
float blend_weight(float t) noexcept {
  float a = (t - 0.5f) * (0.5f / kPlacementBlend) + 0.5f;
  a = a <= 0.0f ? 0.0f : (a >= 1.0f ? 1.0f : a);
  return a * a * (3.0f - 2.0f * a);
}

}  // namespace

void validate_structure(const StructureData& s, int channels) {
  if (s.empty()) {
    if (!s.cosine_table.empty() || !s.turbulence_strata.empty())
      throw std::invalid_argument("lrp: structure arrays without a structure period");
    return;
  }
  if (!power_of_two(s.period) || s.period < 8 || s.period > kMaxPeriod)
    throw std::invalid_argument("lrp: the structure period must be a power of two from 8 to 4096");
  // Blocks are at least 2 pixels wide (structure_analysis.cpp: a block's spectrum is taken on
  // the block and half a block around it, which must start on a pixel).
  if (!power_of_two(s.blocks) || s.blocks > s.period / 2)
    throw std::invalid_argument("lrp: the structure block count is out of range");
  if (s.cosines < 1 || s.cosines > kMaxStructureCosines)
    throw std::invalid_argument("lrp: the structure cosine count is out of range");
  const double values = 4.0 * channels * double(s.blocks) * s.blocks * s.cosines;
  if (values > kMaxStructureValues || s.cosine_table.size() != static_cast<std::size_t>(values))
    throw std::invalid_argument("lrp: the structure cosine table has the wrong size");
  if (!within_model_range(s.cosine_table))
    throw std::invalid_argument(
        "lrp: the structure cosine table has a value that is not finite or beyond +-1e12");
  for (std::size_t k = 0; k < s.cosine_table.size(); k += 4) {
    const float* c = &s.cosine_table[k];
    if (std::abs(c[0]) > 0.5f || std::abs(c[1]) > 0.5f || !(c[2] >= 0.0f) || c[2] > kMaxAmplitude ||
        !(c[3] >= 0.0f && c[3] <= 1.0f))
      throw std::invalid_argument("lrp: a structure cosine is out of range");
  }
  if (!(s.turbulence >= 0.0f && s.turbulence <= kMaxTurbulence))
    throw std::invalid_argument("lrp: the turbulence is out of range");
  if (s.turbulence_strata.size() > static_cast<std::size_t>(kMaxTurbulenceStrata) ||
      (s.turbulence > 0.0f && s.turbulence_strata.empty()))
    throw std::invalid_argument("lrp: the turbulence strata are missing or too many");
  std::size_t substrata = 0;
  for (const TurbulenceStratum& stratum : s.turbulence_strata) {
    if (stratum.cosines < 1 || stratum.cosines > kMaxStructureCosines ||
        !(stratum.spacing >= kMinSpacing && stratum.spacing <= kMaxSpacing) ||
        !(stratum.amplitude >= 0.0f && stratum.amplitude <= kMaxAmplitude))
      throw std::invalid_argument("lrp: a turbulence stratum is out of range");
    substrata += static_cast<std::size_t>(stratum.cosines);
  }
  if (s.turbulence_first.size() != substrata || s.turbulence_count.size() != substrata ||
      s.turbulence_frequencies.size() % 2 != 0 || !within_model_range(s.turbulence_frequencies))
    throw std::invalid_argument("lrp: the turbulence sub-strata do not match its strata");
  check_substrata(s.turbulence_first, s.turbulence_count, s.turbulence_frequencies, "turbulence");
}

void write_structure(const StructureData& s, ModelRecord& record) {
  if (s.empty()) return;
  const std::int64_t rows = static_cast<std::int64_t>(s.cosine_table.size() / 4);
  const auto strata = static_cast<std::int64_t>(s.turbulence_strata.size());
  const auto substrata = static_cast<std::int64_t>(s.turbulence_first.size());
  const auto frequencies = static_cast<std::int64_t>(s.turbulence_frequencies.size() / 2);
  record.scalars["structure_period"] = s.period;
  record.scalars["structure_blocks"] = s.blocks;
  record.scalars["structure_cosines"] = s.cosines;
  record.scalars["placement"] = s.placement ? 1.0 : 0.0;
  record.scalars["turbulence"] = static_cast<double>(s.turbulence);
  record.scalars["turbulence_strata"] = static_cast<double>(strata);
  record.arrays.push_back({"structure_cosines", {rows, 4}, s.cosine_table});
  if (strata == 0) return;
  record.scalars["turbulence_substrata"] = static_cast<double>(substrata);
  record.scalars["turbulence_frequencies"] = static_cast<double>(frequencies);
  std::vector<float> table;
  for (const TurbulenceStratum& stratum : s.turbulence_strata) {
    table.push_back(static_cast<float>(stratum.cosines));
    table.push_back(stratum.spacing);
    table.push_back(stratum.amplitude);
  }
  std::vector<float> ranges;
  for (std::size_t k = 0; k < s.turbulence_first.size(); ++k) {
    ranges.push_back(static_cast<float>(s.turbulence_first[k]));
    ranges.push_back(static_cast<float>(s.turbulence_count[k]));
  }
  record.arrays.push_back({"turbulence_strata", {strata, 3}, std::move(table)});
  record.arrays.push_back({"turbulence_substrata", {substrata, 2}, std::move(ranges)});
  record.arrays.push_back({"turbulence_frequencies", {frequencies, 2}, s.turbulence_frequencies});
}

StructureData read_structure(const ModelRecord& record, int channels, const std::string& source) {
  StructureData s;
  // A model analysed with r = 0 (or written before section 5 existed) has no structure entries.
  if (record.scalars.find("structure_period") == record.scalars.end()) return s;
  const auto read = [&](const char* name, double low, double high) {
    return static_cast<std::int64_t>(record.scalar_in(name, low, high, true, source));
  };
  const std::int64_t period = read("structure_period", 8, kMaxPeriod);
  const std::int64_t blocks = read("structure_blocks", 1, static_cast<double>(period) / 2);
  const std::int64_t cosines = read("structure_cosines", 1, kMaxStructureCosines);
  const std::int64_t rows = channels * blocks * blocks * cosines;
  if (4.0 * static_cast<double>(rows) > kMaxStructureValues)
    throw Error(ErrorCode::format,
                "'" + source + "' declares a structure larger than the limit; the file is corrupt");
  s.period = static_cast<int>(period);
  s.blocks = static_cast<int>(blocks);
  s.cosines = static_cast<int>(cosines);
  s.placement = read("placement", 0, 1) == 1;
  s.turbulence =
      static_cast<float>(record.scalar_in("turbulence", 0, kMaxTurbulence, false, source));
  s.cosine_table = record.array("structure_cosines", {rows, 4}, source).values;
  const std::int64_t strata = read("turbulence_strata", 0, kMaxTurbulenceStrata);
  if (strata > 0) {
    const std::int64_t substrata =
        read("turbulence_substrata", 1, double(kMaxStructureCosines) * kMaxTurbulenceStrata);
    const std::int64_t frequencies = read("turbulence_frequencies", 1, kMaxSubstratumSize * 4.0);
    const NamedArray& table = record.array("turbulence_strata", {strata, 3}, source);
    const NamedArray& ranges = record.array("turbulence_substrata", {substrata, 2}, source);
    s.turbulence_frequencies =
        record.array("turbulence_frequencies", {frequencies, 2}, source).values;
    const auto invalid = [&] {
      return Error(ErrorCode::format, "'" + source +
                                          "' has an invalid lrp turbulence table; re-run "
                                          "`stochtex analyze`");
    };
    for (std::size_t k = 0; k < table.values.size(); k += 3) {
      const float count = table.values[k];
      if (!(count >= 1.0f && count <= kMaxStructureCosines) || count != std::floor(count))
        throw invalid();
      s.turbulence_strata.push_back(
          {static_cast<int>(count), table.values[k + 1], table.values[k + 2]});
    }
    if (!read_substratum_ranges(ranges.values, s.turbulence_first, s.turbulence_count))
      throw invalid();
  }
  return s;
}

void add_fixed_phase(const StructureData& s,
                     const std::array<float, kWindowTerms>& window_coefficients, Vec2d q,
                     const Footprint* footprint, float weight, int channels,
                     float* noise) noexcept {
  // Block nodes sit at the block centres (I + 1/2) b. As for the random strata, nearest_node keeps
  // q = 1e7 as precise as q = 0; blocks repeat every B nodes (the structure image is T-periodic).
  const double side = static_cast<double>(s.period) / s.blocks;
  const auto [cell_x, cell_y, offset_x, offset_y] =
      nearest_node(q.x / side - 0.5, q.y / side - 0.5);
  const auto side_float = static_cast<float>(side);
  const auto per_channel = static_cast<std::size_t>(s.blocks) * s.blocks * s.cosines;
  float axis_a_x = 0.0f, axis_a_y = 0.0f, axis_b_x = 0.0f, axis_b_y = 0.0f;
  if (footprint != nullptr) {
    axis_a_x = static_cast<float>(footprint->dpdx.x);
    axis_a_y = static_cast<float>(footprint->dpdx.y);
    axis_b_x = static_cast<float>(footprint->dpdy.x);
    axis_b_y = static_cast<float>(footprint->dpdy.y);
  }
  float sum[kMaxChannels] = {};
  float window_sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float rx = offset_x - static_cast<float>(dx);
      const float ry = offset_y - static_cast<float>(dy);
      // Delta_R = 2/3 of a block: the window (radius 1.5 Delta_R) reaches one block from its node,
      // exactly the region whose spectrum the block's cosines reproduce. The nearest node is
      // within 0.71 block, where the window is positive, so window_sum > 0.
      const float w =
          window_from_square(window_coefficients, (rx * rx + ry * ry) * kWindowRadiusSquared);
      if (w <= 0.0f) continue;
      const float px = rx * side_float;
      const float py = ry * side_float;
      const std::size_t block = static_cast<std::size_t>(wrap(cell_y + dy, s.blocks)) * s.blocks +
                                static_cast<std::size_t>(wrap(cell_x + dx, s.blocks));
      for (int c = 0; c < channels; ++c) {
        const float* cosine =
            &s.cosine_table[4 * (static_cast<std::size_t>(c) * per_channel + block * s.cosines)];
        float local = 0.0f;
        for (int j = 0; j < s.cosines; ++j, cosine += 4) {
          float value = cosine[2] * cos_turns(cosine[0] * px + cosine[1] * py + cosine[3]);
          if (footprint != nullptr) {
            const float along_a = std::abs(cosine[0] * axis_a_x + cosine[1] * axis_a_y);
            const float along_b = std::abs(cosine[0] * axis_b_x + cosine[1] * axis_b_y);
            value *= clamp_weight(along_a > along_b ? along_a : along_b);
          }
          local += value;
        }
        sum[c] += w * local;
      }
      window_sum += w;
    }
  }
  const float scale = weight / window_sum;
  for (int c = 0; c < channels; ++c) noise[c] += scale * sum[c];
}

float turbulence_noise(const StructureData& s,
                       const std::array<float, kWindowTerms>& window_coefficients,
                       float mean_envelope, Vec2d p, std::uint32_t seed, int axis) noexcept {
  // The local random-phase noise of each turbulence stratum, drawn as LrpModel::evaluate_typed
  // draws a random stratum (eq. 1, section 4.3, envelope normalised), on its own streams.
  const StratumTables tables{s.turbulence_first.data(), s.turbulence_count.data(),
                             s.turbulence_frequencies.data(), nullptr};
  float total = 0.0f;
  std::uint32_t first_substratum = 0;
  for (std::size_t t = 0; t < s.turbulence_strata.size(); ++t) {
    const TurbulenceStratum& stratum = s.turbulence_strata[t];
    const std::uint32_t stratum_seed =
        cell_key(kTurbulenceStreamBase + axis, static_cast<std::int64_t>(t), seed, Stream::phases);
    const auto [sum, window_square] =
        stratum_sum<false>(tables,
                           {1.0 / stratum.spacing, stratum.spacing, first_substratum,
                            static_cast<std::uint32_t>(stratum.cosines), stratum_seed},
                           window_coefficients, p, {});
    total += std::abs(stratum.amplitude * std::sqrt(mean_envelope / window_square) * sum);
    first_substratum += static_cast<std::uint32_t>(stratum.cosines);
  }
  return total;
}

void add_structure(const StructureData& s,
                   const std::array<float, kWindowTerms>& window_coefficients, float mean_envelope,
                   Vec2d p, const Footprint* footprint, std::uint32_t seed, int channels,
                   float* noise) noexcept {
  // Section 5.2: turbulence, x + sigma n_T(x), with n_T taken at the undisplaced, unshifted x
  // (placement "applied first", so the distortion is one continuous field over all blocks),
  // one independent n_T per axis.
  Vec2d q = p;
  if (s.turbulence > 0.0f) {
    const float displacement_x =
        s.turbulence * turbulence_noise(s, window_coefficients, mean_envelope, p, seed, 0);
    const float displacement_y =
        s.turbulence * turbulence_noise(s, window_coefficients, mean_envelope, p, seed, 1);
    q.x += displacement_x;
    q.y += displacement_y;
  }
  if (!s.placement) {
    add_fixed_phase(s, window_coefficients, q, footprint, 1.0f, channels, noise);
    return;
  }
  // Random placement: blocks of half the period T (the paper's x + 1/2 t(floor(2x)) with x in
  // periods) each shift the structure by a hashed offset, uniform over one period. Blocks are
  // found from the undisplaced p. Block i spans [i, i + 1) half-periods; between block centres
  // the blend weight goes from one block to the next near their border.
  const double half_period = 0.5 * s.period;
  const double gx = p.x / half_period - 0.5;
  const double gy = p.y / half_period - 0.5;
  const double base_x = std::floor(gx);
  const double base_y = std::floor(gy);
  const float weight_x = blend_weight(static_cast<float>(gx - base_x));
  const float weight_y = blend_weight(static_cast<float>(gy - base_y));
  const auto block_x = static_cast<std::int64_t>(base_x);
  const auto block_y = static_cast<std::int64_t>(base_y);
  const float weights[2][2] = {
      {(1.0f - weight_x) * (1.0f - weight_y), weight_x * (1.0f - weight_y)},
      {(1.0f - weight_x) * weight_y, weight_x * weight_y}};
  float square_sum = 0.0f;
  for (const auto& row : weights)
    for (const float w : row) square_sum += w * w;
  // Blocks are independent, so a blend of several has the variance sum w^2 times one block's:
  // dividing by sqrt(sum w^2) keeps the variance (the envelope normalisation of the strata).
  const float normalisation = 1.0f / std::sqrt(square_sum);
  for (int ey = 0; ey < 2; ++ey)
    for (int ex = 0; ex < 2; ++ex) {
      const float w = weights[ey][ex];
      if (w <= 0.0f) continue;
      CounterRng rng(cell_key(block_x + ex, block_y + ey, seed, Stream::offsets));
      // One draw per statement (hash.hpp).
      const float shift_x = rng.uniform();
      const float shift_y = rng.uniform();
      const Vec2d shifted{q.x + static_cast<double>(shift_x) * s.period,
                          q.y + static_cast<double>(shift_y) * s.period};
      add_fixed_phase(s, window_coefficients, shifted, footprint, w * normalisation, channels,
                      noise);
    }
}

}  // namespace stochtex::lrp
