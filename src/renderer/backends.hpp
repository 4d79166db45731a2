#pragma once
// The backends of this build (docs/design.md §3): the CPU reference always, the OpenGL one when it
// is built with STOCHTEX_BUILD_GL. The choice between them is made here, for grids and for meshes,
// so that no front end asks how stochtex was built: in a build without the GL backend its
// functions refuse a GL request with Error(io), one sentence saying so (backends/without_gl.cpp).

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

// The request's backend for `model` (a BackendFactory): make_cpu_backend's, or the GL renderer
// of the model (stochtex/gpu.hpp: a context, the compiled evaluator and the model's data), which
// refuses supersampling, a CPU reference, and throws Error when no OpenGL 4.5 context can be
// made. `model` must outlive it.
std::unique_ptr<GridBackend> make_backend(const Model& model, const RenderRequest& request,
                                          int threads);

// Refuses, before any work, a backend this build lacks.
void check_backend_built(Backend backend);

// Whether `backend` maps the model onto a surface with `mapping`: every mapping the model has
// (supports_mapping) on the CPU, those gl_supports_mapping names on the GL backend.
bool backend_supports_mapping(Backend backend, const Model& model, SurfaceMapping mapping);

// render_mesh() on `backend`: the CPU's, or render_mesh_gl() (which uses neither the options'
// threads nor their progress).
void render_mesh_on(Backend backend, const Model& model, const Mesh& mesh, const Camera& camera,
                    const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out);

}  // namespace stochtex::renderer
