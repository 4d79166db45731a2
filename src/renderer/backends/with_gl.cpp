// The GL backend of a build with STOCHTEX_BUILD_GL: the renderers of stochtex::gl.

#include <stdexcept>

#include "renderer/backends/gl_backend.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex::renderer {
namespace {

class GlBackend final : public GridBackend {
 public:
  GlBackend(const Model& model, const RenderRequest& request) : seed_(request.seed) {
    options_.filter = request.filter;
    options_.texture_filter = request.gl_filter;
    if (request.supersample != 1)
      throw std::invalid_argument("--supersample is a CPU reference: use it with --backend cpu");
    renderer_ = std::make_unique<GlRenderer>(model);
  }

  // The GL renderer reports no progress of its own: the grid is done when it returns.
  void render(const Grid& grid, ImageView<float> out,
              const std::function<void(double)>& progress) override {
    renderer_->render(grid, seed_, out, options_);
    progress(1.0);
  }

 private:
  std::uint32_t seed_;
  GpuRenderOptions options_;
  std::unique_ptr<GlRenderer> renderer_;
};

}  // namespace

void check_gl_built() {}

std::unique_ptr<GridBackend> make_gl_backend(const Model& model, const RenderRequest& request) {
  return std::make_unique<GlBackend>(model, request);
}

bool gl_backend_supports_mapping(const Model& model, SurfaceMapping mapping) {
  return gl_supports_mapping(model, mapping);
}

void render_mesh_on_gl(const Model& model, const Mesh& mesh, const Camera& camera,
                       const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out) {
  render_mesh_gl(model, mesh, camera, options, seed, out);
}

}  // namespace stochtex::renderer
