#pragma once
// The GPU twin of histogram-preserving tiling (gl::Twin, src/gl/twin.hpp): the model as GLSL
// data, its constants as GLSL source and its arrays (each pyramid level's texels, 3-D table and
// 1-D tables) as one float array (gl_data.cpp), for the GL renderer (gl_pass.cpp: a storage
// buffer; render.glsl, hardware.glsl) and `stochtex export-shader` (a texture).

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/level_of_detail.hpp"
#include "gl/twin.hpp"
#include "methods/tiling/evaluate.hpp"
#include "methods/tiling/model.hpp"

namespace stochtex::gl {

struct TilingGlsl {
  std::string constants;    // GLSL const declarations, TILING_* (exact float literals)
  std::vector<float> data;  // read by tiling_data_at() of tiling evaluate.glsl
};

// exact: `data` holds each level's texels, 3-D table and 1-D tables (the TILING_LEVEL_* offsets);
// fast: the 1-D tables only (TILING_LEVEL_TABLES), the rest being textures (hardware.glsl).
// Throws a sentence for a model that renders_in_groups.
TilingGlsl tiling_glsl(const tiling::TilingModel& model,
                       ShaderVariant variant = ShaderVariant::exact);

// Bits per channel of the fast variant's PNGs, from measured quality (docs/methods/tiling.md).
inline constexpr int kExemplarBits = 16;
inline constexpr int kLutBits = 16;

// The exact variant: random.glsl, kConstants, the model's constants, tiling_data_at() and tiling
// evaluate.glsl, exact_fetch.glsl, blend.glsl, entry.glsl and triplanar.glsl: all but `#version`.
// The data is the storage buffer at binding 0, or the texture `stochtex_tiling_data` of
// pack_rgba(data).
std::string tiling_library_source(const TilingGlsl& glsl,
                                  DataSource source = DataSource::storage_buffers);

// A model whose channels go through T^-1 in groups of their own (a material's maps, issue 18) or
// that has more than 4 channels: the renderer takes it in two passes (gl_pass.cpp), its Gaussian
// in chunks of up to 4 channels (render.glsl), then each group's T^-1 (groups.glsl); exported
// shaders and meshes (a vec4 and an image's colour and alpha) refuse it.
bool renders_in_groups(const tiling::TilingModel& model);
// A model whose blend needs every channel of each patch (the height-aware blend, a normal map's
// slopes turned with their patches): its chunks write the three patches apart (render.glsl,
// TILING_PATCH_OUTPUT) and groups.glsl turns, weighs and blends them, patch_stride floats a pixel
// (3 patches of the channels, then 3 weights, 3 levels of detail and 3 transforms of 3).
bool blends_patches_apart(const tiling::TilingModel& model);
int patch_stride(const tiling::TilingModel& model);
// The groups' T^-1 for groups.glsl: their constants (TILING_GROUP_*, the bases and means) and each
// pyramid level's 1-D tables as `data` (the TILING_LEVEL_TABLES offsets). Throws a sentence for a
// group of a kind groups.glsl has no case for (the 3-D table).
TilingGlsl tiling_groups_glsl(const tiling::TilingModel& model);
// An exported material's data and constants (material.glsl): each pyramid level's texels of every
// channel (TILING_LEVEL_TEXELS, _WIDTH, _HEIGHT), the lattice's constants and the groups'.
TilingGlsl tiling_material_glsl(const tiling::TilingModel& model);
// The compute shader of the groups' T^-1: `#version`, kConstants, the constants, the storage
// buffer reader, tiling evaluate.glsl and groups.glsl.
std::string tiling_groups_source(const TilingGlsl& glsl);

template <>
struct Twin<tiling::TilingModel> {
  static constexpr std::array<GlslConstant, 5> kConstants = {{
      {"TILING_GAUSSIAN_MEAN", tiling::kGaussianMean},
      {"TILING_ERF_SCALE", tiling::kErfScale},
      {"TILING_INVERSE_SQRT3", static_cast<float>(tiling::kInverseSqrt3)},
      {"TILING_LOD_BIAS", static_cast<float>(kLodBias)},
      {"TILING_STREAM_TRANSFORMS", static_cast<std::uint32_t>(Stream::transforms)},
  }};
  static std::unique_ptr<Pass> pass(const tiling::TilingModel& model);
  // fast: the library and textures of --gl-filter hardware (TilingPass compiles and binds them).
  static ExportParts shader(const tiling::TilingModel& model, ShaderVariant variant);
  // triplanar: the exact library and stochtex_tiling_triplanar (triplanar.glsl); triplanar_linear:
  // the exact library through triplanar_linear_shader (twin.hpp).
  static std::optional<SurfaceShader> surface_shader(const tiling::TilingModel& model,
                                                     const SurfaceOptions& options);
};

}  // namespace stochtex::gl
