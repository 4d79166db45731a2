#pragma once
// Checks shared by the tables of random strata that a model file carries: the noise's
// (LrpData: substratum_first/count, frequencies) and the turbulence's (StructureData).

#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace stochtex::lrp {

// A frequency is picked by multiply-shift on 20 random bits (stratum_sum, evaluate.hpp), so a
// sub-stratum holds at most 2^20 frequencies; analysis builds at most T^2 / 2 (T <= 1024).
inline constexpr std::uint32_t kMaxSubstratumSize = 1u << 20;

// Throws std::invalid_argument naming `table` unless every sub-stratum k, [first[k], first[k] +
// count[k]), is non-empty, at most kMaxSubstratumSize long and inside `frequencies` ((f_x, f_y)
// pairs), and every frequency is at most the Nyquist limit 1/2.
inline void check_substrata(std::span<const std::uint32_t> first,
                            std::span<const std::uint32_t> count,
                            std::span<const float> frequencies, const std::string& table) {
  const std::size_t frequency_count = frequencies.size() / 2;
  for (std::size_t k = 0; k < first.size(); ++k)
    if (count[k] < 1 || count[k] > kMaxSubstratumSize || first[k] >= frequency_count ||
        count[k] > frequency_count - first[k])
      throw std::invalid_argument("lrp: a sub-stratum of the " + table +
                                  " lies outside its frequency table");
  for (const float f : frequencies)
    if (std::abs(f) > 0.5f)
      throw std::invalid_argument("lrp: a frequency of the " + table +
                                  " lies above the Nyquist limit 1/2");
}

// Appends the (first, count) pairs of a model file's float array to `first` and `count`; false
// when one is not an integer in [0, 2^24) (the integers float32 holds exactly).
inline bool read_substratum_ranges(std::span<const float> ranges, std::vector<std::uint32_t>& first,
                                   std::vector<std::uint32_t>& count) {
  for (std::size_t k = 0; k + 1 < ranges.size(); k += 2) {
    for (const float value : {ranges[k], ranges[k + 1]})
      if (!(value >= 0.0f && value < 16777216.0f) || value != std::floor(value)) return false;
    first.push_back(static_cast<std::uint32_t>(ranges[k]));
    count.push_back(static_cast<std::uint32_t>(ranges[k + 1]));
  }
  return true;
}

}  // namespace stochtex::lrp
