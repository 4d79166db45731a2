#pragma once
// GPU rendering through OpenGL 4.5 compute shaders (library stochtex::gl): the same grid, model
// and seed as render() in render.hpp, evaluated by the GLSL twin of each method's evaluator.
// Runs headless through EGL: on NVIDIA drivers where a GPU exists, on Mesa llvmpipe where not.
// The CPU evaluator is the reference; the GPU output matches it within float rounding (tested),
// or in distribution with GlFilter::hardware.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"

namespace stochtex {

// How the GL backend filters footprints wider than a pixel (`render --gl-filter`).
//   exact:    the GLSL twin of the CPU filter (texelFetch, the shader's own interpolation and
//             pyramid levels): the CPU's output to float rounding. The default.
//   hardware: texton (order 1) and tiling read their pyramids as mip-mapped GL textures with
//             textureGrad (trilinear, anisotropic up to 16x where the driver has it), as the
//             papers' shaders do: faster on GPUs, equal to the CPU in distribution (mean,
//             variance; tested), not pixel for pixel. gabor runs its float-only GLSL (no
//             doubles: positions split per grid into a 64-bit cell and a float offset), within
//             about 1e-3 of the image's standard deviation of `exact` (tested). lrp and other
//             texton orders filter analytically and render as `exact`.
enum class GlFilter { exact, hardware };

struct GpuRenderOptions {
  int tile_size = 4096;  // pixels per side of one dispatch; affects speed only, never the output
  bool filter = true;    // pass each pixel's footprint (scale) to the evaluator
  GlFilter texture_filter = GlFilter::exact;
};

// Methods the GL backend evaluates (texton, tiling, lrp and gabor).
bool gl_supports(std::string_view method);

// A model made ready on the GPU: an OpenGL context, the compiled evaluator and the model's data,
// kept for repeated renders (interactive use, benchmarks). Use it from one thread.
class GlRenderer {
 public:
  // Throws stochtex::Error when no OpenGL 4.5 context can be made or the method has no GLSL
  // evaluator yet, with a sentence saying so.
  explicit GlRenderer(const Model& model);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  void render(const Grid& grid, std::uint32_t seed, ImageView<float> out,
              const GpuRenderOptions& options = {});
  // GPU time of the last render's dispatches (GL timer queries), without the read-back.
  double last_gpu_milliseconds() const;
  // "OpenGL <version> on <renderer>".
  std::string device() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One render with a renderer made for it.
void render_gl(const Model& model, const Grid& grid, std::uint32_t seed, ImageView<float> out,
               const GpuRenderOptions& options = {});

// The language of an exported shader (`export-shader --language`):
//   glsl: GLSL 4.50 (OpenGL 4.5), the method's own source. The default.
//   essl: GLSL ES 3.00 (WebGL2, OpenGL ES 3.0);
//   hlsl: HLSL Shader Model 5 (Direct3D 11, Unity, Unreal);
//   msl:  Metal Shading Language 1.2.
// essl, hlsl and msl are cross-compiled from the GLSL through SPIR-V (glslang, SPIRV-Cross).
enum class ShaderLanguage { glsl, essl, hlsl, msl };

struct ShaderExportOptions {
  ShaderLanguage language = ShaderLanguage::glsl;
};

// A text file of an export: its name in the export folder and its contents.
struct TextFile {
  std::string name;
  std::string text;
};

// `stochtex export-shader`: a self-contained shader library exposing, in every language,
//   vec4 stochtex_<method>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)
// (float2/float4 in HLSL and MSL; p in exemplar pixels, dpdx/dpdy its screen derivatives, zero =
// no filtering), the model's data as images to bind as textures, and a README showing how. Needs
// no GL context.
struct ShaderExport {
  TextFile shader;  // stochtex_<method>.glsl, .essl, .hlsl or .metal
  // Engine-shaped wrappers of `shader` (HLSL: a Unity Shader Graph custom function file).
  std::vector<TextFile> wrappers;
  // Write each as <name>.exr (float32, exact); it binds to the texture `stochtex_<name>`.
  std::vector<NamedImage> images;
  std::string readme;
};
// Throws std::invalid_argument, one sentence, when the model's shader uses what the language
// lacks (the gabor shader's double precision in GLSL ES, HLSL and Metal).
ShaderExport export_shader(const Model& model, const ShaderExportOptions& options = {});

// "OpenGL <version> on <renderer>" of the context render_gl uses (creates one).
std::string gl_device_description();

}  // namespace stochtex
