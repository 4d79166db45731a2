// read_mesh (stochtex/mesh.hpp): Wavefront OBJ through Debian's tinyobjloader, then the checks of
// prepare_mesh.

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>

#include "core/file_message.hpp"
#include "core/input_file.hpp"
#include "core/memory_budget.hpp"
#include "stochtex/error.hpp"
#include "stochtex/mesh.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;

// The first line of tinyobjloader's message (it writes several, ending in newlines).
std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// What the OBJ text declares, counted before tinyobjloader reads it.
struct ObjCounts {
  std::uint64_t vertices = 0;  // v, vt and vn lines
  std::uint64_t faces = 0;     // f, l and p lines
  std::uint64_t corners = 0;   // the indices on them
};

// The peak of reading `text_bytes` of OBJ text that declares `counts`: the text and
// tinyobjloader's copy, each vertex's values, each corner's indices and each face's records,
// through to the mesh. Measured with /usr/bin/time: 460 MB for 20 MB of `f 1 2 3` lines
// (7.5 M corners, 2.5 M faces), 465 MB for 40 000 faces of 300 corners, 96 MB for 2.5 M `v` lines;
// the constants give 490, 530 and 120 MB.
std::uint64_t mesh_read_peak_bytes(std::uint64_t text_bytes, const ObjCounts& counts) {
  return kFixedPeakBytes + 2 * text_bytes + 32 * counts.vertices + 40 * counts.corners +
         60 * counts.faces;
}

// tinyobjloader reads a number it cannot parse ("nan", "inf", "1x") as 0, so the v, vt and vn
// lines are checked first: every value a finite number. Returns what the text declares.
ObjCounts check_numbers(const std::string& text, const std::string& name) {
  ObjCounts counts;
  std::size_t line_number = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    ++line_number;
    std::string_view line(text.data() + start, end - start);
    line = line.substr(0, line.find('#'));
    start = end + 1;
    const auto word = [&] {
      const std::size_t first = line.find_first_not_of(" \t\r");
      if (first == std::string_view::npos) return std::string_view();
      const std::size_t last = std::min(line.find_first_of(" \t\r", first), line.size());
      const std::string_view token = line.substr(first, last - first);
      line.remove_prefix(last);
      return token;
    };
    const std::string_view keyword = word();
    if (keyword == "f" || keyword == "l" || keyword == "p") {
      ++counts.faces;
      while (!word().empty()) ++counts.corners;
    }
    if (keyword != "v" && keyword != "vt" && keyword != "vn") continue;
    ++counts.vertices;
    for (std::string_view token = word(); !token.empty(); token = word()) {
      if (token.front() == '+') token.remove_prefix(1);
      double value = 0.0;
      const auto [end_of_number, error] =
          std::from_chars(token.data(), token.data() + token.size(), value);
      if (error != std::errc() || end_of_number != token.data() + token.size() ||
          !std::isfinite(value))
        throw Error(ErrorCode::invalid_input,
                    name + ": line " + std::to_string(line_number) + " has '" +
                        std::string(token.substr(0, 32)) +
                        "', which is not a finite number; repair the mesh");
    }
  }
  return counts;
}

// Splits the faces into fans and each position into one vertex per distinct (position, uv,
// normal) triple its corners use.
Mesh to_mesh(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes,
             const std::string& name) {
  bool all_uvs = true;
  bool all_normals = true;
  std::size_t triangles = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      all_uvs = all_uvs && index.texcoord_index >= 0;
      all_normals = all_normals && index.normal_index >= 0;
    }
    for (const unsigned char corners : shape.mesh.num_face_vertices)
      triangles += corners >= 3 ? corners - 2u : 0u;
  }
  if (triangles > kMaxMeshTriangles)
    throw Error(ErrorCode::invalid_input,
                name + ": the mesh has " + std::to_string(triangles) +
                    " triangles, more than the limit of " + std::to_string(kMaxMeshTriangles) +
                    " that keeps a render within the memory budget; simplify the mesh");
  const auto out_of_range = [&](int index, std::size_t size, int stride) {
    return index >= 0 && static_cast<std::size_t>(index) * static_cast<std::size_t>(stride) +
                                 static_cast<std::size_t>(stride) >
                             size;
  };

  Mesh mesh;
  std::map<std::tuple<int, int, int>, std::uint32_t> vertices;
  const auto vertex = [&](const tinyobj::index_t& index) {
    const int uv = all_uvs ? index.texcoord_index : -1;
    const int normal = all_normals ? index.normal_index : -1;
    if (index.vertex_index < 0 || out_of_range(index.vertex_index, attrib.vertices.size(), 3) ||
        out_of_range(uv, attrib.texcoords.size(), 2) ||
        out_of_range(normal, attrib.normals.size(), 3))
      throw Error(ErrorCode::invalid_input,
                  name +
                      ": a face uses a vertex, texture coordinate or normal index that is out "
                      "of range; repair the mesh");
    const auto [at, added] = vertices.try_emplace({index.vertex_index, uv, normal},
                                                  static_cast<std::uint32_t>(vertices.size()));
    if (added) {
      if (vertices.size() > kMaxMeshVertices)
        throw Error(ErrorCode::invalid_input,
                    name + ": the mesh has more than " + std::to_string(kMaxMeshVertices) +
                        " vertices, the limit that keeps a render within the memory budget; "
                        "simplify the mesh");
      const auto v = static_cast<std::size_t>(index.vertex_index) * 3;
      mesh.positions.push_back(
          {attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]});
      if (uv >= 0) {
        const auto t = static_cast<std::size_t>(uv) * 2;
        mesh.uvs.push_back({attrib.texcoords[t], attrib.texcoords[t + 1]});
      }
      if (normal >= 0) {
        const auto n = static_cast<std::size_t>(normal) * 3;
        mesh.normals.push_back({attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]});
      }
    }
    return at->second;
  };

  mesh.triangles.reserve(triangles);
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t first = 0;
    for (const unsigned char corners : shape.mesh.num_face_vertices) {
      for (std::size_t k = 2; k < corners; ++k)
        mesh.triangles.push_back({vertex(shape.mesh.indices[first]),
                                  vertex(shape.mesh.indices[first + k - 1]),
                                  vertex(shape.mesh.indices[first + k])});
      first += corners;
    }
  }
  return mesh;
}

}  // namespace

Mesh read_mesh(const fs::path& path) {
  const std::string name = quoted(path);
  std::string text =
      InputFile(path, "a mesh").read_all(kMaxMeshFileBytes, "simplify or split the mesh");
  check_memory_budget(mesh_read_peak_bytes(text.size(), check_numbers(text, name)),
                      "reading the mesh " + name, "simplify or split the mesh");
  std::istringstream stream(std::move(text));
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings;
  std::string errors;
  // No material reader: a file never makes stochtex open another file. No triangulation either:
  // the fans are made in to_mesh, under its checks.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, nullptr,
                        false)) {
    const std::string reason = first_line(errors);
    throw Error(ErrorCode::format, name + ": not a readable OBJ mesh" +
                                       (reason.empty() ? std::string() : " (" + reason + ")"));
  }
  Mesh mesh = to_mesh(attrib, shapes, name);
  prepare_mesh(mesh, name);
  return mesh;
}

}  // namespace stochtex
