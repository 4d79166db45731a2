#pragma once
// A model's GLSL surface function for one mapping (gl::Twin<M>::surface_shader, twin.hpp), for the
// GL surface evaluator (surface_gl.cpp) and the GL mesh renderer (mesh_gl.cpp).

#include <optional>

#include "gl/twin.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::gl {

// std::nullopt when the model is empty, its method's twin has no surface_shader, or it has no
// GLSL for options.mapping (the library may depend on the other options: texton surface noise's
// constants for its MNI).
std::optional<SurfaceShader> model_surface_shader(const Model& model,
                                                  const SurfaceOptions& options);

}  // namespace stochtex::gl
