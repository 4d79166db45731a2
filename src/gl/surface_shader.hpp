#pragma once
// A model's GLSL surface function for one mapping (gl::Twin<M>::surface_shader, twin.hpp), for the
// GL surface evaluator (surface_gl.cpp) and the GL mesh renderer (mesh_gl.cpp).

#include <optional>

#include "gl/twin.hpp"
#include "stochtex/model.hpp"

namespace stochtex::gl {

// std::nullopt when the model is empty, its method's twin has no surface_shader, or it has no
// GLSL for `mapping`.
std::optional<SurfaceShader> model_surface_shader(const Model& model, SurfaceMapping mapping);

}  // namespace stochtex::gl
