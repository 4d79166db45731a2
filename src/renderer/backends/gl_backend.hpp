#pragma once
// The GL backend's side of renderer/backends.hpp, for backends.cpp: with_gl.cpp in a build with
// STOCHTEX_BUILD_GL (the GL renderers of stochtex/gpu.hpp), without_gl.cpp otherwise, whose
// functions refuse with Error(io) saying that the build lacks the backend.

#include <cstdint>
#include <memory>

#include "renderer/grid_backend.hpp"
#include "renderer/plan.hpp"
#include "stochtex/image.hpp"
#include "stochtex/mesh.hpp"
#include "stochtex/mesh_render.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::renderer {

void check_gl_built();
std::unique_ptr<GridBackend> make_gl_backend(const Model& model, const RenderRequest& request);
bool gl_backend_supports_mapping(const Model& model, SurfaceMapping mapping);
void render_mesh_on_gl(const Model& model, const Mesh& mesh, const Camera& camera,
                       const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out);

}  // namespace stochtex::renderer
