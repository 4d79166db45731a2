#pragma once
// The 3-D Poisson impulse process of surface noise (section 6 of "Texton Noise", Galerne,
// Leclaire and Moisan, CGF 2017, doi:10.1111/cgf.13073, after Lagae et al. 2009), shared by the
// texton and Gabor surface evaluators (docs/surface.md). Space is cut into cubic cells; each cell
// holds an exact Poisson number of impulses (core/cell_count.hpp), uniform in the cell, drawn from
// the 3-D cell_key (docs/design.md §5) in a fixed order. A surface point y with frame
// (u1, u2, u3) sees the impulses x_i of the oriented box |<y - x_i, u3>| < depth,
// |<y - x_i, u1>|, |<y - x_i, u2>| < reach, as local coordinates
// (t, z1, z2) = (<y - x_i, u3>, <y - x_i, u1>, <y - x_i, u2>).
// Written in the restricted subset of docs/design.md §4 (float offsets, uint32 draws, no
// allocation), so that a GLSL port can mirror it; there is no cell cache, so the result is a pure
// function of the point, whatever the batch.

#include <cmath>
#include <cstdint>

#include "core/cell_count.hpp"
#include "core/hash.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// The local frame of a surface point in float: u1 = tangent, u2 = normal x tangent, u3 = normal.
struct SurfaceFrame {
  float u1[3];
  float u2[3];
  float u3[3];
};

inline SurfaceFrame surface_frame(const SurfacePoint& p) noexcept {
  const Vec3d& n = p.normal;
  const Vec3d& t = p.tangent;
  return {{static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.z)},
          {static_cast<float>(n.y * t.z - n.z * t.y), static_cast<float>(n.z * t.x - n.x * t.z),
           static_cast<float>(n.x * t.y - n.y * t.x)},
          {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)}};
}

// The footprint (dpdx, dpdy) projected on the tangent plane, in the frame (u1, u2): what a 2-D
// evaluator filters.
inline Footprint tangent_footprint(const SurfacePoint& p, const SurfaceFrame& f) noexcept {
  const auto along = [](const Vec3d& v, const float(&u)[3]) {
    return v.x * u[0] + v.y * u[1] + v.z * u[2];
  };
  return {{along(p.dpdx, f.u1), along(p.dpdx, f.u2)}, {along(p.dpdy, f.u1), along(p.dpdy, f.u2)}};
}

// Calls visit_cell(cx, cy, cz, ox, oy, oz) for every cell that meets the bounding box of the
// point's oriented box (half sides reach, reach, depth), in a fixed order (z, then y, then x), with
// the point's offset (ox, oy, oz) from the cell's corner in float.
template <typename VisitCell>
void for_each_surface_cell(const SurfacePoint& p, const SurfaceFrame& f, double reach, double depth,
                           double cell_size, VisitCell&& visit_cell) noexcept {
  const double position[3] = {p.position.x, p.position.y, p.position.z};
  std::int64_t first[3];
  std::int64_t last[3];
  for (int k = 0; k < 3; ++k) {
    const double extent =
        reach * (std::abs(f.u1[k]) + std::abs(f.u2[k])) + depth * std::abs(f.u3[k]);
    first[k] = static_cast<std::int64_t>(std::floor((position[k] - extent) / cell_size));
    last[k] = static_cast<std::int64_t>(std::floor((position[k] + extent) / cell_size));
  }
  for (std::int64_t cz = first[2]; cz <= last[2]; ++cz) {
    // Offsets from the cell corner in double, then float (docs/design.md §4).
    const auto oz = static_cast<float>(position[2] - static_cast<double>(cz) * cell_size);
    for (std::int64_t cy = first[1]; cy <= last[1]; ++cy) {
      const auto oy = static_cast<float>(position[1] - static_cast<double>(cy) * cell_size);
      for (std::int64_t cx = first[0]; cx <= last[0]; ++cx) {
        const auto ox = static_cast<float>(position[0] - static_cast<double>(cx) * cell_size);
        visit_cell(cx, cy, cz, ox, oy, oz);
      }
    }
  }
}

// Calls visit(rng, t, z1, z2) for every impulse of the cells of for_each_surface_cell, impulses
// outside the box included: the callee rejects them, after drawing from `rng` whatever per-impulse
// marks it needs, so that an impulse's marks do not depend on the point that sees it. `count`
// draws the cell's impulse count for cells of side `cell_size`. A cell's draws: the count's
// `chunks` uniforms, then per impulse its position's three and the marks; a callee that always
// draws (or skips) the same number of marks M puts impulse i's position at draw
// chunks + i (3 + M), which a vectorised twin uses (gabor/simd.cpp).
template <typename Visit>
void for_each_surface_impulse(const SurfacePoint& p, const SurfaceFrame& f, double reach,
                              double depth, double cell_size, const CellCount& count,
                              std::uint32_t seed, Visit&& visit) noexcept {
  const auto side = static_cast<float>(cell_size);
  for_each_surface_cell(
      p, f, reach, depth, cell_size,
      [&](std::int64_t cx, std::int64_t cy, std::int64_t cz, float ox, float oy, float oz) {
        CounterRng rng(cell_key(cx, cy, cz, seed, Stream::points));
        const std::uint32_t impulses = count(rng);
        for (std::uint32_t i = 0; i < impulses; ++i) {
          const float u = rng.uniform();
          const float v = rng.uniform();
          const float w = rng.uniform();
          const float dx = ox - u * side;
          const float dy = oy - v * side;
          const float dz = oz - w * side;
          const float t = dx * f.u3[0] + dy * f.u3[1] + dz * f.u3[2];
          const float z1 = dx * f.u1[0] + dy * f.u1[1] + dz * f.u1[2];
          const float z2 = dx * f.u2[0] + dy * f.u2[1] + dz * f.u2[2];
          visit(rng, t, z1, z2);
        }
      });
}

}  // namespace stochtex
