#pragma once
// The GPU twin of texton noise mixing (gl::Twin, src/gl/twin.hpp): texton noise's GLSL
// (texton/evaluate.glsl, exact_fetch.glsl, impulses.glsl: the same shot-noise loop) with this
// method's impulses and mean (evaluate.glsl), the R textons' pyramids as one atlas image and a
// mask as packed floats (gl_data.cpp), used by the GL renderer (gl_pass.cpp, texton render.glsl)
// and by `stochtex export-shader`. Both variants are the exact path: the fast one would need R
// mip-mapped textures, so --gl-filter hardware and --variant fast run and export the exact GLSL.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl/twin.hpp"
#include "methods/texton_mix/model.hpp"
#include "stochtex/image.hpp"

namespace stochtex::gl {

struct TextonMixGlsl {
  std::string library;  // all but `#version`: random.glsl ... texton_mix/entry.glsl
  // texton_atlas: the R textons' atlases (texton_shot_noise_glsl) in a grid,
  // TEXTON_MIX_ATLAS_COLUMNS a row; texton_mix_mask (a mask field): the mask, pack_rgba.
  std::vector<ShaderTexture> textures;
};

TextonMixGlsl texton_mix_glsl(const texton_mix::TextonMixModel& model);

// The field's value at the corner of the grid cell (cell_x, cell_y) of side `cell_size`, in
// double: the ramp's unclamped rho there (x) or the mask's pixel coordinates (x, y). The GLSL
// adds the float offset from that corner, so far origins are as precise as near ones.
std::array<float, 2> texton_mix_field_at(const texton_mix::MixField& field, double cell_x,
                                         double cell_y, double cell_size);

template <>
struct Twin<texton_mix::TextonMixModel> {
  // Its shared constants are texton noise's and random.glsl's (STREAM_SIGNS among them).
  static constexpr std::array<GlslConstant, 0> kConstants = {};
  static std::unique_ptr<Pass> pass(const texton_mix::TextonMixModel& model);
  static ExportParts shader(const texton_mix::TextonMixModel& model, ShaderVariant variant);
};

}  // namespace stochtex::gl
