#pragma once
// Local random-phase noise model (Gilet et al. 2014): per channel of a decorrelated colour space,
// L strata (section 4.1, eq. 2), each with its lattice spacing Delta_S, amplitude A_S (eq. 3) and
// J_S sub-strata, tables of frequencies from which each lattice cell draws one frequency per
// sub-stratum (section 4.3). Plain data; evaluation reads it.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "methods/lrp/structure.hpp"
#include "methods/lrp/window.hpp"
#include "model/model_record.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::lrp {

// The most strata per channel (the parameter `strata`): it sizes the evaluator's stream table and
// node cache.
inline constexpr int kMaxStrataPerChannel = 16;

// Spectral sampling of one stratum S of one channel.
struct Stratum {
  int cosines = 0;  // J_S, also the number of sub-strata
  // float32, as model files store them, so a model renders the same bytes after a round trip.
  float spacing = 1.0f;    // Delta_S, lattice spacing and window scale, exemplar pixels
  float amplitude = 0.0f;  // A_S of equation (3)
};

// The plain data of a model, as analysis builds it and the model file stores it.
struct LrpData {
  int channels = 0;
  int strata = 0;  // L, per channel
  bool normalise_envelope = true;
  std::vector<float> mean;          // channels
  std::vector<float> colour_basis;  // channels x channels, row-major: colour = mean + basis * noise
  std::vector<Stratum> strata_table;  // channels x strata, channel-major
  // Sub-stratum k (in stratum order, J_S per stratum) holds frequencies
  // [substratum_first[k], substratum_first[k] + substratum_count[k]).
  std::vector<std::uint32_t> substratum_first;
  std::vector<std::uint32_t> substratum_count;
  std::vector<float> frequencies;  // (count x 2) cycles per pixel, |f_x|, |f_y| <= 1/2
  // (count) amplitude of each frequency relative to its stratum's A_S (1 as published).
  std::vector<float> weights;
  StructureData structure;  // section 5; empty when r = 0
};

class LrpModel {
 public:
  static constexpr std::string_view kMethodName = "lrp";

  // Validates everything (sizes, ranges, finiteness); throws std::invalid_argument naming the
  // problem.
  explicit LrpModel(LrpData data);

  static LrpModel from_record(const ModelRecord& record, const std::string& source);
  ModelRecord to_record(const ParamValues& params) const;

  int channels() const { return data_.channels; }
  const LrpData& data() const { return data_; }
  // 2 pi int r w^2: the mean over a lattice cell of sum_i w^2(|x - x_i| / Delta) (section 4.3).
  double mean_envelope() const { return mean_envelope_; }

  // n = mean + basis * (sum_S n_S) at each position (equations 1 and 2), with frequencies above
  // the footprint's limit faded out (section 6.4). noexcept, no allocation.
  void evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                std::uint32_t seed, ImageView<float> out) const noexcept;
  // evaluate() for a field of model-space period `period` (core/periodic.hpp): each stratum's
  // lattice spacing becomes period / round(period / spacing) per axis. The scalar loop, for
  // periodic renders (docs/render.md); a model with a structure component (not periodic) is
  // refused before (periodic_refusal). noexcept.
  void evaluate_periodic(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                         std::uint32_t seed, ImageView<float> out, Vec2d period) const noexcept;

 private:
  // Calls typed.template operator()<Channels>() with the loop's channel count for this model.
  template <class Typed>
  void with_channel_count(Typed&& typed) const;
  // The scalar evaluator; Periodic: the field that repeats with `period` (evaluate_periodic).
  template <int Channels, bool Filtered, bool Periodic>
  void evaluate_typed(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                      std::uint32_t seed, ImageView<float> out, Vec2d period) const noexcept;
  // The same samples with the random strata in SIMD lanes (simd.hpp); false, with nothing
  // written, when the strata do not fit its node cache.
  template <int Channels, bool Filtered>
  bool evaluate_simd(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                     std::uint32_t seed, ImageView<float> out) const noexcept;
  // Adds section 5's structure to `noise` (the random strata's sum at positions[index]) and
  // writes mean + basis * noise to the output pixel `index`.
  template <int Channels, bool Filtered>
  void finish_sample(float (&noise)[Channels], std::span<const Vec2d> positions,
                     std::span<const Footprint> footprints, std::size_t index, std::uint32_t seed,
                     ImageView<float> out) const noexcept;
  // The seed of each stratum's random stream for `seed`, in runtime_strata_'s order.
  std::array<std::uint32_t, kMaxChannels * kMaxStrataPerChannel> stratum_seeds(
      std::uint32_t seed) const noexcept;

  LrpData data_;

  // Derived at construction: the flat tables the evaluator reads.
  struct RuntimeStratum {
    double spacing;
    double inverse_spacing;
    float spacing_float;
    float amplitude;
    std::uint32_t first_substratum;
    std::uint32_t cosines;
    int channel;
  };
  std::vector<RuntimeStratum> runtime_strata_;
  std::array<float, kWindowTerms> window_coefficients_{};
  double mean_envelope_ = 0.0;
};

}  // namespace stochtex::lrp
