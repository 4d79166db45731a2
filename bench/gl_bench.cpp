// GPU frame times of the GLSL evaluators (stochtex::gl), to compare with the papers' shader
// timings: texton noise 1024^2 in 4.9 ms (64^2 texton) on a Quadro K5000 (paper Table 1).
// gpu_ms is the GPU time of the compute dispatch (GL timer query), without the read-back.
// On a machine without a GPU this measures Mesa llvmpipe (the CPU), which says nothing about GPUs.

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "bench_support.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;

void BM_GlTextonFrame(benchmark::State& state) {
  const int support = static_cast<int>(state.range(0));
  const int width = static_cast<int>(state.range(1));
  const int height = static_cast<int>(state.range(2));
  std::unique_ptr<GlRenderer> renderer;
  Model model;
  try {
    model = analyze("texton", bench::colour_exemplar().view(), {{"support", support}}, 0);
    renderer = std::make_unique<GlRenderer>(model);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.SetLabel(renderer->device());
  // llvmpipe runs the shader on the CPU at about 20 us per sample: only the small frame is run.
  if (renderer->device().find("llvmpipe") != std::string::npos && width * height > 256 * 256) {
    state.SkipWithError("no GPU: llvmpipe (software) runs the 256x256 frame only");
    return;
  }
  ImageF out(width, height, model.channels());
  const Grid grid{{0.0, 0.0}, 1.0, width, height};
  std::uint32_t seed = 0;
  double gpu_milliseconds = 0.0;
  for (auto _ : state) {
    renderer->render(grid, seed++, out.view());
    gpu_milliseconds += renderer->last_gpu_milliseconds();
  }
  // Real time per iteration includes the read-back of the image to the CPU; gpu_ms is the
  // dispatch alone, the number to compare with the papers' frame times.
  const double iterations = static_cast<double>(state.iterations());
  state.counters["gpu_ms"] = gpu_milliseconds / iterations;
  state.counters["gpu_ns_per_sample"] =
      gpu_milliseconds * 1e6 / iterations / (static_cast<double>(width) * height);
}
BENCHMARK(BM_GlTextonFrame)
    ->ArgNames({"support", "width", "height"})
    ->Args({64, 256, 256})
    ->Args({64, 1024, 1024})
    ->Args({256, 1024, 1024})
    ->Args({64, 1920, 1080})
    ->Args({256, 1920, 1080})
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
