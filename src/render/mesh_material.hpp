#pragma once
// A material model on a mesh (docs/materials.md, "On a mesh"): the maps render_mesh shades with,
// and the bump of the normal map at each fragment as a surface gradient (mesh_shading.hpp).

#include <cstdint>
#include <span>

#include "render/mesh_shading.hpp"

namespace stochtex {

// The model channels render_mesh reads from a material; -1 for a map the material lacks.
struct MeshMaterial {
  int colour = 0;   // the colour map's first channel: the map named albedo, else the first one
  int colours = 0;  // its channels, 1 or 3 (0 for a model of one image)
  int slopes = -1;  // the normal map's two stored slopes
  int height = -1;  // the height a derived normal map follows, with its slope_scale
  double slope_scale = 0.0;
  int occlusion = -1;  // ambient occlusion (ao, occlusion, ambient_occlusion): darkens the ambient
};

// Throws Error(invalid_input), one sentence, when a material has no colour map. A model of one
// image gives colours = 0 (render_mesh shades its channels as they are).
MeshMaterial mesh_material(const Model& model);

// Whether the material bumps the shading normal.
inline bool has_bump(const MeshMaterial& material) {
  return material.slopes >= 0 || material.height >= 0;
}

// The surface gradient of the material's normal map at each fragment, in units of the mesh's
// positions (render_mesh bumps the normal with it), with `values` the model evaluated at the
// fragments through `surface` (options' mapping; uv, no mapping: through evaluate_uv() at the
// fragments' uvs, periodic with options.periodic):
//  - stored slopes, uv: the slopes as the height's gradient over the texture coordinates through
//    the triangle's texture gradients (texture_surface_gradient);
//  - stored slopes, triplanar mappings: each plane's slopes (the mapping evaluated at a normal
//    along the plane's axis: that plane alone) lifted into space, their surface gradients blended
//    with the mapping's weights (Mikkelsen's triplanar bump mapping);
//  - stored slopes, surface noise: along the frame (tangent, normal x tangent) the noise lays the
//    exemplar's x and y on;
//  - derived: the height evaluated one footprint step on either side of the fragment along dpdx
//    and dpdy, with the fragment's footprint (as render_maps takes a grid's central differences
//    one pixel apart, the pixels filtered by the grid's footprint), slope_scale times the
//    differences, through texture_gradient_from_steps (uv) or surface_gradient_from_steps.
// Heights are in units of one exemplar pixel's size on the surface (docs/materials.md).
void bump_gradients(const Model& model, const MeshMaterial& material, const Mesh& mesh,
                    std::span<const MeshFragment> fragments, const MeshRenderOptions& options,
                    const SurfaceOptions& surface, std::uint32_t seed,
                    ImageView<const float> values, std::span<Vec3d> gradients);

}  // namespace stochtex
