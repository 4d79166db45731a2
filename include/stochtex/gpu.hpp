#pragma once
// GPU rendering through OpenGL 4.5 compute shaders (library stochtex::gl): the same grid, model
// and seed as render() in render.hpp, evaluated by the GLSL twin of each method's evaluator.
// Runs headless through EGL: on NVIDIA drivers where a GPU exists, on Mesa llvmpipe where not.
// The CPU evaluator is the reference; the GPU output matches it within float rounding (tested),
// or in distribution with GlFilter::hardware.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/image.hpp"
#include "stochtex/mesh_render.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"
#include "stochtex/surface.hpp"

namespace stochtex {

// How the GL backend filters footprints wider than a pixel (`render --gl-filter`).
//   exact:    the GLSL twin of the CPU filter (texelFetch, the shader's own interpolation and
//             pyramid levels): the CPU's output to float rounding. The default.
//   hardware: texton (order 1) and tiling read their pyramids as mip-mapped GL textures with
//             textureGrad (trilinear, anisotropic up to 16x where the driver has it), as the
//             papers' shaders do, running the GLSL and data of ShaderVariant::fast: faster on GPUs,
//             equal to the CPU in distribution (mean, variance; tested), not pixel for pixel.
//             gabor runs its float-only GLSL (no doubles: positions split per grid into a 64-bit
//             cell and a float offset), within about 1e-3 of the image's standard deviation of
//             `exact` (tested). lrp and other texton orders filter analytically and render as
//             `exact`.
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

// Surface points (stochtex/surface.hpp) on the GPU: evaluate_surface() through the method's GLSL
// surface function (today the triplanar mapping of tiling, stochtex_tiling_triplanar, texton and
// Gabor surface noise, stochtex_texton_surface and stochtex_gabor_surface, and linear triplanar
// mapping for texton, tiling and gabor, stochtex_triplanar_linear), the CPU's output to float
// rounding (tested). Positions are floats on the GPU: keep them below ~1e4 exemplar pixels for
// full precision. lrp (several data buffers) and texton mixing have no GLSL surface function.
bool gl_supports_mapping(const Model& model, SurfaceMapping mapping);

// A model made ready for surface evaluation on the GPU (an OpenGL context and the model's data;
// each mapping's program compiled on first use, and again when the options it depends on change).
// Use it from one thread.
class GlSurfaceEvaluator {
 public:
  // Throws stochtex::Error when no OpenGL 4.5 context can be made.
  explicit GlSurfaceEvaluator(const Model& model);
  ~GlSurfaceEvaluator();
  GlSurfaceEvaluator(const GlSurfaceEvaluator&) = delete;
  GlSurfaceEvaluator& operator=(const GlSurfaceEvaluator&) = delete;

  // Checks its arguments as evaluate_surface() does (std::invalid_argument), then throws
  // stochtex::Error when the mapping has no GLSL for this method (gl_supports_mapping).
  void evaluate(std::span<const SurfacePoint> points, const SurfaceOptions& options,
                std::uint32_t seed, ImageView<float> out);

 private:
  struct Compiled;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One evaluation with an evaluator made for it.
void evaluate_surface_gl(const Model& model, std::span<const SurfacePoint> points,
                         const SurfaceOptions& options, std::uint32_t seed, ImageView<float> out);

// render_mesh() (mesh_render.hpp) on the GPU, the way an engine uses the exported shaders: the
// mesh rasterised with the same camera (pixel for pixel), each fragment calling the method's
// GLSL: the uv mapping the exported stochtex_<method>(p, dpdx, dpdy, seed) (every method), the
// surface mappings the method's GLSL surface function where gl_supports_mapping says so (tiling's
// triplanar today); the CPU's footprints (ray differentials on each triangle's plane, in float);
// the same shading. A material (uv only): the exported stochtex_<method>_material, its colour map
// lit through its normal map and ambient occlusion as render_mesh() does. Positions are floats:
// the CPU's image to float rounding inside the silhouettes but at pixels on a triangle edge
// (docs/meshes.md gives the measured differences). options.threads and options.progress are not
// used. Throws std::invalid_argument as render_mesh() does, and stochtex::Error when no OpenGL 4.5
// context can be made, the mapping has no GLSL for the model's method, the model is a material
// on another mapping than uv or without an exported material function (tiling), or
// options.periodic is set (the GLSL has no periodic evaluation).
void render_mesh_gl(const Model& model, const Mesh& mesh, const Camera& camera,
                    const MeshRenderOptions& options, std::uint32_t seed, ImageView<float> out);

// Which GLSL `stochtex export-shader` writes (`--variant`):
//   exact: the `--gl-filter exact` evaluator: float32 data read with texelFetch, the shader's own
//          interpolation and pyramid levels; the CPU's output to float rounding. The default.
//   fast:  the GLSL that `render --backend gl --gl-filter hardware` runs, with its data as the
//          images engines import (PNG where 8 or 16 bits lose nothing measurable) read through
//          hardware-filtered, mip-mapped samplers; equal to the CPU in distribution (texton,
//          tiling). gabor's fast variant is its float-only GLSL (no doubles), within about 1e-3
//          of the image's standard deviation of exact; lrp's hardware path is its exact one, so
//          its fast variant is exact.
enum class ShaderVariant { exact, fast };

// The language of an exported shader (`export-shader --language`; `stochtex languages` lists each
// with its title and targets, from the table of src/gl/languages.hpp). glsl (GLSL 4.50) is the
// method's own source and the default; the others are cross-compiled from it through SPIR-V
// (glslang, SPIRV-Cross), the same for both variants; godot (Godot 3's shading language) is
// written from the GLSL ES that SPIRV-Cross makes of the library with every function inlined
// (src/gl/godot_shader.hpp).
enum class ShaderLanguage { glsl, essl, hlsl, msl, godot };

struct ShaderExportOptions {
  ShaderVariant variant = ShaderVariant::exact;
  ShaderLanguage language = ShaderLanguage::glsl;
};

// How an exported data image is stored: its file and the GL texture format it loads into.
//   exr_float32: <name>.exr, float32 (GL_R32F .. GL_RGBA32F);
//   png8:        <name>.png, 8 bits per channel, value = byte / 255 (GL_R8 .. GL_RGBA8);
//   png16:       <name>.png, 16 bits per channel, value = sample / 65535 (GL_R16 .. GL_RGBA16).
// Every data image is linear data: load it without sRGB decoding (UNORM, not SRGB8).
enum class TextureEncoding { exr_float32, png8, png16 };
// The sampler's filter: nearest (texelFetch reads), linear (bilinear / trilinear for 3-D, no
// mip-maps) or mipmap (trilinear between mip levels, anisotropic up to 16x where available).
enum class TextureFilter { nearest, linear, mipmap };
// The sampler's wrap on every axis; clamp_to_border uses transparent black (0, 0, 0, 0).
enum class TextureWrap { clamp_to_edge, clamp_to_border, repeat };
// The values' names in the exports' manifest.json files (export-shader's, export-web's): the
// enumerators' ("exr_float32", "mipmap", "clamp_to_border", ...).
std::string_view encoding_name(TextureEncoding encoding);
std::string_view filter_name(TextureFilter filter);
std::string_view wrap_name(TextureWrap wrap);

// One exported data image and the texture it becomes.
struct ShaderTexture {
  std::string name;  // the file <name>.exr or <name>.png, bound to the texture `stochtex_<name>`
  ImageF image;      // the values the file holds (PNG: already quantised to its bit depth)
  TextureEncoding encoding = TextureEncoding::exr_float32;
  // 1: a 2-D texture. More: a 3-D texture of image.width x (image.height / depth) x depth, its
  // slices stacked top to bottom in the image (slice z in rows z * height / depth onwards), so the
  // image's texels in row order are the 3-D texture's in x, y, z order.
  int depth = 1;
  TextureFilter filter = TextureFilter::nearest;
  TextureWrap wrap = TextureWrap::clamp_to_edge;
  // 1: no mip-maps. More: the engine generates the mip chain from the image (2 x 2 box filter,
  // glGenerateMipmap) and samples levels 0 .. mip_levels - 1 (GL_TEXTURE_MAX_LEVEL).
  int mip_levels = 1;
  // Godot 3 (`--language godot`), whose importer makes no float32 texture: a float image read
  // texel by texel stored as its floats' bytes in a grey + alpha image (encoding png8, 2 channels,
  // 8 times as wide): float c of texel (x, y) in the texels 8x + 2c (bytes 0, 1, lowest first)
  // and 8x + 2c + 1 (bytes 2, 3) of row y, which the shader reads back bit for bit.
  bool float_bytes = false;
  std::string file_name() const;
};

// A text file of an export: its name in the export folder and its contents.
struct TextFile {
  std::string name;
  std::string text;
};

// `stochtex export-shader`: a self-contained shader library exposing, in every language,
//   vec4 stochtex_<method>(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)
// (float2/float4 in HLSL and MSL; p in exemplar pixels, dpdx/dpdy its screen derivatives, zero =
// no filtering), the model's data as images to bind as textures, and a README showing how. The
// result is the CPU render's: linear light for a model whose colour is srgb (each channel the
// expectation of the decoded colour over the footprint, docs/design.md §14), the model's values
// as they are for one of data (for an ordinary sRGB exemplar analysed as data, sRGB-encoded).
// A material whose maps are decoded after evaluation is refused for now. Needs no GL context.
struct ShaderExport {
  TextFile shader;  // stochtex_<method> with the language's extension (.glsl, .metal, ...)
  // Engine-shaped wrappers of `shader` (HLSL: a Unity Shader Graph custom function file; Godot:
  // its canvas_item shader, scene, Godot 4 shader and each data file's .import settings).
  std::vector<TextFile> wrappers;
  std::vector<ShaderTexture> textures;  // each bound to the texture `stochtex_<name>`
  std::string readme;
  // manifest.json, for importers (docs/shaders.md, "The manifest"): the files, the entry point,
  // what each of its outputs holds (linear light or data), and each texture's settings.
  std::string manifest;
};
// A material (a model with maps) exports a struct of its maps and
// StochtexMaterial stochtex_<method>_material(vec2 p, vec2 dpdx, vec2 dpdy, uint seed), derived
// normal maps from the height around p (docs/shaders.md, "Materials"). Throws
// std::invalid_argument, one sentence, when the model's shader uses what the language lacks (the
// gabor exact shader's double precision in GLSL ES, HLSL, Metal and Godot; a material's struct,
// or data wider than 2048 texels, in Godot), and Error(invalid_input),
// one sentence, for what cannot be exported (a model of more than 4 channels without maps,
// tiling's material groups, texton's fast variant and lrp's section 5 beyond 4 channels).
ShaderExport export_shader(const Model& model, const ShaderExportOptions& options = {});

// "OpenGL <version> on <renderer>" of the context render_gl uses (creates one).
std::string gl_device_description();

}  // namespace stochtex
