// Local random-phase noise costs (DESIGN.md section 10): analysis time for 128², 256² and 512²
// exemplars, and evaluation cost per sample for J = 10, 50, 100 cosines. The paper (section 6.2)
// puts the cost at 9 (J + L) special-function calls (cosines and windows) per channel; the
// `ns_per_call` counter divides the time per sample by that count, so a constant value across J
// shows the cost follows it.

#include <benchmark/benchmark.h>

#include <chrono>
#include <exception>
#include <map>
#include <string>
#include <utility>

#include "io/image_io.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;

constexpr int kRenderSide = 128;
constexpr std::uint32_t kSeed = 7;

const ImageF& grey_exemplar() {
  static const ImageF image =
      read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/sand_height_grey_512.png");
  return image;
}

ImageF crop_top_left(const ImageF& image, int side) {
  ImageF result(side, side, image.channels());
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < image.channels(); ++c) result.at(x, y, c) = image.at(x, y, c);
  return result;
}

void BM_LrpAnalysis(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  ImageF exemplar;
  try {
    exemplar = crop_top_left(grey_exemplar(), side);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) {
    Model model = analyze("lrp", exemplar.view(), {}, 0);
    benchmark::DoNotOptimize(model);
  }
}
BENCHMARK(BM_LrpAnalysis)
    ->ArgName("side")
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// One thread, point samples of a 128x128 grid, grey exemplar (one channel), L = 4.
void BM_LrpRender(benchmark::State& state) {
  const int cosines = static_cast<int>(state.range(0));
  Model model;
  try {
    model = analyze("lrp", crop_top_left(grey_exemplar(), 256).view(),
                    {{"cosines", static_cast<double>(cosines)}}, 0);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  RenderOptions options;
  options.threads = 1;
  options.filter = false;
  const Grid grid{{0.0, 0.0}, 1.0, kRenderSide, kRenderSide};
  ImageF out(kRenderSide, kRenderSide, 1);
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    render(model, grid, kSeed, out.view(), options);
    benchmark::ClobberMemory();
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  const double samples = static_cast<double>(state.iterations()) * kRenderSide * kRenderSide;
  state.SetItemsProcessed(state.iterations() * kRenderSide * kRenderSide);
  if (samples > 0) {
    const double per_sample = elapsed.count() / samples;
    state.counters["ns_per_sample"] = per_sample;
    state.counters["ns_per_call"] = per_sample / (9.0 * (cosines + 4));
  }
}
BENCHMARK(BM_LrpRender)
    ->ArgName("cosines")
    ->Arg(10)
    ->Arg(50)
    ->Arg(100)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
