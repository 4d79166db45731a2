#pragma once
// The 3-D arithmetic of meshes, cameras and shading (docs/meshes.md), in double, shared by the
// mesh checks (mesh.cpp), the CPU rasteriser (mesh_render.cpp) and, later, the GL rasteriser's
// uniforms.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "stochtex/surface.hpp"

namespace stochtex {

inline Vec3d operator+(const Vec3d& a, const Vec3d& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3d operator-(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3d operator*(const Vec3d& a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3d& a) {
  return std::sqrt(dot(a, a));
}
inline Vec3d normalized(const Vec3d& a) {
  return a * (1.0 / length(a));
}

struct Box {
  Vec3d min;
  Vec3d max;
};

inline Box bounding_box(const std::vector<Vec3d>& points) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Box box{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  for (const Vec3d& p : points) {
    box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y), std::min(box.min.z, p.z)};
    box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y), std::max(box.max.z, p.z)};
  }
  return box;
}

}  // namespace stochtex
