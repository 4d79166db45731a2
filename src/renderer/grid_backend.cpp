#include "renderer/grid_backend.hpp"

namespace stochtex::renderer {
namespace {

class CpuBackend final : public GridBackend {
 public:
  CpuBackend(const Model& model, const RenderRequest& request, int threads)
      : model_(model), seed_(request.seed) {
    options_.threads = threads;
    options_.tile_size = request.tile;
    options_.supersample = request.supersample;
    options_.filter = request.filter;
    if (request.periodic) options_.period = request_period(request);
  }

  void render(const Grid& grid, ImageView<float> out,
              const std::function<void(double)>& progress) override {
    options_.progress = progress;
    stochtex::render(model_, grid, seed_, out, options_);
  }

 private:
  const Model& model_;
  std::uint32_t seed_;
  RenderOptions options_;
};

}  // namespace

std::unique_ptr<GridBackend> make_cpu_backend(const Model& model, const RenderRequest& request,
                                              int threads) {
  return std::make_unique<CpuBackend>(model, request, threads);
}

}  // namespace stochtex::renderer
