// Histogram-preserving tiling and blending costs (docs/design.md §10): analysis time for 128²,
// 256² and 512² colour exemplars with both transports, the load of a 512² colour model file (its
// prefiltered tables are rebuilt, pyramid.hpp), and evaluation cost per sample through
// `render` at 1 and 2 threads for the Gaussian fast path (section 6.1: 3 fetches) and the full
// path (3 fetches + one T^-1 look-up), point-sampled and filtered (scale 8).

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;
using namespace stochtex::bench;

constexpr int kRenderSide = 256;
constexpr std::int64_t kRenderSamples = std::int64_t{kRenderSide} * kRenderSide;
constexpr std::uint32_t kSeed = 7;

// Models of the 256² crop, built once: 0 sliced transport (3-D table), 1 per-channel transport,
// 2 Gaussian fast path.
const Model& tiling_model(int variant) {
  static std::map<int, Model> cache;
  auto found = cache.find(variant);
  if (found == cache.end()) {
    const ImageF exemplar = crop_top_left(colour_exemplar(), 256);
    const ParamValues params = variant == 2   ? ParamValues{{"blend", 1}}
                               : variant == 1 ? ParamValues{{"transport", 1}}
                                              : ParamValues{};
    found = cache.emplace(variant, analyze("tiling", exemplar.view(), params, 0)).first;
  }
  return found->second;
}

void BM_TilingAnalysis(benchmark::State& state) {
  analysis_benchmark(state, "tiling", kColourExemplar, static_cast<int>(state.range(0)),
                     {{"transport", static_cast<double>(state.range(1))}});
}
BENCHMARK(BM_TilingAnalysis)
    ->ArgNames({"side", "transport"})
    ->ArgsProduct({{128, 256, 512}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Reading a model file of the 512² colour exemplar from memory: transport 0 (sliced, a 3-D table)
// or 1 (per channel, three 1-D tables).
void BM_TilingLoad(benchmark::State& state) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = serialize_model(analyze("tiling", colour_exemplar().view(),
                                    {{"transport", static_cast<double>(state.range(0))}}, 0));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(deserialize_model(bytes, "bench.stx"));
}
BENCHMARK(BM_TilingLoad)
    ->ArgNames({"transport"})
    ->DenseRange(0, 1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// A 256x256 render: variant (0 full path with the 3-D table, 1 full path with 1-D tables,
// 2 Gaussian fast path), threads, scale (1 point-sized footprints, 8 minified).
void BM_TilingRender(benchmark::State& state) {
  const Model* model = nullptr;
  try {
    model = &tiling_model(static_cast<int>(state.range(0)));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  RenderOptions options;
  options.threads = static_cast<int>(state.range(1));
  const Grid grid{{0.0, 0.0}, static_cast<double>(state.range(2)), kRenderSide, kRenderSide};
  ImageF out(kRenderSide, kRenderSide, model->channels());
  time_samples(state, kRenderSamples, [&] { render(*model, grid, kSeed, out.view(), options); });
}
BENCHMARK(BM_TilingRender)
    ->ArgNames({"variant", "threads", "scale"})
    ->ArgsProduct({{0, 1, 2}, {1, 2}, {1, 8}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
