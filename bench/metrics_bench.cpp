// The quality measures of `stochtex compare` (docs/design.md §8) on a render the size the
// statistical tier and the report measure: the sliced Wasserstein distance of a 1024² colour render
// to its 256² exemplar, whose cost is sorting each direction's projections.

#include "bench_support.hpp"
#include "metrics/metrics.hpp"

namespace stochtex::bench {
namespace {

void BM_SlicedWasserstein(benchmark::State& state) {
  const ImageF exemplar = crop_top_left(colour_exemplar(), 256);
  const Model model = analyze("tiling", exemplar.view(), {}, 0);
  const int side = static_cast<int>(state.range(0));
  ImageF image(side, side, model.channels());
  render(model, Grid{{0.0, 0.0}, 1.0, side, side}, 1, image.view());
  for (auto _ : state) benchmark::DoNotOptimize(sliced_wasserstein(image.view(), exemplar.view()));
  state.SetItemsProcessed(state.iterations() * std::int64_t{side} * side);
}
BENCHMARK(BM_SlicedWasserstein)->ArgNames({"side"})->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stochtex::bench
