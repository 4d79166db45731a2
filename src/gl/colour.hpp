#pragma once
// The GLSL twin of decode_expectation (model/model_colour.hpp, gl/colour.glsl): what an export of
// a model whose channels are decoded after evaluation adds to its method's GLSL, so that its
// entry point returns linear light as the CPU render does.

#include <span>

#include "gl/twin.hpp"
#include "model/model_colour.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::gl {

// The README's note on the colour of the result (encoded values or linear light; a material's,
// per map). For a model of `channels` (1 to 4) channels whose `colour` decodes some after
// evaluation (ModelColour::expects_any), also renames `parts`' entry point stochtex_<method> to
// stochtex_<method>_encoded and adds a stochtex_<method> of the same signature returning its
// value as linear light (stochtex_linear_light, colour.glsl), with the tables it reads as two more
// textures (`decoded`, `removed`). For a material (`maps`) of that kind, the library gets
// stochtex_material_linear_light (colour_material.glsl) and `parts.decoded_channels` the channels
// its material function decodes (export_material.cpp).
void add_colour(ExportParts& parts, const ModelColour& colour, int channels,
                std::span<const MapInfo> maps);

// For the surface function `shader` (`mapping`) of a model of `channels` (1 to 4) channels whose
// `colour` decodes some after evaluation: its values as linear light, as evaluate_surface's
// (decode_surface; each plane's before the blend for linear triplanar mapping), reading the
// tables as two more textures. Other models' shaders are left as they are.
void add_colour(SurfaceShader& shader, const ModelColour& colour, int channels,
                SurfaceMapping mapping);

}  // namespace stochtex::gl
