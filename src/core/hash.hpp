#pragma once
// Integer hashing and random draws: the randomness spec of docs/design.md §5, written so that the
// GLSL port can mirror it statement for statement (uint32 arithmetic only, which wraps in both
// languages). Reference: Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020.
// The test vectors in tests/unit/hash_test.cpp pin these functions: they must never change, or
// every stored seed renders a different texture.

#include <array>
#include <cstdint>

namespace stochtex {

using Uint4 = std::array<std::uint32_t, 4>;

// PCG RXS-M-XS, one 32-bit word in, one out (Jarzynski & Olano, "pcg").
constexpr std::uint32_t pcg_hash(std::uint32_t v) noexcept {
  const std::uint32_t state = v * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// pcg4d: four words in, four well-mixed words out.
constexpr Uint4 pcg4d(Uint4 v) noexcept {
  for (auto& x : v) x = x * 1664525u + 1013904223u;
  v[0] += v[1] * v[3];
  v[1] += v[2] * v[0];
  v[2] += v[0] * v[1];
  v[3] += v[1] * v[2];
  for (auto& x : v) x ^= x >> 16u;
  v[0] += v[1] * v[3];
  v[1] += v[2] * v[0];
  v[2] += v[0] * v[1];
  v[3] += v[1] * v[2];
  return v;
}

// Streams keep independent uses of the same cell (point process, signs, phases...) uncorrelated.
enum class Stream : std::uint32_t {
  points = 0x9e3779b9u,
  phases = 0x7f4a7c15u,
  offsets = 0x85ebca6bu,
  analysis = 0xc2b2ae35u,    // white noise of the analyses (ADSN, texton initialisation)
  kernels = 0x165667b1u,     // Gabor noise: per-grid seeds and kernel parameters (alias, phase)
  signs = 0xd3a2646cu,       // texton noise (balanced points) and mixing: each impulse's sign
  transforms = 0x27d4eb2fu,  // tiling's artist controls: each patch's rotation and scale
};

// The key of lattice cell (x, y) for a seed and a stream. Cell coordinates are 64-bit signed
// integers in the caller; they enter the hash as their low 32 bits (two's complement), so the
// pattern repeats only after 2^32 cells.
constexpr std::uint32_t cell_key(std::int64_t cell_x, std::int64_t cell_y, std::uint32_t seed,
                                 Stream stream) noexcept {
  return pcg4d({static_cast<std::uint32_t>(cell_x), static_cast<std::uint32_t>(cell_y), seed,
                static_cast<std::uint32_t>(stream)})[0];
}

// The key of 3-D lattice cell (x, y, z), for processes in space (surface noise, docs/surface.md):
// the 2-D key of (x, y) hashed again with z, seed and stream, so no 2-D key or draw changes and
// cells differing only in z get unrelated keys.
constexpr std::uint32_t cell_key(std::int64_t cell_x, std::int64_t cell_y, std::int64_t cell_z,
                                 std::uint32_t seed, Stream stream) noexcept {
  return pcg4d({cell_key(cell_x, cell_y, seed, stream), static_cast<std::uint32_t>(cell_z), seed,
                static_cast<std::uint32_t>(stream)})[0];
}

// Counter-based generator: draw n of a cell is pcg_hash(key ^ pcg_hash(n)), a pure function of
// (key, n). Call next() in its own statement: function-argument evaluation order is unspecified in
// C++, so two draws inside one expression could swap between compilers (and differ from GLSL).
class CounterRng {
 public:
  constexpr explicit CounterRng(std::uint32_t key) noexcept : key_(key) {}

  constexpr std::uint32_t next() noexcept { return pcg_hash(key_ ^ pcg_hash(counter_++)); }
  // Uniform in [0, 1) with 24 random bits, exactly representable as float.
  constexpr float uniform() noexcept {
    return static_cast<float>(next() >> 8u) * (1.0f / 16777216.0f);
  }
  // Passes over the next `draws` draws as if they had been made (the draws after them are the
  // same): what a caller does when it finds it will not use them.
  constexpr void skip(std::uint32_t draws) noexcept { counter_ += draws; }

 private:
  std::uint32_t key_;
  std::uint32_t counter_ = 0;
};

}  // namespace stochtex
