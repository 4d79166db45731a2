// The picture of docs/methods/tiling.md's triplanar paragraph (scripts/triplanar_picture.sh): an
// orthographic view of a sphere without texture coordinates, textured by tiling's triplanar
// histogram-preserving blending (left) and by linear triplanar mapping (right), as figure 16 of
// the tiling paper. Footprints are the screen derivatives of the sphere's points, so the rim
// (grazing views) is filtered. Usage: stochtex_triplanar_sphere EXEMPLAR OUT.png [SIZE] [SEED]

#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"

namespace {

using stochtex::Vec3d;

Vec3d scaled(const Vec3d& v, double s) {
  return {v.x * s, v.y * s, v.z * s};
}
Vec3d plus(const Vec3d& a, const Vec3d& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d normalised(const Vec3d& v) {
  return scaled(v, 1.0 / std::sqrt(dot(v, v)));
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: stochtex_triplanar_sphere EXEMPLAR OUT.png [SIZE] [SEED]\n";
    return 2;
  }
  try {
    using namespace stochtex;
    const int size = argc > 3 ? std::atoi(argv[3]) : 256;
    const auto seed = static_cast<std::uint32_t>(argc > 4 ? std::atoi(argv[4]) : 1);
    const ImageF exemplar = read_image(argv[1]);
    const Model model = analyze("tiling", exemplar.view(), {}, 0);
    // A sphere of 1.2 exemplars' radius seen along (1, 0.8, 0.6): all three planes show, and
    // their overlaps (normals between the axes) fill most of the disc.
    const double radius = 1.2 * std::min(exemplar.width(), exemplar.height());
    const Vec3d view = normalised({1.0, 0.8, 0.6});
    const Vec3d right = normalised(cross({0.0, 0.0, 1.0}, view));
    const Vec3d up = cross(view, right);
    const double pixel = 2.1 * radius / size;
    std::vector<SurfacePoint> points;
    std::vector<int> where;
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const double s = (i + 0.5 - 0.5 * size) * pixel;
        const double t = (0.5 * size - j - 0.5) * pixel;
        const double h2 = radius * radius - s * s - t * t;
        if (h2 <= 0.0) continue;
        const double h = std::max(std::sqrt(h2), 1e-3 * radius);
        const Vec3d position = plus(plus(scaled(right, s), scaled(up, t)), scaled(view, h));
        const Vec3d normal = normalised(position);
        const Vec3d tangent = normalised(plus(right, scaled(normal, -dot(right, normal))));
        // d position / d screen x and y (y down), from h = sqrt(r^2 - s^2 - t^2).
        const Vec3d dpdx = scaled(plus(right, scaled(view, -s / h)), pixel);
        const Vec3d dpdy = scaled(plus(up, scaled(view, -t / h)), -pixel);
        points.push_back({position, normal, tangent, dpdx, dpdy});
        where.push_back(j * size + i);
      }
    ImageF picture(2 * size, size, model.channels());
    for (float& v : picture.pixels()) v = 1.0f;
    for (int side = 0; side < 2; ++side) {
      SurfaceOptions options;
      options.mapping = side == 0 ? SurfaceMapping::triplanar : SurfaceMapping::triplanar_linear;
      ImageF values(static_cast<int>(points.size()), 1, model.channels());
      evaluate_surface(model, points, options, seed, values.view());
      for (std::size_t k = 0; k < points.size(); ++k)
        for (int c = 0; c < model.channels(); ++c)
          picture.at(side * size + where[k] % size, where[k] / size, c) =
              values.at(static_cast<int>(k), 0, c);
    }
    write_image(argv[2], picture.view(), 8);
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "stochtex_triplanar_sphere: " << error.what() << "\n";
    return 1;
  }
}
