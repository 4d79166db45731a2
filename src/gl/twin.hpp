#pragma once
// What a method's GPU twin gives the generic renderer (render_gl.cpp) and exporter
// (export_shader.cpp): each method specialises gl::Twin for its model type in
// src/methods/<m>/gl_twin.hpp,
//
//   template <> struct Twin<m::MModel> {
//     static constexpr std::array<GlslConstant, N> kConstants;  // C++ constants its GLSL shares
//     static std::unique_ptr<Pass> pass(const m::MModel&);       // gl_pass.cpp: GL state
//     static ExportParts shader(const m::MModel&, ShaderVariant);  // gl_data.cpp: export-shader
//   };
//
// `fast` is the GLSL and data that the pass runs for --gl-filter hardware (one source); a method
// whose hardware path is its exact one exports `exact` for both.
// The renderer and the exporter visit stochtex::MethodModel (model/model_data.hpp) with it, so a
// method of the variant without a twin is a compile error (HasTwin below), not a runtime surprise.

#include <concepts>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "gl/glsl_text.hpp"
#include "gl/program.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/render.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::gl {

// One method's GPU state, made once per model: prepare() sets a render's uniforms (and picks the
// program for options.texture_filter), dispatch() evaluates one tile of it into `result`. (A
// virtual call per dispatch, never per sample.)
class Pass {
 public:
  virtual ~Pass() = default;
  virtual void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) = 0;
  virtual void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                        const Buffer& result) const = 0;
};

// What a method's export differs in; export_shader() (export_shader.cpp) writes the rest (the
// file names, header comments, the language and the README) the same for every method.
struct ExportParts {
  std::string_view method;  // the model's kMethodName: the entry point is stochtex_<method>
  std::string title;        // the README's, e.g. "texton noise"
  std::string what;         // the GLSL file's first line, e.g. "Texton noise (3 channels, ...)"
  std::string library;      // the method's GLSL library: all but `#version`
  // The data, each bound to `uniform sampler<2D|3D> stochtex_<name>`.
  std::vector<ShaderTexture> textures;
  std::string notes;                             // the README's method notes
  ShaderVariant variant = ShaderVariant::exact;  // fast: the README lists each file's settings
  // A material beyond 4 channels (export_material.cpp): the function of `library` giving every
  // channel, `float[N] <name>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)` with the arguments of
  // stochtex_<method>, whose vec4 cannot hold them (the library has no stochtex_<method> then).
  // Empty for 1 to 4 channels.
  std::string channels_function = {};
  // A material's channels that its function returns as linear light, decoded after evaluation
  // (gl/colour.cpp add_colour: the srgb maps' channels); empty for a model of one image.
  std::vector<int> decoded_channels = {};
};

// Declared only: the specialisations in the method folders are the twins.
template <typename MethodModel>
struct Twin;

template <typename MethodModel>
concept HasTwin = requires(const MethodModel& model) {
  {std::span<const GlslConstant>(Twin<MethodModel>::kConstants)};
  { Twin<MethodModel>::pass(model) } -> std::same_as<std::unique_ptr<Pass>>;
  { Twin<MethodModel>::shader(model, ShaderVariant::exact) } -> std::same_as<ExportParts>;
};

// A method's GLSL surface function for one mapping (stochtex/surface.hpp), for the GL surface
// evaluator (surface_gl.cpp, surface.glsl) and engines that call it on meshes. A twin opts in
// with
//   static std::optional<SurfaceShader> surface_shader(const m::MModel&, const SurfaceOptions&);
// (std::nullopt: no GLSL for options.mapping), found by HasSurfaceTwin. The library may depend on
// the options (texton surface noise writes the constants of options.surface_mni), so callers
// ask again when the options change.
struct SurfaceShader {
  // GLSL, all but `#version`: the method's library reading its data from the storage buffer at
  // binding 0 (`data`) or from `textures` (ProgramTextures), its constants and its surface
  // function.
  std::string library;
  std::vector<float> data;
  // A GLSL expression of the vec4 value at one point, from the vec3 `position`, `normal`,
  // `tangent`, `dpdx`, `dpdy` (model space), the uint `seed` and the float `parameter`
  // (SurfaceOptions::triplanar_sharpness for the triplanar mappings, surface_mni for surface).
  std::string call;
  // Gabor reads its data with texelFetch: on Mesa 22.3's llvmpipe a loop whose exit depends on a
  // value read from a storage buffer, nested in another loop, ends the outer loop after one
  // iteration in fragment shaders (and in compute shaders whose SIMD vectors start partly empty),
  // which dropped nearly all of Gabor noise's impulses in the mesh renderer (docs/meshes.md).
  std::vector<ShaderTexture> textures;
};

// Linear triplanar mapping (SurfaceMapping::triplanar_linear, src/gl/triplanar_linear.glsl) for a
// method whose planar library `library` reads its data from the storage buffer at binding 0 only
// (or, with `data` empty, from textures the caller adds): its entry point stochtex_<method> called
// on the three axis planes.
SurfaceShader triplanar_linear_shader(std::string_view method, std::string library,
                                      std::vector<float> data);

template <typename MethodModel>
concept HasSurfaceTwin = requires(const MethodModel& model) {
  {
    Twin<MethodModel>::surface_shader(model, SurfaceOptions{})
    } -> std::same_as<std::optional<SurfaceShader>>;
};

// Whether every alternative of a std::variant of method models has a twin.
template <typename Variant>
inline constexpr bool kEveryMethodHasTwin = false;
template <typename... MethodModels>
inline constexpr bool kEveryMethodHasTwin<std::variant<MethodModels...>> = (HasTwin<MethodModels> &&
                                                                            ...);

// The low 32 bits of an integral cell index formed in double (a 64-bit cell in C++), as cell_key
// takes them: the GLSL works relative to this cell, so far origins are as precise as near ones.
inline GLuint low_bits(double cell) {
  return static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(cell)));
}

// Runs `program` over width x height pixels of the grid, writing into `result` (binding 1): the
// render.glsl of every method declares first_pixel, dispatch_size and the result buffer.
void run_tile(const Program& program, std::int64_t first_x, std::int64_t first_y, int width,
              int height, const Buffer& result);

// --gl-filter hardware (texton, tiling): the footprint side the fast GLSL takes as the screen
// derivatives' length, the grid's scale, or zero for point samples.
float hardware_footprint(const Grid& grid, bool filter);

// `image` rounded to what a PNG of `bits` (8 or 16) bits per channel holds and reads back (values
// clamped to [0, 1], sample / (2^bits - 1)), as write_image and read_image do.
ImageF quantized(ImageF image, int bits);

// The GL texture of an exported data image, made as its ShaderTexture says (format, 2-D or 3-D,
// generated mip-maps, filter, wrap): the fast renderer binds what the export ships.
GLuint texture_of(const ShaderTexture& texture);

// The textures of exported data images for one program: made by texture_of, texture i on unit i
// and the program's sampler `stochtex_<name>` set to it; bind() binds them before drawing.
class ProgramTextures {
 public:
  ProgramTextures(const Program& program, std::span<const ShaderTexture> textures);
  ~ProgramTextures();
  ProgramTextures(const ProgramTextures&) = delete;
  ProgramTextures& operator=(const ProgramTextures&) = delete;
  void bind() const;

 private:
  std::vector<GLuint> ids_;
};

// The --gl-filter hardware program of a method with a fast variant (texton, tiling): the fast
// export's GLSL library (what `export-shader --variant fast` ships, less its header comment)
// followed by the method's render.glsl, and the export's textures on units 0, 1, ... in their
// order, so the renderer runs and measures exactly what the export ships.
class ExportedProgram {
 public:
  ExportedProgram(const ExportParts& parts, const std::string& render_source);
  const Program& program() const { return program_; }
  void bind_textures() const { textures_.bind(); }

 private:
  Program program_;
  ProgramTextures textures_;
};

// An RGBA32F texture of `image` (4 channels), read with texelFetch.
GLuint data_texture(const ImageF& image);

}  // namespace stochtex::gl
