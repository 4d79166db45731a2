#pragma once
// Pictures of a textured mesh (docs/meshes.md): a pinhole camera, a z-buffer rasteriser on the
// CPU (the reference), the texture from evaluate_surface() (surface.hpp) or from evaluate() at the
// mesh's texture coordinates, with footprints from ray differentials, and Lambert + ambient
// shading; a material's colour map bumped by its normal map. Like render(): a pure function of its
// arguments, bit-identical whatever the thread count. In stochtex::runtime.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "stochtex/image.hpp"
#include "stochtex/mesh.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// A pinhole camera looking from `eye` at `target`, `up` giving the picture's vertical; square
// pixels, the vertical field of view fixed.
struct Camera {
  Vec3d eye;
  Vec3d target;
  Vec3d up{0.0, 1.0, 0.0};
  double vertical_fov_degrees = 40.0;
};

// A camera on a sphere around the mesh's bounding box centre, looking at it, with +y up:
// azimuth (degrees, about +y, 0 = looking along -z from +z), elevation (degrees, within (-90,
// 90)), distance in multiples of the distance at which the mesh's bounding sphere (about the box's
// centre) just fits the picture of `width` x `height` pixels (1: touching its shorter side). Throws
// std::invalid_argument when an angle or the distance is out of range.
Camera orbit_camera(const Mesh& mesh, double azimuth_degrees, double elevation_degrees,
                    double distance, int width, int height);

// The exemplar pixels per mesh unit that make the bounding box's largest side 1024 exemplar
// pixels: a few exemplars across the mesh.
double default_texture_scale(const Mesh& mesh);

struct MeshRenderOptions {
  // A mapping of evaluate_surface(), or nothing: the mesh's texture coordinates through
  // evaluate(), every method (the mesh must have uvs).
  std::optional<SurfaceMapping> mapping = SurfaceMapping::triplanar_linear;
  SurfaceOptions surface;  // its `mapping` is replaced by the one above
  // Exemplar pixels per mesh unit (per uv unit with the uv mapping).
  double texture_scale = 1.0;
  // The uv mapping only: the texture repeats every uv unit in u and v, as an engine's repeat wrap
  // (evaluate_periodic, period (texture_scale, texture_scale) exemplar pixels), so that a seam
  // where u or v jumps by a whole number (Mesh::uv_wrap_seam) does not show. mesh_periodic_refusal
  // says when it cannot be.
  bool periodic = false;
  // Every colour channel of the pixels no triangle covers, as an output file shows it (sRGB-encoded
  // where mesh_output_space is linear light: mesh_background); alpha 0.
  float background = 0.2f;
  int threads = 0;                       // 0 = all hardware threads
  std::function<void(double)> progress;  // called with the fraction done, from one thread
};

// The channels of render_mesh's picture: a model of one image's own; a material's colour map's
// (the map named albedo, else the first colour map: 1 or 3), lit with its normal map bumping the
// normal and its ambient occlusion map (ao, occlusion or ambient_occlusion) darkening the ambient
// light, its other maps unused (docs/materials.md, "On a mesh"). Throws Error(invalid_input), one
// sentence, for a material without a colour map.
int mesh_output_channels(const Model& model);

// What render_mesh's pixels are (stochtex/colour.hpp): linear light when that colour is srgb or
// linear (each pixel the mean of the decoded colour over its footprint, lit), else data.
ColourSpace mesh_output_space(const Model& model);

// The value render_mesh writes for options.background: decoded from sRGB when the pixels are linear
// light (mesh_output_space), so that every model shows the same background.
float mesh_background(const Model& model, const MeshRenderOptions& options);

// Why render_mesh refuses options.periodic (one sentence), or empty when it does not: another
// mapping than uv (a mapping of positions has no uv unit to repeat), or a model evaluate_periodic
// refuses (periodic_refusal, stochtex/render.hpp: a texton mix, an lrp structure component).
std::string mesh_periodic_refusal(const Model& model, const MeshRenderOptions& options);

// Renders the mesh (prepared by prepare_mesh) seen by the camera into `out`, which has
// mesh_output_channels(model) channels. Throws std::invalid_argument, before any work, when the
// model is empty or does not support the mapping, the uv mapping meets a mesh without uvs, the
// camera is degenerate (eye at target, up along the view), the texture scale puts the mesh
// beyond kPositionLimit or options.periodic is refused (mesh_periodic_refusal);
// Error(invalid_input) for a material without a colour map.
void render_mesh(const Model& model, const Mesh& mesh, const Camera& camera,
                 const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out);

}  // namespace stochtex
