// Gabor noise by example costs (docs/design.md §10): analysis time for 128², 256² and 512²
// exemplars (the paper's Matlab takes about 2 minutes for 128² grey, section 9.1), and evaluation
// cost per sample against the impulse budget N (the paper: roughly linear in N), point-sampled and
// with scale-8 footprints, on one thread through the batch `evaluate`.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"

namespace {

using namespace stochtex;
using namespace stochtex::bench;

constexpr int kSide = 128;
constexpr std::int64_t kSamples = std::int64_t{kSide} * kSide;
constexpr std::uint32_t kSeed = 7;

void BM_GaborAnalysisGrey(benchmark::State& state) {
  analysis_benchmark(state, "gabor", kGreyExemplar, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_GaborAnalysisGrey)
    ->ArgName("side")
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_GaborAnalysisColour(benchmark::State& state) {
  analysis_benchmark(state, "gabor", kColourExemplar, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_GaborAnalysisColour)
    ->ArgName("side")
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// One model per budget, analysed once from the 128² colour crop and shared.
const Model& model_with_budget(int impulses) {
  static std::map<int, Model> cache;
  auto found = cache.find(impulses);
  if (found == cache.end()) {
    const ImageF exemplar = crop_top_left(colour_exemplar(), 128);
    found = cache.emplace(impulses, analyze("gabor", exemplar.view(), {{"impulses", impulses}}, 0))
                .first;
  }
  return found->second;
}

void evaluate_batch(benchmark::State& state, double scale, bool filtered) {
  const Model* model = nullptr;
  try {
    model = &model_with_budget(static_cast<int>(state.range(0)));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::vector<Vec2d> positions;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) positions.push_back({scale * (i + 0.5), scale * (j + 0.5)});
  std::vector<Footprint> footprints;
  if (filtered) footprints.assign(positions.size(), Footprint{{scale, 0.0}, {0.0, scale}});
  ImageF out(kSide * kSide, 1, model->channels());
  time_samples(state, kSamples,
               [&] { evaluate(*model, positions, footprints, kSeed, out.view()); });
}

void BM_GaborEvaluatePoint(benchmark::State& state) {
  evaluate_batch(state, 1.0, false);
}
BENCHMARK(BM_GaborEvaluatePoint)
    ->ArgName("impulses")
    ->Arg(64)
    ->Arg(256)
    ->Arg(1024)
    ->Arg(4096)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_GaborEvaluateFiltered8(benchmark::State& state) {
  evaluate_batch(state, 8.0, true);
}
BENCHMARK(BM_GaborEvaluateFiltered8)
    ->ArgName("impulses")
    ->Arg(1024)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Cost per sample against the channel count at the default budget N = 1024: the budget is split
// over the (channel, band) grids, so the kernels per sample stay ~2N; what grows with the
// channels is the grids' cell visits and the mixing back to the exemplar's channels (n^2).
void BM_GaborEvaluateChannels(benchmark::State& state) {
  static std::map<int, Model> cache;
  const auto channels = static_cast<int>(state.range(0));
  if (!cache.contains(channels)) {
    try {
      cache.emplace(channels, analyze("gabor", stacked_exemplar(channels, kSide).view(), {}, 0));
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return;
    }
  }
  const Model& model = cache.at(channels);
  std::vector<Vec2d> positions;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) positions.push_back({i + 0.5, j + 0.5});
  ImageF out(kSide * kSide, 1, channels);
  time_samples(state, kSamples, [&] { evaluate(model, positions, {}, kSeed, out.view()); });
}
BENCHMARK(BM_GaborEvaluateChannels)
    ->ArgName("channels")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Surface Gabor noise (section 9.1, docs/surface.md) per point of the plane z = 7 with the
// frame (e_x, e_y), point-sampled at the default budget and surface_mni (60), against
// simd: 0 = the scalar reference, 1 = the best CPU target (gabor/simd.hpp surface_impulse_sum).
// The 3-D process visits about six times the planar noise's impulses per grid, most of them
// rejected by the tent or the envelope.
void BM_GaborSurfacePoint(benchmark::State& state) {
  const Model* model = nullptr;
  try {
    model = &model_with_budget(1024);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  constexpr int kPointSide = 32;
  std::vector<SurfacePoint> points;
  for (int j = 0; j < kPointSide; ++j)
    for (int i = 0; i < kPointSide; ++i)
      points.push_back({{i + 0.5, j + 0.5, 7.0}, {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, {}, {}});
  const CpuTarget target =
      state.range(0) != 0 ? available_cpu_targets().back() : CpuTarget::reference;
  set_cpu_target(target);
  state.SetLabel(std::string(cpu_target_name(target)));
  ImageF out(1, static_cast<int>(points.size()), model->channels());
  time_samples(state, static_cast<std::int64_t>(points.size()),
               [&] { evaluate_surface(*model, points, {}, kSeed, out.view()); });
  set_cpu_target(available_cpu_targets().back());
}
BENCHMARK(BM_GaborSurfacePoint)
    ->ArgName("simd")
    ->Arg(0)
    ->Arg(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
