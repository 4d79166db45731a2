#pragma once
// The GPU twin of Gabor noise (gl::Twin, src/gl/twin.hpp): the model as GLSL data, its per-grid
// constants as GLSL source and its Gaussians and Poisson tables packed into one RGBA float image
// (gl_data.cpp). Used by the GL renderer (gl_pass.cpp, render.glsl) and by `stochtex
// export-shader`, so both run evaluate.glsl on the same data.

#include <array>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "gl/twin.hpp"
#include "methods/gabor/model.hpp"
#include "stochtex/image.hpp"

namespace stochtex::gl {

struct GaborGlsl {
  // Texels per row of `data`: the largest model (kMaxGaussians, 2^22) takes 4112 rows.
  static constexpr int kDataWidth = kDataTextureWidth;
  // Texels of one grid's Poisson CDF (CellCount::kTableSize floats, 4 per texel).
  static constexpr int kCdfTexels = CellCount::kTableSize / 4;

  GlslPrecision precision = GlslPrecision::doubles;
  // The model's; beyond 4 the colour is an array of floats (noise_channels.glsl), not a vec4.
  int channels = 1;
  std::string constants;  // GLSL const declarations, GABOR_* (exact float and double literals)
  // 4 channels, kDataWidth wide, read in row-major texel order: texel i < gaussians is Gaussian i
  // of the grid-sorted model (frequency x, frequency y, alias probability, alias index within
  // its grid); then kCdfTexels texels per grid, its Poisson CDF.
  ImageF data;
};

// The model's data and constants for the GLSL of `precision`: with GlslPrecision::floats the
// grids' radius and cell size are the floats the C++ rounds them to, and GABOR_GRID_ARRAY sizes
// gabor_noise's per-grid arrays.
GaborGlsl gabor_glsl(const gabor::GaborModel& model,
                     GlslPrecision precision = GlslPrecision::doubles);

// random.glsl, float_math.glsl, kConstants, the model's constants, the data read (gabor_texel:
// texelFetch from the sampler `stochtex_gabor_data`) and gabor evaluate.glsl and noise.glsl
// (noise_channels.glsl beyond 4 channels), all in glsl.precision (the float one is the `--gl-filter
// hardware` library, without doubles): all but `#version`.
std::string gabor_library_source(const GaborGlsl& glsl);

template <>
struct Twin<gabor::GaborModel> {
  static constexpr std::array<GlslConstant, 6> kConstants = {{
      {"GABOR_PI", std::numbers::pi},
      {"GABOR_PI_F", gabor::kPiF},
      {"GABOR_TAPER_SCALE", gabor::kTaperScale},
      {"GABOR_PIXEL_VARIANCE", gabor::kPixelVariance},
      {"GABOR_NEGLIGIBLE_ATTENUATION", gabor::kNegligibleAttenuation},
      {"GABOR_MAX_LEVEL_RATIO", static_cast<double>(std::uint64_t{1} << gabor::kMaxLevels)},
  }};
  static std::unique_ptr<Pass> pass(const gabor::GaborModel& model);
  // fast: the float-only library of --gl-filter hardware (gabor_glsl with GlslPrecision::floats,
  // the same data image read with texelFetch), which GLSL ES, HLSL and Metal can express.
  static ExportParts shader(const gabor::GaborModel& model, ShaderVariant variant);
  // surface: the double-precision library (the data image as SurfaceShader::textures, each
  // grid's 3-D Poisson CDF appended), surface_process.glsl and stochtex_gabor_surface
  // (surface.glsl), with the constants of options.surface_mni; triplanar_linear: the
  // double-precision library through triplanar_linear_shader (twin.hpp), the data image likewise.
  static std::optional<SurfaceShader> surface_shader(const gabor::GaborModel& model,
                                                     const SurfaceOptions& options);
};

}  // namespace stochtex::gl
