// The renderer's own costs, whatever the method: how the tile size changes the throughput of a
// threaded render (it never changes the output). Also the one main() of stochtex_bench, so that
// each method's benchmarks live in their own file.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <string>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;

constexpr int kSide = 256;

// A quick texton model (support 64 on a 256² colour exemplar) stands in for any method.
const Model& render_model() {
  static const Model model = [] {
    return analyze("texton", bench::corpus_image("grass_lawn_256.png").view(), {{"support", 64}}, 0,
                   "grass_lawn_256.png");
  }();
  return model;
}

void BM_RenderTileSize(benchmark::State& state) {
  const Model* model = nullptr;
  try {
    model = &render_model();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  RenderOptions options;
  options.threads = 2;
  options.tile_size = static_cast<int>(state.range(0));
  const Grid grid{{0.0, 0.0}, 1.0, kSide, kSide};
  ImageF out(kSide, kSide, model->channels());
  for (auto _ : state) {
    render(*model, grid, 7, out.view(), options);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t{kSide} * kSide);
}
BENCHMARK(BM_RenderTileSize)
    ->ArgName("tile")
    ->Arg(16)
    ->Arg(64)
    ->Arg(256)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
