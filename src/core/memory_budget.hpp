#pragma once
// The one memory budget of a request (docs/design.md §9): every command estimates the peak of what
// it is asked to do before doing any of it and refuses, with one sentence naming the option to
// change, a request whose estimate exceeds the budget. Readers bound what a file may declare by
// the same budget: a model file holds at most kMaxModelArrayValues (model/model_file.hpp).

#include <cstdint>
#include <functional>
#include <string>

namespace stochtex {

inline constexpr std::uint64_t kMemoryBudgetBytes = std::uint64_t{2} << 30;

// What a command costs before its data: the process, its libraries and small tables. The
// estimates of analysis and compare below add their per-pixel costs to it.
inline constexpr std::uint64_t kFixedPeakBytes = std::uint64_t{32} << 20;

// --threads beyond this is refused: more threads than any machine has cores only costs memory.
inline constexpr int kMaxThreads = 256;

// A CPU render of a width x height image of `channels` channels (a material's may have up to 16):
// the image and its encoded copy (a 16-bit PNG's), 6 bytes a channel and at least 24 a pixel, and
// on each of `threads` threads one tile's samples: a position (16 bytes) and a footprint
// (32 bytes) each, or with supersampling a position and 4 channel values (32 bytes). Threads
// beyond the number of tiles never start.
std::uint64_t render_peak_bytes(int width, int height, int tile, int supersample, int threads,
                                int channels = 4);

// The Gaussian version (ADSN, spectral/adsn.cpp) at width x height of an exemplar of
// exemplar_width x exemplar_height with `channels` channels: its FFT domain, a 7-smooth size of
// at least the output plus the exemplar on each side, holds the noise, two spectra and a plane,
// 24 bytes a pixel; the output image with its encoded copy 24 more a pixel; the exemplar, its
// periodic component and that component's spectra 24 + 8 x channels bytes a pixel. An exemplar of
// 0 x 0 gives the output's share alone, for a check before the exemplar is read.
std::uint64_t gaussian_peak_bytes(int width, int height, int exemplar_width = 0,
                                  int exemplar_height = 0, int channels = 0);

// evaluate() of `points` positions into `channels` channels: kFixedPeakBytes, and a point's
// position (16 bytes) and footprint (32 bytes) as the caller holds them and as evaluate takes them
// (a Python array converted), and its values, 4 bytes a channel.
std::uint64_t evaluate_peak_bytes(std::uint64_t points, int channels);

// The measures of `compare` (metrics/metrics.hpp compare_images): kFixedPeakBytes plus 56 + 12 x
// channels bytes a pixel of the exemplar and of the image together (spectra, the ADSN sample,
// sorted projections). Measured peaks of `stochtex compare`: 56 (grey), 73 (RGB) and 82 (RGBA)
// bytes a pixel for 1024² and 2048² pairs, and as much for pixels of either image.
std::uint64_t compare_peak_bytes(std::uint64_t exemplar_pixels, std::uint64_t image_pixels,
                                 int channels);

// `stochtex mix` (texton noise mixing) of two exemplars whose common size (the centre crop) is
// width x height with `channels` channels, into `steps` textons of support x support:
// kFixedPeakBytes plus 24 + 46 x channels bytes a pixel of the common size (both exemplars read,
// their spectra, tau_0 and one tau_rho, Algorithm 1) and 28 bytes a texton value (the model's
// textons, each step's padded pyramid and the file being written). Measured peaks of `mix` of two
// equal-size images: 20 + 38 c bytes a pixel between 512² and 1024² (grey 58, RGB 134), and 21
// (grey) and 23 (RGB) bytes a texton value at 1024², 48 textons of 512²; the constants add 20 %.
std::uint64_t mix_peak_bytes(int width, int height, int channels, int steps, int support);

// Throws std::invalid_argument: "<request> needs about N GB of memory, more than the budget of
// 2 GiB; <remedy>" when `bytes` exceed kMemoryBudgetBytes.
void check_memory_budget(std::uint64_t bytes, const std::string& request,
                         const std::string& remedy);

// The images a request holds at once, 4 bytes a value (mix's exemplars and mask, report's
// exemplars, the arrays a Python call copies): add() counts one and refuses, with
// check_memory_budget naming it, their sum with kFixedPeakBytes beyond the budget; check(name) is
// add() as an ImageReadLimits::check_declared, called before a file's pixels are decoded.
class HeldImages {
 public:
  void add(int width, int height, int channels, const std::string& name);
  std::function<void(int width, int height, int channels)> check(const std::string& name);

 private:
  std::uint64_t bytes_ = 0;
};

}  // namespace stochtex
