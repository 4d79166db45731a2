#pragma once
// What every method's benchmark needs: corpus exemplars, square crops of them, and the
// nanoseconds-per-sample measure (docs/design.md §10).

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <string_view>

#include "io/image_io.hpp"
#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::bench {

// A corpus image by file name, read once (throws stochtex::Error if it cannot be read).
inline const ImageF& corpus_image(const std::string& name) {
  static std::map<std::string, ImageF> images;
  auto found = images.find(name);
  if (found == images.end())
    found = images.emplace(name, read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/" + name)).first;
  return found->second;
}

// The 512² colour and grey exemplars: analysis sizes crop them, so every size sees the same kind
// of texture.
inline constexpr const char* kColourExemplar = "moss_ground_512.png";
inline constexpr const char* kGreyExemplar = "sand_height_grey_512.png";
inline const ImageF& colour_exemplar() {
  return corpus_image(kColourExemplar);
}
inline const ImageF& grey_exemplar() {
  return corpus_image(kGreyExemplar);
}

// An exemplar of `channels` channels (a material's maps, issue 18) from the colour exemplar:
// side x side, channel c its colour channel c % 3 shifted by 17 (c / 3) pixels, so the channels
// are distinct maps (only their count matters for the costs measured).
inline ImageF stacked_exemplar(int channels, int side) {
  const ImageF& source = colour_exemplar();
  ImageF exemplar(side, side, channels);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < channels; ++c)
        exemplar.at(x, y, c) = source.at((x + 17 * (c / 3)) % side, y, c % 3);
  return exemplar;
}

inline ImageF crop_top_left(const ImageF& image, int side) {
  ImageF result(side, side, image.channels());
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < image.channels(); ++c) result.at(x, y, c) = image.at(x, y, c);
  return result;
}

// Runs body() per iteration and reports items (samples) per second and the counter ns_per_sample,
// from the wall clock: a render's work happens on worker threads, which CPU time would miss.
template <typename Body>
void time_samples(benchmark::State& state, std::int64_t samples_per_iteration, Body&& body) {
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    body();
    benchmark::ClobberMemory();
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  const std::int64_t samples = state.iterations() * samples_per_iteration;
  state.SetItemsProcessed(samples);
  if (samples > 0) state.counters["ns_per_sample"] = elapsed.count() / static_cast<double>(samples);
}

// Times `analyze(method)` on the top-left side x side crop of the corpus image `name`; skips the
// benchmark with the reason when the image cannot be read.
inline void analysis_benchmark(benchmark::State& state, std::string_view method,
                               const std::string& name, int side, const ParamValues& params = {}) {
  ImageF exemplar;
  try {
    exemplar = crop_top_left(corpus_image(name), side);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) {
    Model model = analyze(method, exemplar.view(), params, 0);
    benchmark::DoNotOptimize(model);
  }
}

}  // namespace stochtex::bench
