#include "stochtex/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <tuple>

#include "render/mesh_geometry.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& problem) {
  throw Error(ErrorCode::invalid_input,
              name + ": " + problem + "; repair the mesh (e.g. in Blender or MeshLab)");
}

// Also false for NaN.
bool within_limit(const Vec3d& v) {
  return std::abs(v.x) <= kMaxMeshCoordinate && std::abs(v.y) <= kMaxMeshCoordinate &&
         std::abs(v.z) <= kMaxMeshCoordinate;
}

// One id per distinct position (bit-identical coordinates are one point), so that the vertices a
// uv seam or a normal crease splits still share their edges.
std::vector<std::uint32_t> position_ids(const std::vector<Vec3d>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto key = [&](std::uint32_t i) {
    return std::tie(positions[i].x, positions[i].y, positions[i].z);
  };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::vector<std::uint32_t> ids(positions.size());
  std::uint32_t id = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && key(order[k]) != key(order[k - 1])) ++id;
    ids[order[k]] = id;
  }
  return ids;
}

// Whether a position (`ids`, position_ids) carries two uvs that differ by a non-zero whole number
// in u or v: each uv in steps of 2^-16 split into its whole number and its fraction, sorted, so
// that the uvs of one position with the same fractions lie side by side.
bool has_uv_wrap_seam(const std::vector<Vec2d>& uvs, const std::vector<std::uint32_t>& ids) {
  constexpr int kFractionBits = 16;
  constexpr std::int64_t kFraction = (std::int64_t{1} << kFractionBits) - 1;
  // (position, u's fraction, v's fraction, u's whole number, v's whole number); the steps stay
  // within int64 for uvs within kMaxMeshCoordinate.
  std::vector<std::array<std::int64_t, 5>> keys;
  keys.reserve(uvs.size());
  for (std::size_t v = 0; v < uvs.size(); ++v) {
    const std::int64_t u = std::llround(std::ldexp(uvs[v].x, kFractionBits));
    const std::int64_t w = std::llround(std::ldexp(uvs[v].y, kFractionBits));
    keys.push_back({ids[v], u & kFraction, w & kFraction, u >> kFractionBits, w >> kFractionBits});
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t k = 1; k < keys.size(); ++k)
    if (std::equal(keys[k].begin(), keys[k].begin() + 3, keys[k - 1].begin()) &&
        keys[k] != keys[k - 1])
      return true;
  return false;
}

void check_sizes_and_values(const Mesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) refuse(name, "the mesh has no triangle");
  if (mesh.triangles.size() > kMaxMeshTriangles || mesh.positions.size() > kMaxMeshVertices)
    refuse(name, "the mesh has " + std::to_string(mesh.triangles.size()) + " triangles and " +
                     std::to_string(mesh.positions.size()) + " vertices, more than the limits (" +
                     std::to_string(kMaxMeshTriangles) +
                     " of each) that keep a render within "
                     "the memory budget");
  if ((!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) ||
      (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()))
    refuse(name, "the mesh's normals or uvs are not one per vertex");
  for (const auto& triangle : mesh.triangles)
    for (const std::uint32_t index : triangle)
      if (index >= mesh.positions.size())
        refuse(name, "a triangle uses vertex " + std::to_string(index) + " of only " +
                         std::to_string(mesh.positions.size()));
  if (!std::all_of(mesh.positions.begin(), mesh.positions.end(), within_limit))
    refuse(name, "a vertex position is not finite (NaN or infinite) or beyond 1e12");
  for (const Vec3d& n : mesh.normals)
    if (!(std::isfinite(length(n)) && length(n) > 0.0))
      refuse(name, "a vertex normal is not finite or is zero");
  for (const Vec2d& uv : mesh.uvs)
    if (!(std::abs(uv.x) <= kMaxMeshCoordinate && std::abs(uv.y) <= kMaxMeshCoordinate))
      refuse(name, "a texture coordinate is not finite (NaN or infinite) or beyond 1e12");
}

}  // namespace

void prepare_mesh(Mesh& mesh, const std::string& name) {
  check_sizes_and_values(mesh, name);
  const Box box = bounding_box(mesh.positions);
  const Vec3d diagonal = box.max - box.min;
  const double min_double_area = 1e-12 * dot(diagonal, diagonal);
  const std::vector<std::uint32_t> ids = position_ids(mesh.positions);

  // Degenerate triangles (a UV sphere's poles, a scan's slivers) cover no pixel: skipped, as
  // renderers do, and counted for the caller to report.
  const std::size_t given = mesh.triangles.size();
  std::erase_if(mesh.triangles, [&](const std::array<std::uint32_t, 3>& triangle) {
    const auto& [a, b, c] = triangle;
    const Vec3d area =
        cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    return !(length(area) > min_double_area);
  });
  mesh.skipped_triangles += given - mesh.triangles.size();
  if (mesh.triangles.empty())
    refuse(name, "every one of its " + std::to_string(given) +
                     " triangles is degenerate (zero area: repeated or collinear vertices)");

  std::vector<std::array<std::uint32_t, 2>> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t p = ids[mesh.triangles[t][static_cast<std::size_t>(k)]];
      const std::uint32_t q = ids[mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)]];
      edges.push_back({std::min(p, q), std::max(p, q)});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k + 2 < edges.size(); ++k)
    if (edges[k] == edges[k + 2])
      refuse(name, "the mesh is not manifold: an edge is shared by more than two triangles");

  if (mesh.normals.empty()) {
    // Area-weighted: the cross product of two edges is twice the triangle's area along its normal.
    std::vector<Vec3d> sums(mesh.positions.size());
    for (const auto& [a, b, c] : mesh.triangles) {
      const Vec3d n =
          cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
      for (const std::uint32_t v : {a, b, c}) sums[ids[v]] = sums[ids[v]] + n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3d& n = sums[ids[v]];
      // Opposite faces around one position (a sheet folded onto itself) cancel: any unit vector
      // will do there, the pixel's face normal replaces it (mesh_render.cpp).
      mesh.normals[v] = length(n) > 0.0 ? n * (1.0 / length(n)) : Vec3d{0.0, 0.0, 1.0};
    }
  } else {
    for (Vec3d& n : mesh.normals) n = n * (1.0 / length(n));
  }
  mesh.uv_wrap_seam = has_uv_wrap_seam(mesh.uvs, ids);
}

}  // namespace stochtex
