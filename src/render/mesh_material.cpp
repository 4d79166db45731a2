#include "render/mesh_material.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/triplanar.hpp"
#include "model/map_layout.hpp"
#include "stochtex/error.hpp"
#include "stochtex/render.hpp"

namespace stochtex {
namespace {

constexpr std::array<std::string_view, 3> kOcclusionNames{"ao", "occlusion", "ambient_occlusion"};

float value(ImageView<const float> values, std::size_t index, int channel) {
  return values.at(static_cast<int>(index), 0, channel);
}

ImageView<float> row_view(std::vector<float>& storage, std::size_t count, int channels) {
  storage.resize(count * static_cast<std::size_t>(channels));
  const auto width = static_cast<int>(count);
  return {storage.data(), width, 1, channels, width * channels};
}

// The derived normal map's height changes along each fragment's footprint steps: slope_scale times
// half the height's change from p - dpdx to p + dpdx (x) and from p - dpdy to p + dpdy (y).
std::vector<Vec2d> height_changes(const Model& model, const MeshMaterial& material,
                                  std::span<const MeshFragment> fragments,
                                  const MeshRenderOptions& options, const SurfaceOptions& surface,
                                  std::uint32_t seed) {
  const std::size_t count = fragments.size() * 4;
  std::vector<float> storage;
  const ImageView<float> heights = row_view(storage, count, model.channels());
  if (!options.mapping) {
    std::vector<Vec2d> positions;
    std::vector<Footprint> footprints;
    for (const MeshFragment& f : fragments) {
      const Vec2d& dx = f.uv_footprint.dpdx;
      const Vec2d& dy = f.uv_footprint.dpdy;
      for (const Vec2d step : {Vec2d{-dx.x, -dx.y}, dx, Vec2d{-dy.x, -dy.y}, dy}) {
        positions.push_back({f.uv.x + step.x, f.uv.y + step.y});
        footprints.push_back(f.uv_footprint);
      }
    }
    evaluate_uv(model, positions, footprints, seed, options, heights);
  } else {
    std::vector<SurfacePoint> points;
    for (const MeshFragment& f : fragments)
      for (const Vec3d step :
           {f.point.dpdx * -1.0, f.point.dpdx, f.point.dpdy * -1.0, f.point.dpdy}) {
        SurfacePoint p = f.point;
        p.position = p.position + step;
        points.push_back(p);
      }
    evaluate_surface(model, points, surface, seed, heights);
  }
  std::vector<Vec2d> changes;
  const double half = 0.5 * material.slope_scale;
  const ImageView<const float> h = heights;
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const auto at = [&](std::size_t k) {
      return static_cast<double>(value(h, 4 * i + k, material.height));
    };
    changes.push_back({half * (at(1) - at(0)), half * (at(3) - at(2))});
  }
  return changes;
}

// Stored slopes through a triplanar mapping: each plane alone (the mapping at a normal along the
// plane's axis gives that plane all the weight), its slopes the gradient of its height in the
// plane, blended as surface gradients with the mapping's weights at the fragment's normal.
void triplanar_slope_gradients(const Model& model, int slopes,
                               std::span<const MeshFragment> fragments,
                               const SurfaceOptions& surface, std::uint32_t seed,
                               std::span<Vec3d> gradients) {
  std::vector<std::array<double, 3>> weights;
  for (const MeshFragment& f : fragments)
    weights.push_back(triplanar_weights(f.normal, surface.triplanar_sharpness));
  std::vector<float> storage;
  for (int k = 0; k < 3; ++k) {
    const auto axis = [](int a) {
      return Vec3d{a == 0 ? 1.0 : 0.0, a == 1 ? 1.0 : 0.0, a == 2 ? 1.0 : 0.0};
    };
    std::vector<SurfacePoint> points;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < fragments.size(); ++i) {
      if (weights[i][static_cast<std::size_t>(k)] == 0.0) continue;
      SurfacePoint p = fragments[i].point;
      p.normal = axis(k);
      p.tangent = axis((k + 1) % 3);
      points.push_back(p);
      which.push_back(i);
    }
    if (points.empty()) continue;
    const ImageView<float> plane = row_view(storage, points.size(), model.channels());
    evaluate_surface(model, points, surface, seed, plane);
    for (std::size_t j = 0; j < points.size(); ++j) {
      const std::size_t i = which[j];
      const Vec2d g =
          texture_gradient_of_slopes(value(plane, j, slopes), value(plane, j, slopes + 1));
      gradients[i] = gradients[i] + surface_gradient(fragments[i].normal, off_plane(g, k)) *
                                        weights[i][static_cast<std::size_t>(k)];
    }
  }
}

}  // namespace

MeshMaterial mesh_material(const Model& model) {
  MeshMaterial material;
  const std::span<const MapInfo> maps = model.maps();
  if (maps.empty()) return material;
  const std::vector<int> first = first_channels(maps);
  const auto channel_of = [&](const MapInfo& map) {
    return first[static_cast<std::size_t>(&map - maps.data())];
  };
  const MapInfo* colour = nullptr;
  std::string names;
  for (const MapInfo& map : maps) {
    names += (names.empty() ? "" : ", ") + map.name;
    if (map.kind == MapKind::colour &&
        (!colour || (map.name == "albedo" && colour->name != "albedo")))
      colour = &map;
    if (map.kind == MapKind::normal && !has_bump(material)) {
      if (map.derived_from.empty()) {
        material.slopes = channel_of(map);
      } else {
        const auto height = std::find_if(maps.begin(), maps.end(), [&](const MapInfo& other) {
          return other.name == map.derived_from;
        });
        material.height = channel_of(*height);
        material.slope_scale = map.slope_scale;
      }
    }
    if (map.kind == MapKind::scalar && material.occlusion < 0 &&
        std::find(kOcclusionNames.begin(), kOcclusionNames.end(), map.name) !=
            kOcclusionNames.end())
      material.occlusion = channel_of(map);
  }
  if (!colour)
    throw Error(
        ErrorCode::invalid_input,
        "render-mesh shades a material's colour map and this material has none (its maps: " +
            names + "); analyse it with one, e.g. --map albedo=FILE");
  material.colour = channel_of(*colour);
  material.colours = colour->channels;
  return material;
}

void bump_gradients(const Model& model, const MeshMaterial& material, const Mesh& mesh,
                    std::span<const MeshFragment> fragments, const MeshRenderOptions& options,
                    const SurfaceOptions& surface, std::uint32_t seed,
                    ImageView<const float> values, std::span<Vec3d> gradients) {
  std::fill(gradients.begin(), gradients.end(), Vec3d{});
  const bool uv = !options.mapping;
  const double texture_scale = options.texture_scale;
  if (material.height >= 0) {
    const std::vector<Vec2d> changes =
        height_changes(model, material, fragments, options, surface, seed);
    for (std::size_t i = 0; i < fragments.size(); ++i) {
      const MeshFragment& f = fragments[i];
      gradients[i] =
          uv ? texture_surface_gradient(
                   f.normal, texture_gradients(mesh, f.triangle, texture_scale),
                   texture_gradient_from_steps(f.uv_footprint, changes[i].x, changes[i].y))
             : surface_gradient_from_steps(f.normal, f.point.dpdx, f.point.dpdy, changes[i].x,
                                           changes[i].y);
    }
    return;
  }
  if (material.slopes < 0) return;
  if (!uv && surface.mapping != SurfaceMapping::surface) {
    triplanar_slope_gradients(model, material.slopes, fragments, surface, seed, gradients);
    return;
  }
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const MeshFragment& f = fragments[i];
    const Vec2d g = texture_gradient_of_slopes(value(values, i, material.slopes),
                                               value(values, i, material.slopes + 1));
    if (uv) {
      gradients[i] =
          texture_surface_gradient(f.normal, texture_gradients(mesh, f.triangle, texture_scale), g);
    } else {
      const Vec3d& t = f.point.tangent;
      gradients[i] = t * g.x + cross(f.normal, t) * g.y;
    }
  }
}

}  // namespace stochtex
