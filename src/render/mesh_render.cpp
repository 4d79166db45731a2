#include "stochtex/mesh_render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/parallel.hpp"
#include "core/srgb.hpp"
#include "model/model_colour.hpp"
#include "render/mesh_material.hpp"
#include "render/mesh_shading.hpp"
#include "stochtex/error.hpp"
#include "stochtex/render.hpp"

namespace stochtex {
namespace {

constexpr int kTile = 32;
// A triangle whose screen box covers more tiles than this is tested by every tile instead of being
// listed in each, so that the bins hold at most this many entries per triangle.
constexpr std::size_t kMaxTilesPerTriangle = 64;
constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

bool finite(const Vec3d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The nearest triangle along a pixel's ray: ray parameter t and barycentrics (1 - u - v, u, v).
struct Hit {
  double t = std::numeric_limits<double>::infinity();
  std::uint32_t triangle = kNoTriangle;
  double u = 0.0;
  double v = 0.0;
};

// Moller-Trumbore ray-triangle intersection in double, edges included (a point on a shared edge
// belongs to both triangles; the nearer, then the lower index, wins: the result never depends on
// the order triangles are tested in).
void intersect(const Vec3d& eye, const Vec3d& d, const Mesh& mesh, std::uint32_t index, Hit& best) {
  const auto& [a, b, c] = mesh.triangles[index];
  const Vec3d e1 = mesh.positions[b] - mesh.positions[a];
  const Vec3d e2 = mesh.positions[c] - mesh.positions[a];
  const Vec3d p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0.0) return;
  const double inverse = 1.0 / det;
  const Vec3d s = eye - mesh.positions[a];
  const double u = dot(s, p) * inverse;
  if (!(u >= 0.0 && u <= 1.0)) return;
  const Vec3d q = cross(s, e1);
  const double v = dot(d, q) * inverse;
  if (!(v >= 0.0 && u + v <= 1.0)) return;
  const double t = dot(e2, q) * inverse;
  if (!(t > 0.0)) return;
  if (t < best.t || (t == best.t && index < best.triangle)) best = {t, index, u, v};
}

// Pixel ranges (inclusive) of a triangle's screen box, or `everywhere` when a vertex is behind the
// eye (its projection is unbounded), or empty.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool everywhere = false;
};

PixelBox screen_box(const PixelRays& rays, const Mesh& mesh, std::uint32_t index) {
  const double step2 = dot(rays.step_x, rays.step_x);
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -xmin, ymax = -xmin;
  int behind = 0;
  for (const std::uint32_t vertex : mesh.triangles[index]) {
    const Vec3d r = mesh.positions[vertex] - rays.eye;
    const double z = dot(r, rays.forward);
    if (!(z > 0.0)) {
      ++behind;
      continue;
    }
    // The pixel whose centre the vertex projects to, in continuous pixel coordinates.
    const double x = dot(r, rays.step_x) / (step2 * z) + 0.5 * rays.width - 0.5;
    const double y = dot(r, rays.step_y) / (step2 * z) + 0.5 * rays.height - 0.5;
    xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  }
  if (behind == 3) return {};
  if (behind > 0) return {0, 0, rays.width - 1, rays.height - 1, true};
  // One pixel of margin for rounding: the intersection test decides.
  const auto clamp = [](double value, int high) {
    return static_cast<int>(std::clamp(value, -1.0, static_cast<double>(high) + 1.0));
  };
  PixelBox box{clamp(std::floor(xmin) - 1.0, rays.width),
               clamp(std::floor(ymin) - 1.0, rays.height), clamp(std::ceil(xmax) + 1.0, rays.width),
               clamp(std::ceil(ymax) + 1.0, rays.height)};
  box.x0 = std::max(box.x0, 0), box.y0 = std::max(box.y0, 0);
  box.x1 = std::min(box.x1, rays.width - 1), box.y1 = std::min(box.y1, rays.height - 1);
  return box;
}

// Triangles listed per tile of kTile x kTile pixels, and those every tile tests.
struct Bins {
  int tiles_x = 0;
  int tiles_y = 0;
  std::vector<std::vector<std::uint32_t>> tiles;
  std::vector<std::uint32_t> everywhere;
  std::vector<PixelBox> boxes;  // per triangle
};

Bins bin_triangles(const PixelRays& rays, const Mesh& mesh) {
  Bins bins;
  bins.tiles_x = (rays.width + kTile - 1) / kTile;
  bins.tiles_y = (rays.height + kTile - 1) / kTile;
  bins.tiles.resize(static_cast<std::size_t>(bins.tiles_x) *
                    static_cast<std::size_t>(bins.tiles_y));
  bins.boxes.resize(mesh.triangles.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const PixelBox box = screen_box(rays, mesh, t);
    bins.boxes[t] = box;
    if (box.x1 < box.x0 || box.y1 < box.y0) continue;
    const int tx0 = box.x0 / kTile, tx1 = box.x1 / kTile;
    const int ty0 = box.y0 / kTile, ty1 = box.y1 / kTile;
    if (box.everywhere ||
        static_cast<std::size_t>(tx1 - tx0 + 1) * static_cast<std::size_t>(ty1 - ty0 + 1) >
            kMaxTilesPerTriangle) {
      bins.everywhere.push_back(t);
      continue;
    }
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        bins.tiles[static_cast<std::size_t>(ty * bins.tiles_x + tx)].push_back(t);
  }
  return bins;
}

template <typename T>
T interpolate(const std::vector<T>& values, const std::array<std::uint32_t, 3>& corners,
              const Hit& hit) {
  const double w0 = 1.0 - hit.u - hit.v;
  const T& a = values[corners[0]];
  const T& b = values[corners[1]];
  const T& c = values[corners[2]];
  if constexpr (std::is_same_v<T, Vec2d>)
    return {w0 * a.x + hit.u * b.x + hit.v * c.x, w0 * a.y + hit.u * b.y + hit.v * c.y};
  else
    return a * w0 + b * hit.u + c * hit.v;
}

Vec3d clamp_length(const Vec3d& v, double limit) {
  const double l = length(v);
  return l > limit ? v * (limit / l) : v;
}

MeshFragment make_fragment(const PixelRays& rays, const Mesh& mesh, const Hit& hit, int x, int y,
                           double scale, bool uv) {
  const auto& corners = mesh.triangles[hit.triangle];
  const Vec3d& p0 = mesh.positions[corners[0]];
  const Vec3d e1 = mesh.positions[corners[1]] - p0;
  const Vec3d e2 = mesh.positions[corners[2]] - p0;
  const Vec3d face = cross(e1, e2);
  MeshFragment f;
  f.x = x;
  f.y = y;
  f.triangle = hit.triangle;
  f.direction = rays.direction(x, y);
  const Vec3d position = rays.eye + f.direction * hit.t;
  const PlaneHit differentials = plane_differentials(rays, f.direction, hit.t, face);
  const Vec3d interpolated = interpolate(mesh.normals, corners, hit);
  f.normal = length(interpolated) > 1e-6 ? normalized(interpolated) : normalized(face);
  f.point.position = position * scale;
  f.point.normal = f.normal;
  f.point.tangent = surface_tangent(f.normal);
  f.point.dpdx = clamp_length(differentials.dpdx * scale, kMaxFootprint);
  f.point.dpdy = clamp_length(differentials.dpdy * scale, kMaxFootprint);
  if (uv) {
    const BarycentricGradients gradients = barycentric_gradients(e1, e2);
    const Vec2d& t0 = mesh.uvs[corners[0]];
    const Vec2d& t1 = mesh.uvs[corners[1]];
    const Vec2d& t2 = mesh.uvs[corners[2]];
    const auto uv_derivative = [&](const Vec3d& dp) {
      const double a = dot(gradients.du, dp);
      const double b = dot(gradients.dv, dp);
      const double dx = ((t1.x - t0.x) * a + (t2.x - t0.x) * b) * scale;
      const double dy = ((t1.y - t0.y) * a + (t2.y - t0.y) * b) * scale;
      const double l = std::hypot(dx, dy);
      return l > kMaxFootprint ? Vec2d{dx * kMaxFootprint / l, dy * kMaxFootprint / l}
                               : Vec2d{dx, dy};
    };
    const Vec2d at = interpolate(mesh.uvs, corners, hit);
    f.uv = {at.x * scale, at.y * scale};
    f.uv_footprint = {uv_derivative(differentials.dpdx), uv_derivative(differentials.dpdy)};
  }
  return f;
}

}  // namespace

void check_mesh_render_arguments(const Model& model, const Mesh& mesh,
                                 const MeshRenderOptions& options, ImageView<float> out) {
  if (model.empty()) throw std::invalid_argument("render_mesh: the model is empty");
  const MeshMaterial material = mesh_material(model);
  if (material.colours > 0 && (out.channels != material.colours || out.width < 1 || out.height < 1))
    throw std::invalid_argument(
        "render_mesh: the output must be an image of the material's colour map's " +
        std::to_string(material.colours) + " channels");
  if (material.colours == 0 &&
      (out.channels != model.channels() || out.width < 1 || out.height < 1))
    throw std::invalid_argument("render_mesh: the output must be an image of the model's " +
                                std::to_string(model.channels()) + " channels");
  if (options.mapping && !supports_mapping(model, *options.mapping))
    throw std::invalid_argument(std::string(model.method()) + " models have no " +
                                std::string(mapping_name(*options.mapping)) + " mapping");
  if (!options.mapping && mesh.uvs.empty())
    throw std::invalid_argument(
        "the uv mapping needs texture coordinates (vt) on every vertex, and the mesh has none");
  if (!(std::isfinite(options.texture_scale) && options.texture_scale > 0.0))
    throw std::invalid_argument("the texture scale must be a positive number");
  // Every sampled position lies within the mesh's (or the uvs') bounding box.
  double extent = 0.0;
  if (options.mapping) {
    const Box box = bounding_box(mesh.positions);
    extent = std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z),
                       std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z)});
  } else {
    for (const Vec2d& uv : mesh.uvs) extent = std::max({extent, std::abs(uv.x), std::abs(uv.y)});
  }
  // A derived normal map samples the height up to a footprint (kMaxFootprint) beyond.
  const double margin = material.height >= 0 ? kMaxFootprint : 0.0;
  if (!(extent * options.texture_scale <= kPositionLimit - margin))
    throw std::invalid_argument(
        "the texture scale puts the mesh beyond 2^32 exemplar pixels from the origin; use a "
        "smaller texture scale");
  if (options.periodic) {
    const std::string refusal = mesh_periodic_refusal(model, options);
    if (!refusal.empty()) throw std::invalid_argument(refusal);
  }
}

void evaluate_uv(const Model& model, std::span<const Vec2d> positions,
                 std::span<const Footprint> footprints, std::uint32_t seed,
                 const MeshRenderOptions& options, ImageView<float> out) {
  if (options.periodic)
    evaluate_periodic(model, positions, footprints, seed, out,
                      {options.texture_scale, options.texture_scale});
  else
    evaluate(model, positions, footprints, seed, out);
}

PixelRays pixel_rays(const Camera& camera, int width, int height) {
  const Vec3d view = camera.target - camera.eye;
  if (!finite(camera.eye) || !finite(camera.target) || !finite(camera.up) || !(length(view) > 0.0))
    throw std::invalid_argument("the camera's eye and target must be two distinct finite points");
  if (!(camera.vertical_fov_degrees > 0.0 && camera.vertical_fov_degrees < 180.0))
    throw std::invalid_argument("the camera's field of view must be within (0, 180) degrees");
  const Vec3d forward = normalized(view);
  const Vec3d side = cross(forward, camera.up);
  if (!(length(side) > 1e-9 * length(camera.up)))
    throw std::invalid_argument("the camera's up vector must not be along its view");
  const Vec3d right = normalized(side);
  const Vec3d down = cross(forward, right);
  const double step = 2.0 * std::tan(radians(camera.vertical_fov_degrees) / 2.0) / height;
  return {camera.eye, forward, right * step, down * step, width, height};
}

Vec3d surface_tangent(const Vec3d& normal) {
  const Vec3d east{normal.z, 0.0, -normal.x};  // Y x n
  if (length(east) > 1e-6) return normalized(east);
  return normalized(Vec3d{1.0, 0.0, 0.0} - normal * normal.x);
}

PlaneHit plane_differentials(const PixelRays& rays, const Vec3d& d, double t, const Vec3d& n) {
  const double nd = dot(n, d);
  return {(rays.step_x - d * (dot(n, rays.step_x) / nd)) * t,
          (rays.step_y - d * (dot(n, rays.step_y) / nd)) * t};
}

BarycentricGradients barycentric_gradients(const Vec3d& e1, const Vec3d& e2) {
  const Vec3d face = cross(e1, e2);
  const double n2 = dot(face, face);
  return {cross(e2, face) * (1.0 / n2), cross(face, e1) * (1.0 / n2)};
}

double shading(const Vec3d& light, const Vec3d& view_direction, const Vec3d& normal) {
  return lambert(light, facing_viewer(view_direction, normal), 1.0);
}

Vec3d facing_viewer(const Vec3d& view_direction, const Vec3d& normal) {
  return dot(normal, view_direction) > 0.0 ? normal * -1.0 : normal;
}

double lambert(const Vec3d& light, const Vec3d& facing_normal, double ambient_occlusion) {
  return kAmbient * ambient_occlusion + (1.0 - kAmbient) * std::max(0.0, dot(facing_normal, light));
}

Vec3d surface_gradient(const Vec3d& n, const Vec3d& gradient) {
  return gradient - n * dot(n, gradient);
}

Vec3d surface_gradient_from_steps(const Vec3d& n, const Vec3d& dpdx, const Vec3d& dpdy, double dh_x,
                                  double dh_y) {
  const Vec3d sigma_x = surface_gradient(n, dpdx);
  const Vec3d sigma_y = surface_gradient(n, dpdy);
  const Vec3d r1 = cross(sigma_y, n);
  const Vec3d r2 = cross(n, sigma_x);
  const double det = dot(sigma_x, r1);
  // Parallel steps (relative to their lengths, at double's resolution) determine no gradient.
  if (!(std::abs(det) > 1e-12 * length(sigma_x) * length(sigma_y))) return {};
  return (r1 * dh_x + r2 * dh_y) * (1.0 / det);
}

TextureGradients texture_gradients(const Mesh& mesh, std::uint32_t triangle, double scale) {
  const auto& [a, b, c] = mesh.triangles[triangle];
  const BarycentricGradients bary = barycentric_gradients(mesh.positions[b] - mesh.positions[a],
                                                          mesh.positions[c] - mesh.positions[a]);
  const Vec2d& t0 = mesh.uvs[a];
  const Vec2d& t1 = mesh.uvs[b];
  const Vec2d& t2 = mesh.uvs[c];
  return {(bary.du * (t1.x - t0.x) + bary.dv * (t2.x - t0.x)) * scale,
          (bary.du * (t1.y - t0.y) + bary.dv * (t2.y - t0.y)) * scale};
}

Vec3d texture_surface_gradient(const Vec3d& n, const TextureGradients& texture,
                               const Vec2d& gradient) {
  const double area = length(cross(texture.x, texture.y));  // exemplar pixels per unit area
  if (!(area > 0.0) || !std::isfinite(area)) return {};
  return surface_gradient(n, texture.x * gradient.x + texture.y * gradient.y) *
         (1.0 / std::sqrt(area));
}

Vec2d texture_gradient_from_steps(const Footprint& footprint, double dh_x, double dh_y) {
  const Vec2d& a = footprint.dpdx;
  const Vec2d& b = footprint.dpdy;
  const double det = a.x * b.y - a.y * b.x;
  if (!(std::abs(det) > 1e-12 * std::hypot(a.x, a.y) * std::hypot(b.x, b.y))) return {};
  // [a; b] g = (dh_x, dh_y) by Cramer's rule.
  return {(dh_x * b.y - dh_y * a.y) / det, (a.x * dh_y - b.x * dh_x) / det};
}

Vec3d bumped_normal(const Vec3d& n, const Vec3d& surface_gradient) {
  return normalized(n - surface_gradient);
}

Vec3d light_direction(const PixelRays& rays) {
  return normalized(rays.step_x * -0.5 + rays.step_y * -0.8 +
                    rays.forward * (-0.6 * length(rays.step_x)));
}

Camera orbit_camera(const Mesh& mesh, double azimuth_degrees, double elevation_degrees,
                    double distance, int width, int height) {
  if (!std::isfinite(azimuth_degrees) || !(std::abs(elevation_degrees) < 90.0))
    throw std::invalid_argument(
        "the camera's azimuth must be finite and its elevation within (-90, 90) degrees");
  if (!(distance > 0.0 && distance <= 1e6))
    throw std::invalid_argument("the camera's distance must be within (0, 1e6] framings");
  Camera camera;
  const Box box = bounding_box(mesh.positions);
  const Vec3d centre = (box.min + box.max) * 0.5;
  double radius = 0.0;
  for (const Vec3d& p : mesh.positions) radius = std::max(radius, length(p - centre));
  const double half_vertical = radians(camera.vertical_fov_degrees) / 2.0;
  const double half_horizontal =
      std::atan(std::tan(half_vertical) * static_cast<double>(width) / height);
  const double fit = radius / std::sin(std::min(half_vertical, half_horizontal));
  const double az = radians(azimuth_degrees);
  const double el = radians(elevation_degrees);
  const Vec3d towards_eye{std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
  camera.target = centre;
  camera.eye = centre + towards_eye * (fit * distance);
  return camera;
}

int mesh_output_channels(const Model& model) {
  if (model.empty()) throw std::invalid_argument("render_mesh: the model is empty");
  const MeshMaterial material = mesh_material(model);
  return material.colours > 0 ? material.colours : model.channels();
}

ColourSpace mesh_output_space(const Model& model) {
  if (model.empty()) throw std::invalid_argument("render_mesh: the model is empty");
  const MeshMaterial material = mesh_material(model);
  return rendered_space(
      material.colours > 0
          ? map_channel_spaces(model.maps())[static_cast<std::size_t>(material.colour)]
          : model.colour_space());
}

float mesh_background(const Model& model, const MeshRenderOptions& options) {
  return mesh_output_space(model) == ColourSpace::linear ? srgb_decode(options.background)
                                                         : options.background;
}

std::string mesh_periodic_refusal(const Model& model, const MeshRenderOptions& options) {
  if (options.mapping)
    return "a periodic texture repeats every uv unit, so it needs the uv mapping, not " +
           std::string(mapping_name(*options.mapping));
  if (const std::string refusal = periodic_refusal(model); !refusal.empty()) return refusal;
  if (!(options.texture_scale <= kPositionLimit))
    return "the period of a periodic texture, one uv unit, is the texture scale, and it is beyond "
           "2^32 exemplar pixels; use a smaller texture scale";
  return {};
}

double default_texture_scale(const Mesh& mesh) {
  const Box box = bounding_box(mesh.positions);
  const Vec3d size = box.max - box.min;
  return 1024.0 / std::max({size.x, size.y, size.z});
}

void render_mesh(const Model& model, const Mesh& mesh, const Camera& camera,
                 const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out) {
  check_mesh_render_arguments(model, mesh, options, out);
  const MeshMaterial material = mesh_material(model);
  const PixelRays rays = pixel_rays(camera, out.width, out.height);
  const Vec3d light_towards = light_direction(rays);
  SurfaceOptions surface = options.surface;
  if (options.mapping) surface.mapping = *options.mapping;
  const Bins bins = bin_triangles(rays, mesh);
  const int channels = out.channels;
  const int colours = channels == 2 || channels == 4 ? channels - 1 : channels;
  const float background = mesh_background(model, options);
  const bool uv = !options.mapping;

  const auto tiles =
      static_cast<std::size_t>(bins.tiles_x) * static_cast<std::size_t>(bins.tiles_y);
  const auto render_tile = [&](std::size_t tile) {
    const int tx = static_cast<int>(tile % static_cast<std::size_t>(bins.tiles_x));
    const int ty = static_cast<int>(tile / static_cast<std::size_t>(bins.tiles_x));
    const int x0 = tx * kTile, y0 = ty * kTile;
    const int x1 = std::min(x0 + kTile, out.width), y1 = std::min(y0 + kTile, out.height);
    std::array<Hit, kTile * kTile> hits{};
    const auto test = [&](std::uint32_t t) {
      const PixelBox& box = bins.boxes[t];
      for (int y = std::max(y0, box.y0); y < std::min(y1, box.y1 + 1); ++y)
        for (int x = std::max(x0, box.x0); x < std::min(x1, box.x1 + 1); ++x)
          intersect(rays.eye, rays.direction(x, y), mesh, t,
                    hits[static_cast<std::size_t>((y - y0) * kTile + (x - x0))]);
    };
    for (const std::uint32_t t : bins.tiles[tile]) test(t);
    for (const std::uint32_t t : bins.everywhere) test(t);

    std::vector<MeshFragment> fragments;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const Hit& hit = hits[static_cast<std::size_t>((y - y0) * kTile + (x - x0))];
        if (hit.triangle != kNoTriangle)
          fragments.push_back(make_fragment(rays, mesh, hit, x, y, options.texture_scale, uv));
        else
          for (int c = 0; c < channels; ++c) out.at(x, y, c) = c < colours ? background : 0.0f;
      }
    if (fragments.empty()) return;
    const auto count = static_cast<int>(fragments.size());
    const int model_channels = model.channels();
    std::vector<float> values(fragments.size() * static_cast<std::size_t>(model_channels));
    const ImageView<float> view{values.data(), count, 1, model_channels, count * model_channels};
    if (uv) {
      std::vector<Vec2d> positions;
      std::vector<Footprint> footprints;
      for (const MeshFragment& f : fragments) {
        positions.push_back(f.uv);
        footprints.push_back(f.uv_footprint);
      }
      evaluate_uv(model, positions, footprints, seed, options, view);
    } else {
      std::vector<SurfacePoint> points;
      for (const MeshFragment& f : fragments) points.push_back(f.point);
      evaluate_surface(model, points, surface, seed, view);
    }
    if (material.colours == 0) {
      for (int i = 0; i < count; ++i) {
        const MeshFragment& f = fragments[static_cast<std::size_t>(i)];
        const auto light = static_cast<float>(shading(light_towards, f.direction, f.normal));
        for (int c = 0; c < channels; ++c)
          out.at(f.x, f.y, c) = c < colours ? view.at(i, 0, c) * light : view.at(i, 0, c);
      }
      return;
    }
    // A material: its colour map lit with the bumped normal, turned towards the viewer as the
    // surface's own normal is, the ambient term times the ambient occlusion (within [0, 1]).
    std::vector<Vec3d> gradients(fragments.size());
    if (has_bump(material))
      bump_gradients(model, material, mesh, fragments, options, surface, seed, view, gradients);
    for (int i = 0; i < count; ++i) {
      const MeshFragment& f = fragments[static_cast<std::size_t>(i)];
      const Vec3d n = bumped_normal(f.normal, gradients[static_cast<std::size_t>(i)]);
      const double occlusion =
          material.occlusion < 0 ? 1.0 : std::clamp(view.at(i, 0, material.occlusion), 0.0f, 1.0f);
      const Vec3d facing = dot(f.normal, f.direction) > 0.0 ? n * -1.0 : n;
      const auto light = static_cast<float>(lambert(light_towards, facing, occlusion));
      for (int c = 0; c < channels; ++c)
        out.at(f.x, f.y, c) = view.at(i, 0, material.colour + c) * light;
    }
  };
  parallel_for(tiles, options.threads, render_tile, [&](std::size_t done) {
    if (options.progress) options.progress(static_cast<double>(done) / static_cast<double>(tiles));
  });
}

}  // namespace stochtex
