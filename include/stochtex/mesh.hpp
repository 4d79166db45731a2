#pragma once
// Triangle meshes (docs/meshes.md): the data `render_mesh` (mesh_render.hpp) draws, checked before
// use. The mesh and its checks are in stochtex::runtime (an engine may build meshes itself);
// read_mesh, the OBJ reader, is in stochtex::io.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// One entry per vertex: a corner of a triangle indexes positions, normals and uvs alike (the
// OBJ reader splits a position into one vertex per distinct (position, uv, normal) it carries).
// Normals are unit length; uvs are either empty (no texture coordinates) or one per vertex.
struct Mesh {
  std::vector<Vec3d> positions;
  std::vector<Vec3d> normals;
  std::vector<Vec2d> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // The degenerate triangles prepare_mesh removed (zero area: they cover no pixel).
  std::size_t skipped_triangles = 0;
  // Set by prepare_mesh: whether one position carries uvs that differ by a non-zero whole number
  // in u or v (within 2^-16), a uv wrap seam such as a UV sphere's u = 0 and u = 1, where the uv
  // mapping shows a seam unless the texture repeats every uv unit (MeshRenderOptions::periodic).
  bool uv_wrap_seam = false;
};

// The sizes a mesh may have: with 4 Mi triangles and 4 Mi vertices a mesh holds about 300 MB
// (64 bytes a vertex, 12 a triangle) and its checks sort 12 Mi edges (200 MB), within the 2 GiB
// memory budget of a request (docs/design.md §9) beside the image being rendered.
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 22;
inline constexpr std::size_t kMaxMeshVertices = std::size_t{1} << 22;
// Coordinates beyond this are refused: the mesh's areas (products of two coordinates) then stay
// far from double's range, and a texture scale can bring any mesh within kPositionLimit.
inline constexpr double kMaxMeshCoordinate = 1e12;

// Checks a mesh before use and throws Error(invalid_input), one sentence starting with `name`
// (the file), when it has no triangle, more than the limits above, a vertex index out of range,
// a position, normal or uv that is not finite (or a coordinate beyond kMaxMeshCoordinate), a normal
// of zero length, only degenerate triangles or a non-manifold edge (one shared by more than two
// triangles; vertices at the same position are the same point, so uv seams are edges like any
// other). Degenerate triangles (an area at most 1e-12 times the squared diagonal of the bounding
// box: a repeated or collinear vertex) are removed and counted in `skipped_triangles`, as
// renderers skip them. `normals` may be empty: the check then computes them, area-weighted over
// the triangles around each position. Sets uv_wrap_seam.
void prepare_mesh(Mesh& mesh, const std::string& name);

// The OBJ file at `path` (v, vt, vn and f lines; polygons are split into fans; lines, points,
// groups and materials are ignored and no other file is opened), then prepare_mesh. Files above
// kMaxMeshFileBytes are refused before reading. Texture coordinates are kept when every corner of
// every face has one, normals likewise (otherwise they are computed). Every failure throws
// stochtex::Error, one sentence naming the file. In stochtex::io (tinyobjloader).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{256} << 20;
Mesh read_mesh(const std::filesystem::path& path);

}  // namespace stochtex
