#pragma once
// Periodic evaluation (tileable bakes, docs/render.md "Periodic renders"): a field that repeats
// with a model-space period P, f(p + P) = f(p). Every random draw keyed by a lattice cell or
// vertex takes the cell's index modulo the cells of one period, while the geometry stays relative
// to the unwrapped cell (a kernel is evaluated at p minus its impulse's position), so each period
// holds the same impulses at the same places. That needs the cells to divide the period: each
// axis has round(P / cell) cells of side P / round(P / cell), a cell within half a cell of the
// method's over the period; the evaluators keep the impulse density (counts scale with the area)
// or the lattice's spacing per axis. Positions are first reduced into [0, P), so f(p) and f(p + P)
// are the same bits wherever that reduction is exact (pixel centres of a render are).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stochtex/model.hpp"

namespace stochtex {

// One axis of a periodic lattice: `cells` cells of side `size` make up the period exactly.
struct PeriodicAxis {
  std::int64_t cells = 1;
  double size = 1.0;

  // A cell index reduced into [0, cells): the index a random draw is keyed by. The evaluators
  // reduce positions into the period first, so their cells lie within a period of it: those skip
  // the 64-bit division.
  std::int64_t wrap(std::int64_t cell) const noexcept {
    if (cell >= 0 && cell < cells) return cell;
    if (cell < 0 && cell >= -cells) return cell + cells;
    if (cell >= cells && cell < 2 * cells) return cell - cells;
    const std::int64_t r = cell % cells;
    return r < 0 ? r + cells : r;
  }
};

// The axis of `period` (> 0) for cells of side near `cell_size` (> 0): at least one cell.
inline PeriodicAxis periodic_axis(double period, double cell_size) noexcept {
  const double cells = std::max(1.0, std::round(period / cell_size));
  return {static_cast<std::int64_t>(cells), period / cells};
}

// p reduced into [0, period) per axis.
inline Vec2d reduce_position(Vec2d p, Vec2d period) noexcept {
  const auto reduce = [](double v, double length) {
    const double r = v - std::floor(v / length) * length;
    return r < length ? r : 0.0;
  };
  return {reduce(p.x, period.x), reduce(p.y, period.y)};
}

}  // namespace stochtex
