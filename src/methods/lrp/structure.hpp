#pragma once
// Structure preservation of local random-phase noise (section 5 of Gilet et al. 2014): the
// fixed-phase region R of the spectrum (eq. 4) approximated by J_R = rJ cosines per block of a
// subdivided structure image (section 5.3), evaluated at a position distorted by turbulence and
// shifted by random placement (section 5.2). Plain data and a runtime evaluator in the restricted
// subset of docs/design.md §4; structure_analysis.cpp builds the data.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "methods/lrp/window.hpp"
#include "model/model_record.hpp"
#include "stochtex/model.hpp"

namespace stochtex::lrp {

// The numbers of section 5 that are ours where the paper is silent (docs/methods/lrp.md).
// Random placement (section 5.2) shifts blocks of half the structure period; neighbouring blocks
// are blended over this fraction of a block on each side of their border (the paper blends blocks
// but does not say how wide), with weights normalised by sqrt(sum w^2) so the variance is kept.
inline constexpr float kPlacementBlend = 0.125f;
// The turbulence noise n_T = sum_S |n_S| (section 5.2: "a rough stratification and a low cosine
// budget is actually sufficient"): this many strata and cosines in all, per displacement axis.
inline constexpr int kTurbulenceStrata = 2;
inline constexpr int kTurbulenceCosines = 8;
// Each turbulence axis has its own stream, keyed like a colour channel 4 and 5, so n_T is
// independent of the noise it distorts; the channels of a material from 4 on skip those keys
// (channel_stream).
inline constexpr std::int64_t kTurbulenceStreamBase = 4;
inline constexpr std::int64_t kTurbulenceAxes = 2;

// The key of channel c's random strata: c itself for channels 0 to 3 (the streams of every 1-4
// channel model), c + 2 from channel 4 on, past the turbulence's two axes.
constexpr std::int64_t channel_stream(int channel) {
  return channel < kTurbulenceStreamBase ? channel : channel + kTurbulenceAxes;
}

// One stratum of the turbulence noise (the same sampling as a random stratum, section 4.3).
struct TurbulenceStratum {
  int cosines = 0;         // J_S, also the number of sub-strata
  float spacing = 1.0f;    // Delta_S, exemplar pixels
  float amplitude = 0.0f;  // A_S, scaled so that the strata sum to unit variance
};

// The fixed-phase structure of one model; period == 0 means none (r = 0).
struct StructureData {
  int period = 0;   // T, side of the structure image in exemplar pixels (a power of two)
  int blocks = 0;   // B, blocks per side after the subdivision of section 5.3; side T / B
  int cosines = 0;  // J_R per block and channel
  bool placement = false;
  float turbulence = 0.0f;  // sigma of section 5.2, exemplar pixels
  // channels x B x B x J_R cosines (block row-major), 4 floats each: f_x, f_y (cycles per pixel),
  // amplitude, phase in turns relative to the block's lattice node.
  std::vector<float> cosine_table;
  // The turbulence noise: a grey stratified LRP noise of the whole spectrum whose strata sum to
  // unit variance; sub-strata and frequencies in
  // the layout of LrpData's substratum_first / substratum_count / frequencies.
  std::vector<TurbulenceStratum> turbulence_strata;
  std::vector<std::uint32_t> turbulence_first;
  std::vector<std::uint32_t> turbulence_count;
  std::vector<float> turbulence_frequencies;

  bool empty() const { return period == 0; }
};

// Throws std::invalid_argument naming the problem (sizes, ranges, finiteness).
void validate_structure(const StructureData& structure, int channels);
// The record entries of a structure (nothing when empty) and back; `read` refuses a hostile file
// with stochtex::Error before allocating.
void write_structure(const StructureData& structure, ModelRecord& record);
StructureData read_structure(const ModelRecord& record, int channels, const std::string& source);

// Fixed-phase structure n_R of eq. (4) at position `q` (exemplar pixels), added to noise[0..C):
// each block's lattice node carries its J_R cosines, windowed by the Kaiser-Bessel window of
// radius one block (Delta_R = 2/3 block) and normalised by the sum of the windows, so the blocks
// form a partition of unity (section 5.3: "n_R is computed by block and re-assembled"). `weight`
// scales the contribution; `footprint` (may be null) fades frequencies out (section 6.4).
void add_fixed_phase(const StructureData& structure,
                     const std::array<float, kWindowTerms>& window_coefficients, Vec2d q,
                     const Footprint* footprint, float weight, int channels, float* noise) noexcept;

// The whole of section 5 at position p: turbulence displacement sigma (n_T,x(p), n_T,y(p)) and
// random placement, then add_fixed_phase. Pure function of (structure, p, footprint, seed).
void add_structure(const StructureData& structure,
                   const std::array<float, kWindowTerms>& window_coefficients, float mean_envelope,
                   Vec2d p, const Footprint* footprint, std::uint32_t seed, int channels,
                   float* noise) noexcept;

// The turbulence n_T = sum_S |n_S| of one axis at p (section 5.2), exposed for tests.
float turbulence_noise(const StructureData& structure,
                       const std::array<float, kWindowTerms>& window_coefficients,
                       float mean_envelope, Vec2d p, std::uint32_t seed, int axis) noexcept;

}  // namespace stochtex::lrp
