#pragma once
// The GPU twin of local random-phase noise (gl::Twin, src/gl/twin.hpp): the model as GLSL data,
// its constants as GLSL source and its tables (gl_data.cpp), as storage buffers for the GL
// renderer (gl_pass.cpp, render.glsl) and as one texture for `stochtex export-shader`.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl/twin.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/model.hpp"
#include "methods/lrp/structure.hpp"
#include "methods/lrp/window.hpp"

namespace stochtex::gl {

struct LrpGlsl {
  std::string constants;                 // GLSL const declarations, LRP_* (exact float literals)
  std::vector<float> frequencies;        // `lrp_frequencies`: (f_x, f_y, weight) triples
  std::vector<std::uint32_t> substrata;  // `lrp_substrata`: (first, count) pairs
  // Section 5 (empty without structure): `lrp_structure` (f_x, f_y, amplitude, phase) per
  // cosine, `lrp_turbulence_frequencies` and `lrp_turbulence_substrata` as above.
  std::vector<float> structure;
  std::vector<float> turbulence_frequencies;
  std::vector<std::uint32_t> turbulence_substrata;
};

LrpGlsl lrp_glsl(const lrp::LrpModel& model);

// random.glsl, kConstants, the model's constants, the table readers and lrp evaluate.glsl: all but
// `#version`. The tables are the storage buffers at bindings 0 and 2, or the texture
// `stochtex_lrp_tables` of lrp_tables_image().
std::string lrp_library_source(const LrpGlsl& glsl,
                               DataSource source = DataSource::storage_buffers);

// The tables as one RGBA image for an exported shader, one entry per texel, one table after the
// other: frequencies (f_x, f_y, weight), sub-strata (first, count), and for section 5 the
// structure cosines (f_x, f_y, amplitude, phase), turbulence frequencies (f_x, f_y) and turbulence
// sub-strata (first, count); the shader's LRP_*_TEXEL constants give where each starts. Counts
// are floats, exact below 2^24 (export_shader checks).
ImageF lrp_tables_image(const LrpGlsl& glsl);

template <>
struct Twin<lrp::LrpModel> {
  static constexpr std::array<GlslConstant, 9> kConstants = {{
      {"LRP_PICK_BITS", lrp::kPickBits},
      {"LRP_PICK_MASK", lrp::kPickMask},
      {"LRP_PHASE_STEP", lrp::kPhaseStep},
      {"LRP_CLAMP_START", lrp::kClampStart},
      {"LRP_CLAMP_END", lrp::kClampEnd},
      {"LRP_PLACEMENT_BLEND", lrp::kPlacementBlend},
      {"LRP_WINDOW_RADIUS_SQUARED", lrp::kWindowRadiusSquared},
      {"LRP_WINDOW_TERMS", lrp::kWindowTerms},
      {"LRP_TURBULENCE_STREAM_BASE", static_cast<int>(lrp::kTurbulenceStreamBase)},
  }};
  static std::unique_ptr<Pass> pass(const lrp::LrpModel& model);
  // The hardware path of lrp is its exact one (it filters analytically), so ShaderVariant::fast
  // exports the exact variant: the same files, byte for byte.
  static ExportParts shader(const lrp::LrpModel& model, ShaderVariant variant);
};

}  // namespace stochtex::gl
