// Time to a file (issue 39): what writing a 2048x2048 render costs beside rendering it. The image
// is `stochtex render`'s of the colour exemplar's tiling model: linear light, written as the CLI
// writes it (an sRGB-encoded PNG, linear OpenEXR and PFM).
//
// BM_Render2048: the render alone, 2 threads. BM_EncodeImage/format:F: encode_image of that render
// in memory (0 PNG 8-bit, 1 PNG 16-bit, 2 OpenEXR, 3 PFM), with the encoded bytes as a counter.
// BM_RenderToFile/format:F: the render and the write to a file together, as `stochtex render`
// makes them (renderer::render_to_file on the CPU backend with 2 threads).

#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "model/model_colour.hpp"
#include "renderer/grid_backend.hpp"
#include "renderer/render_file.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;
using namespace stochtex::bench;

constexpr int kSide = 2048;
constexpr int kThreads = 2;

struct Format {
  ImageFormat format;
  int bit_depth;
  const char* extension;
};
constexpr std::array<Format, 4> kFormats = {{{ImageFormat::png, 8, ".png"},
                                             {ImageFormat::png, 16, ".png"},
                                             {ImageFormat::exr, 8, ".exr"},
                                             {ImageFormat::pfm, 8, ".pfm"}}};

// The tiling model of the whole colour exemplar, an sRGB photo as `stochtex analyze` reads it
// (its model renders linear light), analysed once per run.
const Model& tiling_model() {
  static const Model model =
      analyze("tiling", colour_exemplar().view(), {}, 0, kColourExemplar, {}, ColourSpace::srgb);
  return model;
}

const Grid kGrid{{0.0, 0.0}, 1.0, kSide, kSide};

const ImageF& rendered() {
  static const ImageF image = [] {
    ImageF out(kSide, kSide, tiling_model().channels());
    RenderOptions options;
    options.threads = kThreads;
    render(tiling_model(), kGrid, 0, out.view(), options);
    return out;
  }();
  return image;
}

void BM_Render2048(benchmark::State& state) {
  try {
    tiling_model();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  ImageF out(kSide, kSide, tiling_model().channels());
  RenderOptions options;
  options.threads = kThreads;
  for (auto _ : state) {
    render(tiling_model(), kGrid, 0, out.view(), options);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_Render2048)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_EncodeImage(benchmark::State& state) {
  const Format& format = kFormats[static_cast<std::size_t>(state.range(0))];
  try {
    rendered();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const ColourSpace space = rendered_space(tiling_model().colour_space());
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<std::uint8_t> encoded =
        encode_image(rendered().view(), format.format, format.bit_depth, space);
    bytes = encoded.size();
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_EncodeImage)
    ->ArgName("format")
    ->DenseRange(0, 3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_RenderToFile(benchmark::State& state) {
  const Format& format = kFormats[static_cast<std::size_t>(state.range(0))];
  try {
    tiling_model();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const std::filesystem::path output =
      std::filesystem::temp_directory_path() / (std::string("stochtex_bench") + format.extension);
  renderer::RenderRequest request;
  request.width = kSide;
  request.height = kSide;
  request.threads = kThreads;
  request.bit_depth = format.bit_depth;
  for (auto _ : state)
    renderer::render_to_file([] { return tiling_model(); }, request, output.string(), "",
                             renderer::make_cpu_backend);
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(output));
  std::filesystem::remove(output);
}
BENCHMARK(BM_RenderToFile)
    ->ArgName("format")
    ->DenseRange(0, 3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
