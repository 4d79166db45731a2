// The GL mesh renderer (render_mesh_gl, stochtex/gpu.hpp; docs/meshes.md): the mesh rasterised
// into an offscreen float framebuffer with the CPU renderer's camera (src/render/mesh_shading.hpp),
// and each fragment textured the way an engine uses `export-shader`: the uv mapping calls the
// exported GLSL's stochtex_<method>(p, dpdx, dpdy, seed) with its textures bound as the README
// says (a material: stochtex_<method>_material, its colour map lit through its normal map as
// render_mesh does), the surface mappings the twin's GLSL surface function
// (gl::Twin<M>::surface_shader); footprints from the CPU's ray differentials on each triangle's
// plane (mesh_fragment.glsl). The image is drawn in tiles of at most kTile pixels a side.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gl/context.hpp"
#include "gl/export_material.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "gl/surface_shader.hpp"
#include "gl/twin.hpp"
#include "model/map_layout.hpp"
#include "render/mesh_material.hpp"
#include "render/mesh_shading.hpp"
#include "stochtex/error.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex {
namespace {

constexpr int kTile = 2048;
// The near plane, as a fraction of the farthest vertex's depth: parts of triangles nearer the eye
// than that are clipped (the CPU draws them). With reversed depth in float it costs no precision.
constexpr double kNearFraction = 1e-6;

constexpr std::array<gl::GlslConstant, 2> kMeshConstants = {{
    {"MESH_AMBIENT", static_cast<float>(kAmbient)},
    {"MESH_MAX_FOOTPRINT", static_cast<float>(kMaxFootprint)},
}};

// The fragment shader's texturing: the program and what it reads (textures or a storage buffer).
struct Texturing {
  std::string fragment;  // all of the fragment shader after the constants
  std::vector<ShaderTexture> textures;
  std::vector<float> data;
};

// The macros by which mesh_fragment.glsl shades a material m, the StochtexMaterial of the
// exported function, with the maps render_mesh picks (mesh_material): STOCHTEX_MESH_COLOUR(m) its
// colour map as a vec4, STOCHTEX_MESH_NORMAL(m) the unit tangent-space normal of the normal map
// that bumps, STOCHTEX_MESH_OCCLUSION(m) its ambient occlusion (the last two where it has them).
std::string material_macros(const Model& model) {
  const MeshMaterial material = mesh_material(model);
  const std::span<const MapInfo> maps = model.maps();
  const std::vector<int> first = first_channels(maps);
  const std::vector<gl::MaterialMember> members = gl::material_members(maps);
  std::string macros;
  bool bump = false;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const std::string member = "m." + members[i].name;
    if (maps[i].kind == MapKind::colour && first[i] == material.colour)
      macros += "#define STOCHTEX_MESH_COLOUR(m) vec4(" + member +
                (members[i].vector ? ", 0.0)\n" : ", 0.0, 0.0, 0.0)\n");
    if (maps[i].kind == MapKind::normal && !bump) {
      bump = true;
      macros += "#define STOCHTEX_MESH_NORMAL(m) " + member + "\n";
    }
    if (maps[i].kind == MapKind::scalar && first[i] == material.occlusion)
      macros += "#define STOCHTEX_MESH_OCCLUSION(m) " + member + "\n";
  }
  return macros;
}

// The exported GLSL at the mesh's uvs: stochtex_<method>, or a material's function.
Texturing uv_texturing(const Model& model, const std::string& fragment) {
  if (model.maps().empty()) {
    ShaderExport files = export_shader(model);
    return {"#define STOCHTEX_MESH_UV stochtex_" + std::string(model.method()) + "\n" +
                files.shader.text + fragment,
            std::move(files.textures),
            {}};
  }
  ShaderExport files;
  try {
    files = export_shader(model);
  } catch (const Error& error) {
    throw Error(ErrorCode::invalid_input,
                "the gl backend of render-mesh shades a material through its exported material "
                "function, which export-shader does not write for this one (" +
                    std::string(error.what()) + "); render it with --backend cpu");
  }
  return {"#define STOCHTEX_MESH_UV stochtex_" + std::string(model.method()) + "_material\n" +
              material_macros(model) + files.shader.text + fragment,
          std::move(files.textures),
          {}};
}

Texturing texturing(const Model& model, const MeshRenderOptions& options) {
  if (options.periodic)
    throw Error(ErrorCode::invalid_input,
                "the gl backend of render-mesh has no periodic texture (its GLSL keys the cells "
                "as the default evaluators do, docs/render.md); render it with --backend cpu");
  const std::string fragment = gl::shader_source("gl/mesh_fragment.glsl");
  if (!options.mapping) return uv_texturing(model, fragment);
  if (!model.maps().empty())
    throw Error(ErrorCode::invalid_input,
                "the gl backend of render-mesh shades a material through its exported material "
                "function, at the mesh's uvs only, and this render asks for the " +
                    std::string(mapping_name(*options.mapping)) +
                    " mapping; render it with --mapping uv or --backend cpu");
  SurfaceOptions surface = options.surface;
  surface.mapping = *options.mapping;
  std::optional<gl::SurfaceShader> shader = gl::model_surface_shader(model, surface);
  if (!shader)
    throw Error(ErrorCode::invalid_input,
                "the gl backend has no GLSL " + std::string(mapping_name(*options.mapping)) +
                    " mapping for " + std::string(model.method()) + " models; use --backend cpu");
  return {"#define STOCHTEX_SURFACE_CALL " + shader->call + "\n" + shader->library + fragment,
          std::move(shader->textures), std::move(shader->data)};
}

// The mesh as one vertex buffer of (position, normal, uv) floats, one index buffer and the faces'
// storage buffer of mesh_fragment.glsl: per triangle the unit normal and the two rows of the map
// from a displacement in its plane to the uv's, each padded to a vec4, computed in double.
struct MeshBuffers {
  gl::Buffer vertices;
  gl::Buffer indices;
  gl::Buffer faces;
  GLuint vertex_array = 0;

  static std::vector<float> face_data(const Mesh& mesh) {
    std::vector<float> values;
    values.reserve(mesh.triangles.size() * 12);
    for (const auto& [a, b, c] : mesh.triangles) {
      const Vec3d e1 = mesh.positions[b] - mesh.positions[a];
      const Vec3d e2 = mesh.positions[c] - mesh.positions[a];
      Vec3d row_u, row_v;
      if (!mesh.uvs.empty()) {
        const BarycentricGradients g = barycentric_gradients(e1, e2);
        const Vec2d& t0 = mesh.uvs[a];
        const Vec2d u1 = {mesh.uvs[b].x - t0.x, mesh.uvs[b].y - t0.y};
        const Vec2d u2 = {mesh.uvs[c].x - t0.x, mesh.uvs[c].y - t0.y};
        row_u = g.du * u1.x + g.dv * u2.x;
        row_v = g.du * u1.y + g.dv * u2.y;
      }
      for (const Vec3d& v : {normalized(cross(e1, e2)), row_u, row_v})
        for (const double x : {v.x, v.y, v.z, 0.0}) values.push_back(static_cast<float>(x));
    }
    return values;
  }

  static std::vector<float> interleaved(const Mesh& mesh) {
    std::vector<float> values;
    values.reserve(mesh.positions.size() * 8);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3d& p = mesh.positions[i];
      const Vec3d& n = mesh.normals[i];
      const Vec2d uv = mesh.uvs.empty() ? Vec2d{} : mesh.uvs[i];
      for (const double v : {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y})
        values.push_back(static_cast<float>(v));
    }
    return values;
  }

  explicit MeshBuffers(const Mesh& mesh)
      : vertices(mesh.positions.size() * 8 * sizeof(float), interleaved(mesh).data()),
        indices(mesh.triangles.size() * 3 * sizeof(std::uint32_t), mesh.triangles.data()),
        faces(mesh.triangles.size() * 12 * sizeof(float), face_data(mesh).data()) {
    glCreateVertexArrays(1, &vertex_array);
    glVertexArrayVertexBuffer(vertex_array, 0, vertices.id(), 0, 8 * sizeof(float));
    glVertexArrayElementBuffer(vertex_array, indices.id());
    constexpr std::array<std::array<GLuint, 2>, 3> kAttributes = {{{3, 0}, {3, 3}, {2, 6}}};
    for (GLuint a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(vertex_array, a);
      glVertexArrayAttribFormat(vertex_array, a, static_cast<GLint>(kAttributes[a][0]), GL_FLOAT,
                                GL_FALSE, kAttributes[a][1] * sizeof(float));
      glVertexArrayAttribBinding(vertex_array, a, 0);
    }
  }
  ~MeshBuffers() { glDeleteVertexArrays(1, &vertex_array); }
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;
};

// An offscreen RGBA32F colour + 32-bit float depth framebuffer.
struct Framebuffer {
  GLuint id = 0;
  std::array<GLuint, 2> renderbuffers{};
  Framebuffer(int width, int height) {
    glCreateRenderbuffers(2, renderbuffers.data());
    glNamedRenderbufferStorage(renderbuffers[0], GL_RGBA32F, width, height);
    glNamedRenderbufferStorage(renderbuffers[1], GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &id);
    glNamedFramebufferRenderbuffer(id, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
    glNamedFramebufferRenderbuffer(id, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
    if (glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      release();
      gl::check_gl("making the framebuffer");
      throw Error(ErrorCode::numerical,
                  "the OpenGL backend failed: the driver has no RGBA32F + float depth "
                  "framebuffer; use --backend cpu");
    }
  }
  ~Framebuffer() { release(); }
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
  void release() {
    glDeleteFramebuffers(1, &id);
    glDeleteRenderbuffers(2, renderbuffers.data());
  }
};

// The clip coordinates of r = position - eye for the tile of `width` x `height` pixels at
// (x0, y0) of the picture: with a = r.step_x / |step|^2 and b = r.step_y / |step|^2 (pixels at unit
// depth) and z = r.forward, the pixel coordinate is a / z + width/2 (as the CPU's rays), the
// tile's normalised x is 2 (a / z + picture_width/2 - x0) / width - 1, so clip x = (2 a + (W - 2 x0
// - width) z) / width with w = z; likewise y, the picture's rows being the framebuffer's rows (no
// flip). Depth is reversed, near / z (1 at the near plane, towards 0 far away). Column-major.
std::array<float, 16> clip_from_eye(const PixelRays& rays, int x0, int y0, int width, int height,
                                    double near) {
  const double step2 = dot(rays.step_x, rays.step_x);
  const Vec3d ax = rays.step_x * (2.0 / (step2 * width));
  const Vec3d by = rays.step_y * (2.0 / (step2 * height));
  const Vec3d zx = rays.forward * (static_cast<double>(rays.width - 2 * x0 - width) / width);
  const Vec3d zy = rays.forward * (static_cast<double>(rays.height - 2 * y0 - height) / height);
  const Vec3d row_x = ax + zx;
  const Vec3d row_y = by + zy;
  const Vec3d& row_w = rays.forward;
  // Element (row, column) at [column * 4 + row].
  return {static_cast<float>(row_x.x),
          static_cast<float>(row_y.x),
          0.0f,
          static_cast<float>(row_w.x),
          static_cast<float>(row_x.y),
          static_cast<float>(row_y.y),
          0.0f,
          static_cast<float>(row_w.y),
          static_cast<float>(row_x.z),
          static_cast<float>(row_y.z),
          0.0f,
          static_cast<float>(row_w.z),
          0.0f,
          0.0f,
          static_cast<float>(near),
          0.0f};
}

}  // namespace

void render_mesh_gl(const Model& model, const Mesh& mesh, const Camera& camera,
                    const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out) {
  check_mesh_render_arguments(model, mesh, options, out);
  const PixelRays rays = pixel_rays(camera, out.width, out.height);
  const Texturing parts = texturing(model, options);

  const gl::Context context;
  const gl::Program program("#version 450\n" + gl::shader_source("gl/mesh_vertex.glsl"),
                            "#version 450\n" + gl::glsl_constants(kMeshConstants) + parts.fragment);
  const gl::ProgramTextures textures(program, parts.textures);
  const gl::Buffer data(std::max<std::size_t>(parts.data.size(), 1) * sizeof(float),
                        parts.data.data());
  const MeshBuffers buffers(mesh);
  const int channels = out.channels;
  const int colours = channels == 2 || channels == 4 ? channels - 1 : channels;
  const auto set_vector = [&](const char* name, const Vec3d& v) {
    glProgramUniform3f(program.id(), program.location(name), static_cast<float>(v.x),
                       static_cast<float>(v.y), static_cast<float>(v.z));
  };
  set_vector("mesh_eye", rays.eye);
  set_vector("mesh_forward", rays.forward);
  set_vector("mesh_step_x", rays.step_x);
  set_vector("mesh_step_y", rays.step_y);
  set_vector("mesh_light", light_direction(rays));
  program.set("mesh_texture_scale", static_cast<float>(options.texture_scale));
  program.set("mesh_colours", colours);
  program.set("seed", static_cast<unsigned>(seed));
  program.set("parameter", static_cast<float>(options.mapping == SurfaceMapping::surface
                                                  ? options.surface.surface_mni
                                                  : options.surface.triplanar_sharpness));
  double farthest = 0.0;
  for (const Vec3d& p : mesh.positions)
    farthest = std::max(farthest, dot(p - rays.eye, rays.forward));
  const double near = std::max(farthest, 1e-300) * kNearFraction;

  const int tile_width = std::min(out.width, kTile);
  const int tile_height = std::min(out.height, kTile);
  const Framebuffer framebuffer(tile_width, tile_height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_CULL_FACE);
  glUseProgram(program.id());
  glBindVertexArray(buffers.vertex_array);
  textures.bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, buffers.faces.id());
  std::array<float, 4> background{};
  for (int c = 0; c < colours; ++c)
    background[static_cast<std::size_t>(c)] = mesh_background(model, options);
  const float far_depth = 0.0f;
  std::vector<float> values(static_cast<std::size_t>(tile_width) * tile_height * 4);
  for (int y0 = 0; y0 < out.height; y0 += kTile)
    for (int x0 = 0; x0 < out.width; x0 += kTile) {
      const int w = std::min(kTile, out.width - x0);
      const int h = std::min(kTile, out.height - y0);
      glViewport(0, 0, w, h);
      glClearNamedFramebufferfv(framebuffer.id, GL_COLOR, 0, background.data());
      glClearNamedFramebufferfv(framebuffer.id, GL_DEPTH, 0, &far_depth);
      glUniformMatrix4fv(program.location("clip_from_eye"), 1, GL_FALSE,
                         clip_from_eye(rays, x0, y0, w, h, near).data());
      glUniform2f(program.location("mesh_pixel_offset"), static_cast<float>(x0 - 0.5 * out.width),
                  static_cast<float>(y0 - 0.5 * out.height));
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.triangles.size() * 3), GL_UNSIGNED_INT,
                     nullptr);
      glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, values.data());
      gl::check_gl("drawing the mesh");
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < channels; ++c)
            out.at(x0 + x, y0 + y, c) =
                values[(static_cast<std::size_t>(y) * w + x) * 4 + static_cast<std::size_t>(c)];
    }
  glUseProgram(0);
}

}  // namespace stochtex
