#include "spectral/torus_masks.hpp"

#include <cstddef>
#include <limits>

namespace stochtex {
namespace {

// Squared Euclidean distance transform of one line (Felzenszwalb & Huttenlocher 2012): d(p) =
// min_q (p - q)^2 + f(q), f = 0 on features and `kFar` elsewhere.
constexpr double kFar = 1e20;
void distance_transform_1d(const std::vector<double>& f, std::vector<double>& d,
                           std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  for (int q = 1; q < n; ++q) {
    double s = 0.0;
    while (true) {
      const int p = v[static_cast<std::size_t>(k)];
      s = ((f[static_cast<std::size_t>(q)] + double(q) * q) -
           (f[static_cast<std::size_t>(p)] + double(p) * p)) /
          (2.0 * q - 2.0 * p);
      if (s > z[static_cast<std::size_t>(k)] || k == 0) break;
      --k;
    }
    if (s <= z[static_cast<std::size_t>(k)]) {
      v[0] = q;
      z[0] = -std::numeric_limits<double>::infinity();
      z[1] = std::numeric_limits<double>::infinity();
      k = 0;
      continue;
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = s;
    z[static_cast<std::size_t>(k) + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(k) + 1] < q) ++k;
    const int p = v[static_cast<std::size_t>(k)];
    d[static_cast<std::size_t>(q)] = double(q - p) * (q - p) + f[static_cast<std::size_t>(p)];
  }
}

}  // namespace

std::vector<double> periodic_distance_squared(const std::vector<char>& inside, int size) {
  const auto n = static_cast<std::size_t>(3 * size);
  std::vector<double> f(n), d(n), z(n + 1), columns(inside.size()), result(inside.size());
  std::vector<int> v(n);
  const auto at = [size](int x, int y) { return static_cast<std::size_t>(y) * size + x; };
  for (int x = 0; x < size; ++x) {
    for (std::size_t i = 0; i < n; ++i)
      f[i] = inside[at(x, static_cast<int>(i % size))] ? kFar : 0.0;
    distance_transform_1d(f, d, v, z);
    for (int y = 0; y < size; ++y) columns[at(x, y)] = d[static_cast<std::size_t>(y + size)];
  }
  for (int y = 0; y < size; ++y) {
    for (std::size_t i = 0; i < n; ++i) f[i] = columns[at(static_cast<int>(i % size), y)];
    distance_transform_1d(f, d, v, z);
    for (int x = 0; x < size; ++x) result[at(x, y)] = d[static_cast<std::size_t>(x + size)];
  }
  return result;
}

// Labels of the 8-connected parts of `inside` on the size x size torus (-1 outside).
std::vector<int> connected_parts(const std::vector<char>& inside, int size) {
  std::vector<int> label(inside.size(), -1);
  std::vector<int> stack;
  int next = 0;
  for (std::size_t start = 0; start < inside.size(); ++start) {
    if (!inside[start] || label[start] >= 0) continue;
    label[start] = next;
    stack.push_back(static_cast<int>(start));
    while (!stack.empty()) {
      const int index = stack.back();
      stack.pop_back();
      const int x = index % size;
      const int y = index / size;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto neighbour =
              static_cast<std::size_t>(((y + dy + size) % size) * size + (x + dx + size) % size);
          if (inside[neighbour] && label[neighbour] < 0) {
            label[neighbour] = next;
            stack.push_back(static_cast<int>(neighbour));
          }
        }
    }
    ++next;
  }
  return label;
}
}  // namespace stochtex
