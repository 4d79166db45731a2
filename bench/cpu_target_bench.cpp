// The CPU evaluators side by side (docs/performance.md, "SIMD"): every registered method, its
// default parameters on a 256² crop of the colour and the grey exemplar, rendered at
//   simd     0 = the scalar reference, 1 = the best CPU target of the machine (render.hpp),
//   threads  1 or 2,
//   zoom     1 = point samples at scale 1, 8 = filtered at scale 8 (zoomed out),
//   colour   0 = grey, 1 = colour,
// one row per combination in one run, so the ratios compare like with like. ns_per_sample is
// wall-clock time per output pixel of a 128² render. BM_CpuThreads: 1 and 2 threads on 512².

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <utility>

#include "bench_support.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;
using namespace stochtex::bench;

constexpr int kSide = 128;
constexpr int kExemplarSide = 256;

// The default model of `method` for the colour or grey exemplar, analysed once per run.
const Model& default_model(const std::string& method, bool colour) {
  static std::map<std::pair<std::string, bool>, Model> models;
  const auto key = std::make_pair(method, colour);
  auto found = models.find(key);
  if (found == models.end()) {
    const ImageF exemplar =
        crop_top_left(colour ? colour_exemplar() : grey_exemplar(), kExemplarSide);
    found = models.emplace(key, analyze(method, exemplar.view(), {}, 0)).first;
  }
  return found->second;
}

void evaluate_benchmark(benchmark::State& state, const std::string& method) {
  const bool simd = state.range(0) != 0;
  const auto threads = static_cast<int>(state.range(1));
  const auto zoom = static_cast<double>(state.range(2));
  const bool colour = state.range(3) != 0;
  const Model* model = nullptr;
  try {
    model = &default_model(method, colour);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const CpuTarget target = simd ? available_cpu_targets().back() : CpuTarget::reference;
  set_cpu_target(target);
  state.SetLabel(std::string(cpu_target_name(target)));
  RenderOptions options;
  options.threads = threads;
  options.filter = zoom > 1.0;
  const Grid grid{{0.0, 0.0}, zoom, kSide, kSide};
  ImageF out(kSide, kSide, model->channels());
  time_samples(state, std::int64_t{kSide} * kSide,
               [&] { render(*model, grid, 7, out.view(), options); });
  set_cpu_target(available_cpu_targets().back());
}

// Two threads against one on a larger render (512², colour, the best target): a 128² render is
// 4 tiles of 64², and starting the second thread weighs on its fraction of a millisecond.
void threads_benchmark(benchmark::State& state, const std::string& method) {
  const auto threads = static_cast<int>(state.range(0));
  const auto zoom = static_cast<double>(state.range(1));
  const Model* model = nullptr;
  try {
    model = &default_model(method, true);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.SetLabel(std::string(cpu_target_name(cpu_target())));
  RenderOptions options;
  options.threads = threads;
  options.filter = zoom > 1.0;
  constexpr int kLargeSide = 512;
  const Grid grid{{0.0, 0.0}, zoom, kLargeSide, kLargeSide};
  ImageF out(kLargeSide, kLargeSide, model->channels());
  time_samples(state, std::int64_t{kLargeSide} * kLargeSide,
               [&] { render(*model, grid, 7, out.view(), options); });
}

// One family per registered method: BM_CpuEvaluate/<method>/simd:S/threads:T/zoom:Z/colour:C and
// BM_CpuThreads/<method>/threads:T/zoom:Z.
[[maybe_unused]] const bool registered = [] {
  for (const MethodInfo& method : methods()) {
    const std::string name(method.name);
    benchmark::RegisterBenchmark(
        ("BM_CpuEvaluate/" + name).c_str(),
        [name](benchmark::State& state) { evaluate_benchmark(state, name); })
        ->ArgNames({"simd", "threads", "zoom", "colour"})
        ->ArgsProduct({{0, 1}, {1, 2}, {1, 8}, {0, 1}})
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
        ("BM_CpuThreads/" + name).c_str(),
        [name](benchmark::State& state) { threads_benchmark(state, name); })
        ->ArgNames({"threads", "zoom"})
        ->ArgsProduct({{1, 2}, {1, 8}})
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
