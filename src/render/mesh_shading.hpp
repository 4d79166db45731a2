#pragma once
// What a rasteriser of meshes needs besides visibility (docs/meshes.md): the camera's rays, the
// tangent frame field, the footprints from ray differentials and the shading. The CPU rasteriser
// (mesh_render.cpp) uses them; a GL rasteriser passes the same rays and light as uniforms.

#include "render/mesh_geometry.hpp"
#include "stochtex/mesh_render.hpp"

namespace stochtex {

// The ray through pixel (x, y) (its centre at x + 1/2, y + 1/2) leaves `eye` along
//   forward + (x + 1/2 - width/2) step_x + (y + 1/2 - height/2) step_y,
// with `forward` the unit view direction and |step_x| = |step_y| = 2 tan(fov/2) / height: one
// pixel at unit distance along `forward`. Throws std::invalid_argument when the eye is at the
// target, the up vector is along the view, or a value is not finite.
struct PixelRays {
  Vec3d eye;
  Vec3d forward;
  Vec3d step_x;  // right
  Vec3d step_y;  // down
  int width = 0;
  int height = 0;

  Vec3d direction(int x, int y) const {
    return forward + step_x * (x + 0.5 - 0.5 * width) + step_y * (y + 0.5 - 0.5 * height);
  }
};
PixelRays pixel_rays(const Camera& camera, int width, int height);

// The tangent of the frame at a point of unit normal n: the "east" direction of a y-up globe,
// normalise(Y x n); where n is within 1e-6 of +-Y (the poles of that field, where every
// continuous tangent field on a closed surface of genus 0 must have a singularity), the
// projection of X on the tangent plane instead.
Vec3d surface_tangent(const Vec3d& normal);

// A point where a pixel's ray of direction `d` meets the plane through `p` of normal `n`, and
// the derivatives of that point along the picture's x and y (Igehy's ray differentials, exact
// for a plane): dp/dx = t (step_x - (n.step_x / n.d) d), with t the ray parameter.
struct PlaneHit {
  Vec3d dpdx;
  Vec3d dpdy;
};
PlaneHit plane_differentials(const PixelRays& rays, const Vec3d& d, double t, const Vec3d& n);

// The gradients of the barycentrics u and v of the triangle p0 + u e1 + v e2 within its plane:
// u = (q . (e2 x N)) / |N|^2 and v = (q . (N x e1)) / |N|^2 for q = p - p0 and N = e1 x e2, so
// du/dx = du . dp/dx. A texture coordinate's derivatives follow through the corners' values.
struct BarycentricGradients {
  Vec3d du;
  Vec3d dv;
};
BarycentricGradients barycentric_gradients(const Vec3d& e1, const Vec3d& e2);

// Lambert + ambient with a light fixed to the camera, above-left and behind it (`light`, from
// light_direction once per render); `normal` is turned towards the viewer first (both sides of a
// surface are lit, holes show the inside).
inline constexpr double kAmbient = 0.3;
double shading(const Vec3d& light, const Vec3d& view_direction, const Vec3d& normal);
// The light's unit direction of shading(): towards the light, in world space.
Vec3d light_direction(const PixelRays& rays);

// Footprint components are clamped to this length (exemplar pixels): a footprint wider than any
// exemplar already filters to the mean, and grazing angles (the ray along the plane) stay finite.
inline constexpr double kMaxFootprint = 65536.0;

// render_mesh()'s checks of its arguments, shared by every backend (std::invalid_argument, one
// sentence): an empty model, an output of other channels, a mapping the model lacks, the uv
// mapping on a mesh without uvs, a texture scale that is not positive or puts the mesh beyond
// kPositionLimit.
void check_mesh_render_arguments(const Model& model, const Mesh& mesh,
                                 const MeshRenderOptions& options, ImageView<float> out);

}  // namespace stochtex
