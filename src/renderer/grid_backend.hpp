#pragma once
// What evaluates a render's grids: the CPU reference here, the GL backend where the build has it
// (renderer/backends.hpp). A render to a file asks its backend for one grid (the whole image) or
// one after another (the strips of a tiled file, a material's grid with its margin).

#include <cstdint>
#include <functional>
#include <memory>

#include "renderer/plan.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"

namespace stochtex::renderer {

class GridBackend {
 public:
  virtual ~GridBackend() = default;
  // Renders `grid` of the backend's model into `out` (grid.width x grid.height pixels of the
  // model's channels), calling `progress` with the fraction of this grid done (1 at the end).
  virtual void render(const Grid& grid, ImageView<float> out,
                      const std::function<void(double)>& progress) = 0;
};

// The backend of a request for a model, on `threads` CPU threads: what render_to_file asks for
// once the model is made. make_backend (renderer/backends.hpp) gives the request's backend.
using BackendFactory = std::function<std::unique_ptr<GridBackend>(
    const Model& model, const RenderRequest& request, int threads)>;

// The CPU reference (stochtex::render) with the request's seed, tile, supersampling and
// filtering, whatever its backend setting. `model` must outlive it.
std::unique_ptr<GridBackend> make_cpu_backend(const Model& model, const RenderRequest& request,
                                              int threads);

}  // namespace stochtex::renderer
