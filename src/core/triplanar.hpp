#pragma once
// The geometry of triplanar mapping, shared by the linear baseline (src/render/surface.cpp) and
// tiling's histogram-preserving operator (TilingModel::evaluate_triplanar; its GLSL twin is tiling
// triplanar.glsl): the three axis planes and the weights the normal gives them.

#include <array>
#include <cmath>

#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// The weights of the projections on the axis planes (y,z), (z,x), (x,y): |n_k|^sharpness,
// normalised to sum 1 (a unit normal has a component >= 1/sqrt(3), so the sum is > 0 for every
// sharpness in SurfaceOptions' range).
inline std::array<double, 3> triplanar_weights(const Vec3d& normal, double sharpness) {
  std::array<double, 3> w = {std::pow(std::abs(normal.x), sharpness),
                             std::pow(std::abs(normal.y), sharpness),
                             std::pow(std::abs(normal.z), sharpness)};
  const double total = w[0] + w[1] + w[2];
  for (double& v : w) v /= total;
  return w;
}

// A position (or a footprint vector) projected on axis plane k: (y,z), (z,x) or (x,y).
inline Vec2d on_plane(const Vec3d& v, int k) {
  return k == 0 ? Vec2d{v.y, v.z} : k == 1 ? Vec2d{v.z, v.x} : Vec2d{v.x, v.y};
}

// The vector within axis plane k whose on_plane coordinates are v: a plane's 2-D gradient in space.
inline Vec3d off_plane(const Vec2d& v, int k) {
  return k == 0 ? Vec3d{0.0, v.x, v.y} : k == 1 ? Vec3d{v.y, 0.0, v.x} : Vec3d{v.x, v.y, 0.0};
}

}  // namespace stochtex
