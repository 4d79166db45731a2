#pragma once
// The GPU twin of texton noise (gl::Twin, src/gl/twin.hpp): the model as GLSL data, its constants
// as GLSL source and its texel pyramid as one RGBA atlas image (gl_data.cpp), used by the GL
// renderer (gl_pass.cpp: render.glsl, hardware.glsl) and by `stochtex export-shader`, so both run
// evaluate.glsl on the same data.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/level_of_detail.hpp"
#include "gl/twin.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/model.hpp"
#include "stochtex/image.hpp"

namespace stochtex::gl {

struct TextonGlsl {
  std::string constants;  // GLSL const declarations (exact: every float reads back unchanged)
  ImageF atlas;           // 4 channels; level l's padded texels start at row TEXTON_LEVEL_ROW[l]
};

// The shot noise's constants (channels, order, cell size, cell counts and signs, intensity, the
// pyramid levels) and texel atlas: what impulses.glsl needs, shared with texton noise mixing
// (texton_mix/gl_data.cpp, one texton model per step). A model of more than 4 channels renders
// in chunks of 4 (gl_pass.cpp): `first_channel` picks the chunk (TEXTON_CHANNELS = its width, the
// atlas its channels); every chunk has the same impulses.
TextonGlsl texton_shot_noise_glsl(const texton::TextonModel& model, int first_channel = 0);
// The shot noise's and texton noise's own constants (TEXTON_CONSTANT_TERM, TEXTON_MEAN).
TextonGlsl texton_glsl(const texton::TextonModel& model, int first_channel = 0);
// Throws a sentence naming `what` (a GPU path that takes 1 to 4 channels) for a wider model.
void refuse_beyond_four_channels(const texton::TextonModel& model, const std::string& what);

// texton_atlas_texel(), the read of the atlas that exact_fetch.glsl makes: from the sampler
// `stochtex_texton_atlas` (textures) or from the storage buffer at binding 0 holding its texels.
std::string texton_atlas_source(const ImageF& atlas, DataSource source);

// The exact variant: random.glsl, kConstants, the model's constants, the atlas read and texton
// evaluate.glsl, exact_fetch.glsl, impulses.glsl, noise.glsl and entry.glsl: all but `#version`.
std::string texton_library_source(const TextonGlsl& glsl, DataSource source = DataSource::textures);

// Whether the model has a fast variant: hardware bilinear reconstruction is the order-1 B-spline
// only, so other orders export (and render with --gl-filter hardware) as exact.
bool has_fast_variant(const texton::TextonModel& model);

// The uniforms of texton render.glsl for a grid, shared by texton noise mixing's pass: the grid
// origin as a cell (its low 32 bits) and a float offset from that cell's corner, the scale, the
// seed and the filter that filter_setup chooses for the grid's footprint (in double, as the CPU
// evaluator chooses it). `shape` gives the cell size and pyramid. Returns the origin cell.
std::array<double, 2> set_render_uniforms(const Program& program, const texton::TextonModel& shape,
                                          const Grid& grid, std::uint32_t seed, bool filter);

template <>
struct Twin<texton::TextonModel> {
  static constexpr std::array<GlslConstant, 5> kConstants = {{
      {"TEXTON_PADDING", texton::kPadding},
      {"TEXTON_MAX_PROBES", texton::kMaxProbes},
      {"TEXTON_LOD_BIAS", static_cast<float>(kLodBias)},
      {"TEXTON_LATTICE_STEP_U", texton::kLatticeStepU},
      {"TEXTON_LATTICE_STEP_V", texton::kLatticeStepV},
  }};
  static std::unique_ptr<Pass> pass(const texton::TextonModel& model);
  // fast: the library and texture of --gl-filter hardware (TextonPass compiles and binds them).
  static ExportParts shader(const texton::TextonModel& model, ShaderVariant variant);
  // surface: the exact library (the atlas in the storage buffer), surface_process.glsl and
  // stochtex_texton_surface (surface.glsl), with the constants of options.surface_mni;
  // triplanar_linear: the exact library through triplanar_linear_shader (twin.hpp).
  static std::optional<SurfaceShader> surface_shader(const texton::TextonModel& model,
                                                     const SurfaceOptions& options);
};

}  // namespace stochtex::gl
