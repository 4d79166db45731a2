// Local random-phase noise costs (docs/design.md §10): analysis time for 128², 256² and 512²
// exemplars, and evaluation cost per sample for J = 10, 50, 100 cosines. The paper (section 6.2)
// puts the cost at 9 (J + L) special-function calls (cosines and windows) per channel; the
// `ns_per_call` counter divides the time per sample by that count, so a constant value across J
// shows the cost follows it. BM_LrpStructureRender adds section 5: r = 0.1 and 0.3 with J = 50,
// fixed phases alone and with turbulence and random placement (the paper's table 1: fixed phases
// cost nothing more, random placement 10-20%). BM_LrpMaterialRender: 4, 8 and 16 channels.

#include <benchmark/benchmark.h>

#include <exception>
#include <string>
#include <utility>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;
using namespace stochtex::bench;

constexpr int kRenderSide = 128;
constexpr std::uint32_t kSeed = 7;

void BM_LrpAnalysis(benchmark::State& state) {
  analysis_benchmark(state, "lrp", kGreyExemplar, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_LrpAnalysis)
    ->ArgName("side")
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Times one-thread point samples of a 128x128 grid of the lrp model of the grey 256x256 exemplar
// with `params`; false (and the benchmark skipped) when the analysis fails.
bool time_lrp_render(benchmark::State& state, const ParamValues& params) {
  Model model;
  try {
    model = analyze("lrp", crop_top_left(grey_exemplar(), 256).view(), params, 0);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
  RenderOptions options;
  options.threads = 1;
  options.filter = false;
  const Grid grid{{0.0, 0.0}, 1.0, kRenderSide, kRenderSide};
  ImageF out(kRenderSide, kRenderSide, 1);
  time_samples(state, std::int64_t{kRenderSide} * kRenderSide,
               [&] { render(model, grid, kSeed, out.view(), options); });
  return true;
}

// L = 4 strata, J cosines: a sample costs 9 (J + L) cosines and windows.
void BM_LrpRender(benchmark::State& state) {
  const int cosines = static_cast<int>(state.range(0));
  if (!time_lrp_render(state, {{"cosines", static_cast<double>(cosines)}})) return;
  state.counters["ns_per_call"] = state.counters["ns_per_sample"] / (9.0 * (cosines + 4));
}
BENCHMARK(BM_LrpRender)
    ->ArgName("cosines")
    ->Arg(10)
    ->Arg(50)
    ->Arg(100)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Section 5 at J = 50, one thread, point samples, grey exemplar: `ratio` in percent; `full` = 0
// for fixed phases alone (R with its block subdivision), 1 with turbulence (sigma = 4) and random
// placement.
void BM_LrpStructureRender(benchmark::State& state) {
  const double ratio = static_cast<double>(state.range(0)) / 100.0;
  const bool full = state.range(1) != 0;
  time_lrp_render(state, {{"cosines", 50.0},
                          {"ratio", ratio},
                          {"turbulence", full ? 4.0 : 0.0},
                          {"placement", full ? 1.0 : 0.0}});
}
BENCHMARK(BM_LrpStructureRender)
    ->ArgNames({"ratio_percent", "full"})
    ->Args({0, 0})
    ->Args({10, 0})
    ->Args({30, 0})
    ->Args({10, 1})
    ->Args({30, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Materials (issue 18): the 256² stacked_exemplar of N channels (bench_support.hpp) at J = 50,
// one thread, point samples. N = 4 is a colour + alpha model; 8 and 16 one PCA over all
// channels. The strata cost 9 (J + L) per channel; `ns_per_channel` shows it is linear in N (the
// N x N basis mixing is N multiply-adds per channel).
void BM_LrpMaterialRender(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0));
  Model model;
  try {
    model = analyze("lrp", stacked_exemplar(channels, 256).view(), {{"cosines", 50.0}}, 0);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  RenderOptions options;
  options.threads = 1;
  options.filter = false;
  const Grid grid{{0.0, 0.0}, 1.0, kRenderSide, kRenderSide};
  ImageF out(kRenderSide, kRenderSide, channels);
  time_samples(state, std::int64_t{kRenderSide} * kRenderSide,
               [&] { render(model, grid, kSeed, out.view(), options); });
  state.counters["ns_per_channel"] = state.counters["ns_per_sample"] / channels;
}
BENCHMARK(BM_LrpMaterialRender)
    ->ArgName("channels")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
