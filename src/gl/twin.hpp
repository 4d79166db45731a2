#pragma once
// What a method's GPU twin gives the generic renderer (render_gl.cpp) and exporter
// (export_shader.cpp): each method specialises gl::Twin for its model type in
// src/methods/<m>/gl_twin.hpp,
//
//   template <> struct Twin<m::MModel> {
//     static constexpr std::array<GlslConstant, N> kConstants;  // C++ constants its GLSL shares
//     static std::unique_ptr<Pass> pass(const m::MModel&);       // gl_pass.cpp: GL state
//     static ExportParts shader(const m::MModel&);               // gl_data.cpp: export-shader
//   };
//
// The renderer and the exporter visit stochtex::MethodModel (model/model_data.hpp) with it, so a
// method of the variant without a twin is a compile error (HasTwin below), not a runtime surprise.

#include <concepts>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "gl/glsl_text.hpp"
#include "gl/program.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/render.hpp"

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
  // The data, each bound to `uniform sampler2D stochtex_<name>` (written as <name>.exr).
  std::vector<NamedImage> images;
  std::string notes;  // the README's method notes
};

// Declared only: the specialisations in the method folders are the twins.
template <typename MethodModel>
struct Twin;

template <typename MethodModel>
concept HasTwin = requires(const MethodModel& model) {
  {std::span<const GlslConstant>(Twin<MethodModel>::kConstants)};
  { Twin<MethodModel>::pass(model) } -> std::same_as<std::unique_ptr<Pass>>;
  { Twin<MethodModel>::shader(model) } -> std::same_as<ExportParts>;
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

// --gl-filter hardware (texton, tiling): the footprint side given to textureGrad, the grid's scale
// over sqrt(3), so that the hardware's level of detail log2(scale / sqrt(3)) is the CPU pyramids'
// (kLodBias, core/level_of_detail.hpp), or zero for point samples.
float hardware_footprint(const Grid& grid, bool filter);

// An RGBA32F texture with a full mip chain for hardware filtering: `levels[l]` (RGBA texels of
// max(1, width >> l) x max(1, height >> l)) where the caller has the level, glGenerateTextureMipmap
// for the rest. Trilinear, anisotropic where available, `wrap` on both axes.
GLuint mipmapped_texture(int width, int height, const std::vector<std::vector<float>>& levels,
                         GLenum wrap);

// `values` with `channels` floats per texel as RGBA (missing channels zero).
std::vector<float> to_rgba(const float* values, std::size_t texels, int channels);

// An RGBA32F texture of `image` (4 channels), read with texelFetch.
GLuint data_texture(const ImageF& image);

}  // namespace stochtex::gl
