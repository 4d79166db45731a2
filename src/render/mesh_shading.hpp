#pragma once
// What a rasteriser of meshes needs besides visibility (docs/meshes.md): the camera's rays, the
// tangent frame field, the footprints from ray differentials and the shading. The CPU rasteriser
// (mesh_render.cpp) uses them; a GL rasteriser passes the same rays and light as uniforms.

#include <cstdint>
#include <span>

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
// surface are lit, holes show the inside): lambert(light, facing_viewer(view_direction, normal),
// 1).
inline constexpr double kAmbient = 0.3;
double shading(const Vec3d& light, const Vec3d& view_direction, const Vec3d& normal);
// The normal, or its opposite where it faces away from the viewer (view_direction: from the eye).
Vec3d facing_viewer(const Vec3d& view_direction, const Vec3d& normal);
// kAmbient * ambient_occlusion + (1 - kAmbient) max(0, n.l) of a normal facing the viewer.
double lambert(const Vec3d& light, const Vec3d& facing_normal, double ambient_occlusion);
// The light's unit direction of shading(): towards the light, in world space.
Vec3d light_direction(const PixelRays& rays);

// Bump mapping by surface gradients (M. S. Mikkelsen, "Surface Gradient-Based Bump Mapping
// Framework", JCGT 9(3), 2020, https://jcgt.org/published/0009/03/04/): a height H on a surface
// of unit normal n turns the normal into normalize(n - grad_S H), grad_S H the height's gradient
// within the tangent plane (the surface gradient). The height and the positions are in
// the same units; every function below gives grad_S H in them.

// The surface gradient of a height whose gradient in space is `gradient` (a height defined in
// space, e.g. one triplanar projection's, whose gradient lies in its plane): its tangent part,
// gradient - n (n . gradient) (the paper's surfgrad of a volume gradient).
Vec3d surface_gradient(const Vec3d& n, const Vec3d& gradient);

// The surface gradient of a height that changes by dh_x over the step dpdx and by dh_y over dpdy
// (two steps along the surface, e.g. a pixel's footprint): the tangent vector v with
// v . sigma_x = dh_x and v . sigma_y = dh_y, sigma the steps projected on the tangent plane,
// v = (dh_x (sigma_y x n) + dh_y (n x sigma_x)) / (sigma_x . (sigma_y x n)) (the paper's surface
// gradient from screen-space derivatives). Zero where the steps are parallel.
Vec3d surface_gradient_from_steps(const Vec3d& n, const Vec3d& dpdx, const Vec3d& dpdy, double dh_x,
                                  double dh_y);

// The gradients, within a triangle's plane, of the texture coordinates p = scale * uv (exemplar
// pixels) per unit of position: p_x(q) = p_x(q0) + texture_x . (q - q0), likewise y.
struct TextureGradients {
  Vec3d x;
  Vec3d y;
};
TextureGradients texture_gradients(const Mesh& mesh, std::uint32_t triangle, double scale);

// The surface gradient of a height given over the texture coordinates: `gradient` its gradient
// over p (height per exemplar pixel), the height in units of one exemplar pixel's size on the
// surface, l = 1 / sqrt(|texture_x x texture_y|) (the square root of a pixel's area there). Then
// grad_S H = l (gradient_x grad_S p_x + gradient_y grad_S p_y), grad_S p the tangent parts of the
// texture gradients: for texture coordinates that keep angles, gradient_x t + gradient_y b with t
// and b the unit tangents along p_x and p_y, the tangent-space normal map's convention. Zero on a
// triangle whose texture coordinates are degenerate.
Vec3d texture_surface_gradient(const Vec3d& n, const TextureGradients& texture,
                               const Vec2d& gradient);

// The gradient g over the texture of a height that changes by dh_x over the footprint's step
// dpdx and by dh_y over dpdy: g . dpdx = dh_x, g . dpdy = dh_y. Zero where the footprint is
// degenerate (its steps parallel or zero).
Vec2d texture_gradient_from_steps(const Footprint& footprint, double dh_x, double dh_y);

// A normal map's stored slopes s (y up the image, stochtex/model.hpp MapKind::normal) as the
// height's gradient over the texture coordinates (y down the image, as rows and p_y grow).
inline Vec2d texture_gradient_of_slopes(double slope_x, double slope_y) {
  return {slope_x, -slope_y};
}

// The bumped normal normalize(n - surface_gradient).
Vec3d bumped_normal(const Vec3d& n, const Vec3d& surface_gradient);

// What one covered pixel needs for texturing and shading (render_mesh).
struct MeshFragment {
  int x = 0;
  int y = 0;
  std::uint32_t triangle = 0;
  Vec3d direction;     // the pixel's ray, from the eye
  Vec3d normal;        // unit, interpolated (the face's where that cancels)
  SurfacePoint point;  // in model space
  Vec2d uv;            // in model space, with its footprint (the uv mapping)
  Footprint uv_footprint;
};

// Footprint components are clamped to this length (exemplar pixels): a footprint wider than any
// exemplar already filters to the mean, and grazing angles (the ray along the plane) stay finite.
inline constexpr double kMaxFootprint = 65536.0;

// render_mesh()'s checks of its arguments, shared by every backend (std::invalid_argument, one
// sentence): an empty model, an output of other channels, a mapping the model lacks, the uv
// mapping on a mesh without uvs, a texture scale that is not positive or puts the mesh beyond
// kPositionLimit, a refused options.periodic (mesh_periodic_refusal).
void check_mesh_render_arguments(const Model& model, const Mesh& mesh,
                                 const MeshRenderOptions& options, ImageView<float> out);

// The uv mapping's texture at `positions` (the uvs times the texture scale) with their
// footprints: evaluate(), or with options.periodic evaluate_periodic() repeating every uv unit.
void evaluate_uv(const Model& model, std::span<const Vec2d> positions,
                 std::span<const Footprint> footprints, std::uint32_t seed,
                 const MeshRenderOptions& options, ImageView<float> out);

}  // namespace stochtex
