// Texton noise costs (docs/design.md §10): analysis time for 128², 256² and 512² exemplars, and
// evaluation cost per sample for several texton supports, through `render` at 1 and 2 threads and
// through the batch `evaluate` with point and filtered (scale 8) footprints.

#include <benchmark/benchmark.h>

#include <cstddef>
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

// Analysing the 512² exemplar takes about half a second, so each model is built once and shared by
// every evaluation benchmark that uses it.
const Model& texton_model(int support) {
  static std::map<int, Model> cache;
  auto found = cache.find(support);
  if (found == cache.end()) {
    const Model model = analyze("texton", colour_exemplar().view(), {{"support", support}}, 0,
                                "moss_ground_512.png");
    found = cache.emplace(support, model).first;
  }
  return found->second;
}

void BM_TextonAnalysis(benchmark::State& state) {
  analysis_benchmark(state, "texton", kColourExemplar, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_TextonAnalysis)
    ->ArgName("side")
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The paper's large case (section 9: about 5 s in Matlab for 768 x 512). No corpus image is that
// wide, so the 512 x 512 colour exemplar is extended by its mirror image (only the size matters
// for the cost).
void BM_TextonAnalysis768x512(benchmark::State& state) {
  ImageF exemplar(768, 512, 3);
  try {
    const ImageF& source = colour_exemplar();
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 768; ++x)
        for (int c = 0; c < 3; ++c) exemplar.at(x, y, c) = source.at(x < 512 ? x : 1023 - x, y, c);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  for (auto _ : state) {
    Model model = analyze("texton", exemplar.view(), {}, 0);
    benchmark::DoNotOptimize(model);
  }
}
BENCHMARK(BM_TextonAnalysis768x512)->UseRealTime()->Unit(benchmark::kMillisecond);

// A 256x256 render at scale 1.
void BM_TextonRender(benchmark::State& state) {
  const Model* model = nullptr;
  try {
    model = &texton_model(static_cast<int>(state.range(0)));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  RenderOptions options;
  options.threads = static_cast<int>(state.range(1));
  const Grid grid{{0.0, 0.0}, 1.0, kRenderSide, kRenderSide};
  ImageF out(kRenderSide, kRenderSide, model->channels());
  time_samples(state, kRenderSamples, [&] { render(*model, grid, kSeed, out.view(), options); });
}
BENCHMARK(BM_TextonRender)
    ->ArgNames({"support", "threads"})
    ->ArgsProduct({{32, 64, 128, 256}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Materials (issue 18): the cost per sample of N channels analysed jointly, point samples of a
// 256x256 grid on one thread, on a 256x256 stacked_exemplar. Lanes (texton_lanes): 1-4 channels
// their own count, then 8, 12, 16.
const Model& material_model(int channels) {
  static std::map<int, Model> cache;
  auto found = cache.find(channels);
  if (found == cache.end())
    found =
        cache.emplace(channels, analyze("texton", stacked_exemplar(channels, 256).view(), {}, 0))
            .first;
  return found->second;
}

// The batch API on one thread, with the positions of a 256x256 grid at `scale`: scale 1 without
// footprints (point samples), scale 8 with the footprints of the grid (prefiltered textons). The
// model: model_of(the benchmark's argument).
void evaluate_batch(benchmark::State& state, double scale, bool filtered,
                    const Model& (*model_of)(int) = texton_model) {
  const Model* model = nullptr;
  try {
    model = &model_of(static_cast<int>(state.range(0)));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::vector<Vec2d> positions;
  positions.reserve(static_cast<std::size_t>(kRenderSamples));
  for (int j = 0; j < kRenderSide; ++j)
    for (int i = 0; i < kRenderSide; ++i)
      positions.push_back({scale * (i + 0.5), scale * (j + 0.5)});
  std::vector<Footprint> footprints;
  if (filtered) footprints.assign(positions.size(), Footprint{{scale, 0.0}, {0.0, scale}});
  ImageF out(1, kRenderSide * kRenderSide, model->channels());
  time_samples(state, kRenderSamples,
               [&] { evaluate(*model, positions, footprints, kSeed, out.view()); });
}

void BM_TextonEvaluatePoint(benchmark::State& state) {
  evaluate_batch(state, 1.0, false);
}
BENCHMARK(BM_TextonEvaluatePoint)
    ->ArgName("support")
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_TextonEvaluateFiltered8(benchmark::State& state) {
  evaluate_batch(state, 8.0, true);
}
BENCHMARK(BM_TextonEvaluateFiltered8)
    ->ArgName("support")
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_TextonEvaluateChannels(benchmark::State& state) {
  evaluate_batch(state, 1.0, false, material_model);
}
BENCHMARK(BM_TextonEvaluateChannels)
    ->ArgName("channels")
    ->Arg(3)
    ->Arg(4)
    ->Arg(8)
    ->Arg(9)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
