// Texton noise mixing as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gl/glsl_text.hpp"
#include "gl/shaders.hpp"
#include "methods/texton/gl_twin.hpp"
#include "methods/texton_mix/gl_twin.hpp"

namespace stochtex::gl {

std::array<float, 2> texton_mix_field_at(const texton_mix::MixField& field, double cell_x,
                                         double cell_y, double cell_size) {
  const double x = cell_x * cell_size;
  const double y = cell_y * cell_size;
  if (field.is_mask())
    return {static_cast<float>(x * field.inverse_scale() - 0.5),
            static_cast<float>(y * field.inverse_scale() - 0.5)};
  return {static_cast<float>((x * field.unit_x() + y * field.unit_y() - field.ramp_start()) *
                             field.inverse_length()),
          0.0f};
}

TextonMixGlsl texton_mix_glsl(const texton_mix::TextonMixModel& model) {
  const int steps = model.steps();
  // Every step's texton model has the same support, order and MNI, hence the same constants and
  // atlas layout: step 0's constants serve all, and the atlases go in a grid of near-square shape.
  const TextonGlsl first = texton_shot_noise_glsl(model.texton(0));
  const int tile_width = first.atlas.width();
  const int tile_height = first.atlas.height();
  const int columns = std::clamp(
      static_cast<int>(std::ceil(std::sqrt(static_cast<double>(steps) * tile_height / tile_width))),
      1, steps);
  const int rows = (steps + columns - 1) / columns;
  ShaderTexture atlas{"texton_atlas", ImageF(columns * tile_width, rows * tile_height, 4)};
  for (int step = 0; step < steps; ++step) {
    const TextonGlsl glsl = step == 0 ? first : texton_shot_noise_glsl(model.texton(step));
    const int x0 = step % columns * tile_width;
    const int y0 = step / columns * tile_height;
    for (int y = 0; y < tile_height; ++y)
      for (int x = 0; x < tile_width; ++x)
        for (int c = 0; c < 4; ++c) atlas.image.at(x0 + x, y0 + y, c) = glsl.atlas.at(x, y, c);
  }

  const texton_mix::MixField& field = model.field();
  const std::array<float, 2> at_origin = texton_mix_field_at(field, 0.0, 0.0, 1.0);
  std::string constants = first.constants;
  constants += "const int TEXTON_MIX_STEPS = " + std::to_string(steps) + ";\n";
  constants += "const int TEXTON_MIX_ATLAS_COLUMNS = " + std::to_string(columns) + ";\n";
  constants += "const ivec2 TEXTON_MIX_ATLAS_TILE = ivec2(" + std::to_string(tile_width) + ", " +
               std::to_string(tile_height) + ");\n";
  constants += "const vec4 TEXTON_MIX_MEAN_A = " + glsl_vec4(model.mean_a()) + ";\n";
  constants += "const vec4 TEXTON_MIX_MEAN_B = " + glsl_vec4(model.mean_b()) + ";\n";
  constants += "const vec2 TEXTON_MIX_FIELD_AT_ORIGIN = vec2(" + glsl_float(at_origin[0]) + ", " +
               glsl_float(at_origin[1]) + ");\n";
  std::vector<ShaderTexture> textures;
  textures.push_back(std::move(atlas));
  std::string mask_source;
  if (field.is_mask()) {
    constants += "#define TEXTON_MIX_MASK\n";
    constants += "const ivec2 TEXTON_MIX_MASK_SIZE = ivec2(" + std::to_string(field.mask_width()) +
                 ", " + std::to_string(field.mask_height()) + ");\n";
    constants += "const float TEXTON_MIX_MASK_INVERSE_SCALE = " +
                 glsl_float(static_cast<float>(field.inverse_scale())) + ";\n";
    mask_source = glsl_packed_read("stochtex_texton_mix_mask", "texton_mix_mask");
    textures.push_back({"texton_mix_mask", pack_rgba(field.mask())});
  } else {
    constants += "const vec2 TEXTON_MIX_RAMP_UNIT = vec2(" +
                 glsl_float(static_cast<float>(field.unit_x())) + ", " +
                 glsl_float(static_cast<float>(field.unit_y())) + ");\n";
    constants += "const float TEXTON_MIX_RAMP_INVERSE_LENGTH = " +
                 glsl_float(static_cast<float>(field.inverse_length())) + ";\n";
  }
  return {random_source() + glsl_constants(Twin<texton::TextonModel>::kConstants) +
              glsl_constants(Twin<texton_mix::TextonMixModel>::kConstants) + constants +
              texton_atlas_source(textures.front().image, DataSource::textures) + mask_source +
              shader_source("methods/texton/evaluate.glsl") +
              shader_source("methods/texton/exact_fetch.glsl") +
              shader_source("methods/texton/impulses.glsl") +
              shader_source("methods/texton_mix/evaluate.glsl") +
              shader_source("methods/texton_mix/entry.glsl"),
          std::move(textures)};
}

ExportParts Twin<texton_mix::TextonMixModel>::shader(const texton_mix::TextonMixModel& model,
                                                     ShaderVariant) {
  TextonMixGlsl glsl = texton_mix_glsl(model);
  std::ostringstream what;
  what << "Texton noise mixing (" << model.channels() << " channels, " << model.steps()
       << " textons " << model.support() << "x" << model.support() << ", "
       << (model.field().is_mask() ? "mask" : "ramp") << " field)";
  return {texton_mix::TextonMixModel::kMethodName,
          "texton noise mixing",
          what.str(),
          std::move(glsl.library),
          std::move(glsl.textures),
          "The fast variant is this exact shader (R textons would need R mip-mapped textures).\n"
          "`texton_atlas.exr` holds the R textons' pyramids in a grid; "
          "`texton_mix_mask.exr` (a mask\nfield only) the mask, four values a texel. "
          "Keep |p| below ~1e4 for full float precision."};
}

}  // namespace stochtex::gl
