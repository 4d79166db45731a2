#pragma once
// A Gabor noise model as GLSL data: its per-grid constants as GLSL source and its Gaussians and
// Poisson tables packed into one RGBA float image. Used by the GL renderer and by `stochtex
// export-shader`, so both run the same code.

#include <string>

#include "gl/glsl_text.hpp"
#include "methods/gabor/model.hpp"
#include "stochtex/image.hpp"

namespace stochtex::gl {

struct GaborGlsl {
  // Texels per row of `data`: the largest model (kMaxGaussians, 2^22) takes 4112 rows.
  static constexpr int kDataWidth = kDataTextureWidth;
  // Texels of one grid's Poisson CDF (PoissonSampler::kTableSize floats, 4 per texel).
  static constexpr int kCdfTexels = PoissonSampler::kTableSize / 4;

  std::string constants;  // GLSL const declarations, GABOR_* (exact float and double literals)
  // 4 channels, kDataWidth wide, read in row-major texel order: texel i < gaussians is Gaussian i
  // of the grid-sorted model (frequency x, frequency y, alias probability, alias index within
  // its grid); then kCdfTexels texels per grid, its Poisson CDF.
  ImageF data;
};

GaborGlsl gabor_glsl(const gabor::GaborModel& model);

// random.glsl, the constants, the data sampler and gabor evaluate.glsl: all but `#version`.
std::string gabor_library_source(const GaborGlsl& glsl);

}  // namespace stochtex::gl
