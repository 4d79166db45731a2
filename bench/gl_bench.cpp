// GPU frame times of the GLSL evaluators (stochtex::gl), to compare with the papers' shader
// timings: texton noise 1024^2 in 4.9 ms (64^2 texton) on a Quadro K5000 (texton paper, Table 1);
// tiling and blending 1080p in 0.29 ms (0.11 ms on the Gaussian fast path) on a GTX 980; LRP noise
// 128^2 in about 0.5 ms on a GTX 780; Gabor noise by example 128^2 grey at about 30 fps (33 ms),
// default parameters, CUDA on a Quadro 5000 (Gabor paper, section 9.1).
// gpu_ms is the GPU time of the compute dispatch (GL timer query), without the read-back.
// On a machine without a GPU this measures Mesa llvmpipe (the CPU), which says nothing about GPUs.

#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <string>

#include "bench_support.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;

// Renders width x height frames of `method` analysed on `exemplar`, point samples by default,
// or zoomed out by `scale` and filtered by `texture_filter`; on llvmpipe only frames of at most
// `software_pixels` pixels.
void frame_benchmark(benchmark::State& state, const char* method, const ParamValues& params,
                     int width, int height, const ImageF& exemplar = bench::colour_exemplar(),
                     double scale = 1.0, GlFilter texture_filter = GlFilter::exact,
                     int software_pixels = 256 * 256) {
  std::unique_ptr<GlRenderer> renderer;
  Model model;
  try {
    model = analyze(method, exemplar.view(), params, 0);
    renderer = std::make_unique<GlRenderer>(model);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.SetLabel(renderer->device());
  // llvmpipe runs the shaders on the CPU (texton: about 20 us per sample): small frames only.
  if (renderer->device().find("llvmpipe") != std::string::npos &&
      width * height > software_pixels) {
    state.SkipWithError("no GPU: llvmpipe (software) runs the small frames only");
    return;
  }
  ImageF out(width, height, model.channels());
  const Grid grid{{0.0, 0.0}, scale, width, height};
  GpuRenderOptions options;
  options.texture_filter = texture_filter;
  // One frame outside the timing: the program of a filter is compiled and its data uploaded on
  // first use.
  renderer->render(grid, 0, out.view(), options);
  std::uint32_t seed = 0;
  double gpu_milliseconds = 0.0;
  for (auto _ : state) {
    renderer->render(grid, seed++, out.view(), options);
    gpu_milliseconds += renderer->last_gpu_milliseconds();
  }
  // Real time per iteration includes the read-back of the image to the CPU; gpu_ms is the
  // dispatch alone, the number to compare with the papers' frame times.
  const double iterations = static_cast<double>(state.iterations());
  state.counters["gpu_ms"] = gpu_milliseconds / iterations;
  state.counters["gpu_ns_per_sample"] =
      gpu_milliseconds * 1e6 / iterations / (static_cast<double>(width) * height);
}

void BM_GlTextonFrame(benchmark::State& state) {
  frame_benchmark(state, "texton", {{"support", static_cast<double>(state.range(0))}},
                  static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
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

// Materials (issue 18): N channels render in chunks of 4 (texton gl_pass.cpp), each chunk drawing
// the same impulses: 256x256 frames of a support-64 texton of a 256x256 stacked_exemplar.
void BM_GlTextonChannels(benchmark::State& state) {
  frame_benchmark(state, "texton", {{"support", 64}}, 256, 256,
                  bench::stacked_exemplar(static_cast<int>(state.range(0)), 256));
}
BENCHMARK(BM_GlTextonChannels)
    ->ArgName("channels")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Iterations(4)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// blend 0: histogram-preserving (3 fetches + T^-1); 1: the Gaussian fast path (3 fetches).
void BM_GlTilingFrame(benchmark::State& state) {
  frame_benchmark(state, "tiling", {{"blend", static_cast<double>(state.range(0))}},
                  static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
}
BENCHMARK(BM_GlTilingFrame)
    ->ArgNames({"blend", "width", "height"})
    ->Args({0, 256, 256})
    ->Args({0, 1920, 1080})
    ->Args({1, 1920, 1080})
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Materials (issue 18) on tiling, 256x256 frames zoomed out by 4, --gl-filter exact (0) and
// hardware (1), on a 256x256 stacked_exemplar of 4, 8 and 16 channels: 4 renders as an image
// (one program, the colour's 3-D table and alpha); beyond, the Gaussian in chunks of 4 channels
// (the same patches), then the groups' T^-1 (src/methods/tiling/gl_pass.cpp, groups.glsl). An
// image of N channels is one group of N on its principal axes: N^2 products per pixel and level,
// the costliest grouping (a material's maps are groups of at most 3).
void BM_GlTilingChannels(benchmark::State& state) {
  frame_benchmark(state, "tiling", {}, 256, 256,
                  bench::stacked_exemplar(static_cast<int>(state.range(0)), 256), 4.0,
                  state.range(1) == 1 ? GlFilter::hardware : GlFilter::exact);
}
BENCHMARK(BM_GlTilingChannels)
    ->ArgNames({"channels", "hardware"})
    ->ArgsProduct({{4, 8, 16}, {0, 1}})
    ->Iterations(4)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// LRP noise, J = 50 cosines, L = 4 (paper: about 0.5 ms for 128^2 on a GTX 780).
void BM_GlLrpFrame(benchmark::State& state) {
  frame_benchmark(state, "lrp", {}, static_cast<int>(state.range(0)),
                  static_cast<int>(state.range(1)));
}
BENCHMARK(BM_GlLrpFrame)
    ->ArgNames({"width", "height"})
    ->Args({128, 128})
    ->Args({1920, 1080})
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// LRP noise on a material of N = 4, 8, 16 channels (the stacked_exemplar of bench_support.hpp,
// J = 50): N > 4 runs one program per chunk of 4 channels (src/methods/lrp/gl_pass.cpp).
void BM_GlLrpMaterialFrame(benchmark::State& state) {
  frame_benchmark(state, "lrp", {}, 128, 128,
                  bench::stacked_exemplar(static_cast<int>(state.range(0)), 256));
}
BENCHMARK(BM_GlLrpMaterialFrame)
    ->ArgName("channels")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Zoomed out by 4 (footprint filtering), --gl-filter exact (0) against hardware (1): texton
// (support 64) and tiling, the colour exemplar, 256x256 and 1080p frames.
void BM_GlFilteredFrame(benchmark::State& state) {
  const bool texton = state.range(0) == 1;
  frame_benchmark(
      state, texton ? "texton" : "tiling", texton ? ParamValues{{"support", 64}} : ParamValues{},
      static_cast<int>(state.range(2)), static_cast<int>(state.range(3)), bench::colour_exemplar(),
      4.0, state.range(1) == 1 ? GlFilter::hardware : GlFilter::exact);
}
BENCHMARK(BM_GlFilteredFrame)
    ->ArgNames({"texton", "hardware", "width", "height"})
    ->ArgsProduct({{0, 1}, {0, 1}, {256}, {256}})
    ->ArgsProduct({{0, 1}, {0, 1}, {1920}, {1080}})
    ->Iterations(10)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The fast path (`--gl-filter hardware` = `export-shader --variant fast`) of every method at
// 1920x1080, at scale 1 and zoomed out by 4: tiling (3 + 1 filtered fetches: the 16-bit exemplar,
// the 3-D table of T^-1), texton noise (support 64, the mip-mapped texton), lrp (its exact path)
// and gabor (the float-only GLSL; 128² colour crop, N = 1024, as BM_GlGaborFrame). On llvmpipe
// the 1080p frames of tiling and texton run (one frame each: wall times of the software
// rasteriser, not GPU times); the others are for a GPU.
void BM_GlFastFrame(benchmark::State& state) {
  static const ImageF gabor_exemplar = bench::crop_top_left(bench::colour_exemplar(), 128);
  constexpr std::array<const char*, 4> kMethods = {"tiling", "texton", "lrp", "gabor"};
  const std::string method = kMethods[static_cast<std::size_t>(state.range(0))];
  const ParamValues params = method == "texton" ? ParamValues{{"support", 64}} : ParamValues{};
  const bool software_frame = method == "tiling" || method == "texton";
  frame_benchmark(state, method.c_str(), params, 1920, 1080,
                  method == "gabor" ? gabor_exemplar : bench::colour_exemplar(),
                  static_cast<double>(state.range(1)), GlFilter::hardware,
                  software_frame ? 1920 * 1080 : 256 * 256);
}
BENCHMARK(BM_GlFastFrame)
    ->ArgNames({"method", "scale"})
    ->ArgsProduct({{0, 1, 2, 3}, {1, 4}})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Gabor noise, impulse budget N (default 1024), on the 128² top-left crops of the grey and colour
// exemplars (the paper's timing is 128² grey at the default parameters).
void BM_GlGaborFrame(benchmark::State& state) {
  static const ImageF grey = bench::crop_top_left(bench::grey_exemplar(), 128);
  static const ImageF colour = bench::crop_top_left(bench::colour_exemplar(), 128);
  frame_benchmark(state, "gabor", {{"impulses", static_cast<double>(state.range(1))}},
                  static_cast<int>(state.range(2)), static_cast<int>(state.range(3)),
                  state.range(0) == 1 ? grey : colour);
}
BENCHMARK(BM_GlGaborFrame)
    ->ArgNames({"grey", "impulses", "width", "height"})
    ->Args({1, 1024, 128, 128})
    ->Args({0, 1024, 128, 128})
    ->Args({1, 256, 128, 128})
    ->Args({1, 1024, 1920, 1080})
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Gabor noise, --gl-filter exact (float 0: the double-precision twin) against hardware (float 1:
// the float-only GLSL), 128² grey crop, default parameters (N = 1024), scale 1 and zoomed out 4x.
void BM_GlGaborPrecision(benchmark::State& state) {
  static const ImageF grey = bench::crop_top_left(bench::grey_exemplar(), 128);
  frame_benchmark(state, "gabor", {}, 128, 128, grey, static_cast<double>(state.range(1)),
                  state.range(0) == 1 ? GlFilter::hardware : GlFilter::exact);
}
BENCHMARK(BM_GlGaborPrecision)
    ->ArgNames({"float", "scale"})
    ->ArgsProduct({{0, 1}, {1, 4}})
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Gabor noise of 4, 8 and 16 channels (a material's maps, bench::stacked_exemplar), 128² frames,
// default parameters: beyond 4 channels the colour is an array of floats (noise_channels.glsl).
void BM_GlGaborChannels(benchmark::State& state) {
  const ImageF exemplar = bench::stacked_exemplar(static_cast<int>(state.range(0)), 128);
  frame_benchmark(state, "gabor", {}, 128, 128, exemplar);
}
BENCHMARK(BM_GlGaborChannels)
    ->ArgName("channels")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
