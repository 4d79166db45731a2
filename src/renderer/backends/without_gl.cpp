// The GL backend's stand-in in a build without it (STOCHTEX_BUILD_GL=OFF): every request for it
// is refused with the same sentence.

#include "renderer/backends/gl_backend.hpp"
#include "stochtex/error.hpp"

namespace stochtex::renderer {
namespace {

[[noreturn]] void refuse() {
  throw Error(ErrorCode::io,
              "this stochtex was built without the OpenGL backend (STOCHTEX_BUILD_GL=OFF); use "
              "--backend cpu");
}

}  // namespace

void check_gl_built() {
  refuse();
}

std::unique_ptr<GridBackend> make_gl_backend(const Model&, const RenderRequest&) {
  refuse();
}

bool gl_backend_supports_mapping(const Model&, SurfaceMapping) {
  refuse();
}

void render_mesh_on_gl(const Model&, const Mesh&, const Camera&, const MeshRenderOptions&,
                       std::uint32_t, ImageView<float>) {
  refuse();
}

}  // namespace stochtex::renderer
