#include "renderer/backends.hpp"

#include "renderer/backends/gl_backend.hpp"

namespace stochtex::renderer {

std::unique_ptr<GridBackend> make_backend(const Model& model, const RenderRequest& request,
                                          int threads) {
  if (request.backend == Backend::gl) return make_gl_backend(model, request);
  return make_cpu_backend(model, request, threads);
}

void check_backend_built(Backend backend) {
  if (backend == Backend::gl) check_gl_built();
}

bool backend_supports_mapping(Backend backend, const Model& model, SurfaceMapping mapping) {
  if (backend == Backend::gl) return gl_backend_supports_mapping(model, mapping);
  return supports_mapping(model, mapping);
}

void render_mesh_on(Backend backend, const Model& model, const Mesh& mesh, const Camera& camera,
                    const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out) {
  if (backend == Backend::gl) {
    render_mesh_on_gl(model, mesh, camera, options, seed, out);
    return;
  }
  render_mesh(model, mesh, camera, options, seed, out);
}

}  // namespace stochtex::renderer
