#pragma once
// The argument checks of evaluate_surface() (stochtex/surface.hpp), shared with its GL twin
// evaluate_surface_gl() (src/gl/surface_gl.cpp) so both refuse the same input with the same words.

#include <span>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// Throws std::invalid_argument as evaluate_surface() documents: the model does not support the
// mapping on the CPU, an option is out of range, the output view is too small or has the wrong
// channel count, or a point is not finite, beyond kPositionLimit, or its frame is not orthonormal.
void check_surface_arguments(const Model& model, std::span<const SurfacePoint> points,
                             const SurfaceOptions& options, ImageView<float> out);

}  // namespace stochtex
