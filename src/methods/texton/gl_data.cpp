// Texton noise as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gl/glsl_text.hpp"
#include "gl/shaders.hpp"
#include "methods/texton/gl_twin.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {

TextonGlsl texton_shot_noise_glsl(const texton::TextonModel& model, int first_channel) {
  const auto& pyramid = model.pyramid();
  const int lanes = model.lanes();
  const int channels = std::min(4, model.channels() - first_channel);
  std::vector<int> rows;
  std::vector<float> spacing;
  std::vector<float> first;
  std::vector<float> half;
  int height = 0;
  for (const auto& level : pyramid) {
    rows.push_back(height);
    spacing.push_back(level.spacing);
    first.push_back(level.first_texel);
    half.push_back(level.half_width);
    height += level.stride;
  }
  TextonGlsl glsl;
  glsl.atlas = ImageF(pyramid.front().stride, height, 4);
  for (std::size_t l = 0; l < pyramid.size(); ++l)
    for (int y = 0; y < pyramid[l].stride; ++y)
      for (int x = 0; x < pyramid[l].stride; ++x)
        for (int c = 0; c < channels; ++c)
          glsl.atlas.at(x, rows[l] + y, c) =
              pyramid[l].coefficients[(static_cast<std::size_t>(y) * pyramid[l].stride + x) *
                                          static_cast<std::size_t>(lanes) +
                                      static_cast<std::size_t>(first_channel + c)];

  const auto& cdf = model.cell_count().cdf();
  std::string& text = glsl.constants;
  text += "const int TEXTON_CHANNELS = " + std::to_string(channels) + ";\n";
  text += "const int TEXTON_ORDER = " + std::to_string(model.order()) + ";\n";
  text +=
      "const float TEXTON_CELL_SIZE = " + glsl_float(static_cast<float>(model.cell_size())) + ";\n";
  text += glsl_array("float", "TEXTON_COUNT_CDF", std::span<const float>(cdf), glsl_float);
  text +=
      "const uint TEXTON_COUNT_CHUNKS = " + std::to_string(model.cell_count().chunks()) + "u;\n";
  text += std::string("const bool TEXTON_BALANCED = ") +
          (model.balanced_points() ? "true" : "false") + ";\n";
  text +=
      "const float TEXTON_INVERSE_SQRT_INTENSITY = " + glsl_float(model.inverse_sqrt_intensity()) +
      ";\n";
  text += "const int TEXTON_LEVELS = " + std::to_string(pyramid.size()) + ";\n";
  text += glsl_array("int", "TEXTON_LEVEL_ROW", std::span<const int>(rows), glsl_int);
  text += glsl_array("float", "TEXTON_LEVEL_SPACING", std::span<const float>(spacing), glsl_float);
  text +=
      glsl_array("float", "TEXTON_LEVEL_FIRST_TEXEL", std::span<const float>(first), glsl_float);
  text += glsl_array("float", "TEXTON_LEVEL_HALF_WIDTH", std::span<const float>(half), glsl_float);
  return glsl;
}

TextonGlsl texton_glsl(const texton::TextonModel& model, int first_channel) {
  TextonGlsl glsl = texton_shot_noise_glsl(model, first_channel);
  const auto first = static_cast<std::size_t>(first_channel);
  glsl.constants +=
      "const vec4 TEXTON_CONSTANT_TERM = " + glsl_vec4(model.constant_term().subspan(first)) +
      ";\n";
  glsl.constants += "const vec4 TEXTON_MEAN = " + glsl_vec4(model.mean().subspan(first)) + ";\n";

  return glsl;
}

void refuse_beyond_four_channels(const texton::TextonModel& model, const std::string& what) {
  if (model.channels() > 4)
    throw Error(ErrorCode::invalid_input,
                "texton: " + what + " takes 1 to 4 channels and this model has " +
                    std::to_string(model.channels()) +
                    "; `render --backend gl --gl-filter exact` and the CPU backend render it");
}

std::string texton_atlas_source(const ImageF& atlas, DataSource source) {
  if (source == DataSource::textures)
    return "uniform sampler2D stochtex_texton_atlas;\nvec4 texton_atlas_texel(ivec2 texel) {\n"
           "  return texelFetch(stochtex_texton_atlas, texel, 0);\n}\n";
  return "layout(std430, binding = 0) readonly buffer TextonAtlas { vec4 texton_atlas[]; };\n"
         "vec4 texton_atlas_texel(ivec2 texel) {\n  return texton_atlas[texel.y * " +
         std::to_string(atlas.width()) + " + texel.x];\n}\n";
}

namespace {

// The exact library up to texton_noise (noise.glsl), with `atlas_read` defining
// texton_atlas_texel.
std::string texton_noise_source(const TextonGlsl& glsl, const std::string& atlas_read) {
  return random_source() + glsl_constants(Twin<texton::TextonModel>::kConstants) + glsl.constants +
         atlas_read + shader_source("methods/texton/evaluate.glsl") +
         shader_source("methods/texton/exact_fetch.glsl") +
         shader_source("methods/texton/impulses.glsl") + shader_source("methods/texton/noise.glsl");
}

}  // namespace

std::string texton_library_source(const TextonGlsl& glsl, DataSource source) {
  return texton_noise_source(glsl, texton_atlas_source(glsl.atlas, source)) +
         shader_source("methods/texton/entry.glsl");
}

namespace {

// A material beyond 4 channels (export-shader): the exact library of every chunk of 4 channels at
// once, texton_channels (channels.glsl) summing the impulses once per chunk with the same draws, as
// the renderer's chunks do (gl_pass.cpp). The chunks' atlases lie side by side in one image, chunk
// k's from column k * TEXTON_CHUNK_WIDTH; chunk 0's constants serve every chunk but for the
// constant term and mean, which TEXTON_MATERIAL_CONSTANT and TEXTON_MATERIAL_MEAN give per channel.
ExportParts material_shader(const texton::TextonModel& model) {
  TextonGlsl glsl = texton_glsl(model);
  const int width = glsl.atlas.width();
  const int chunks = (model.channels() + 3) / 4;
  ImageF atlas(width * chunks, glsl.atlas.height(), 4);
  for (int chunk = 0; chunk < chunks; ++chunk) {
    const ImageF part = chunk == 0 ? glsl.atlas : texton_glsl(model, 4 * chunk).atlas;
    for (int y = 0; y < part.height(); ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < 4; ++c) atlas.at(chunk * width + x, y, c) = part.at(x, y, c);
  }
  glsl.constants +=
      "const int TEXTON_MATERIAL_CHANNELS = " + glsl_int(model.channels()) +
      ";\nconst int TEXTON_CHUNK_WIDTH = " + glsl_int(width) + ";\n" +
      glsl_array("float", "TEXTON_MATERIAL_CONSTANT", model.constant_term(), glsl_float) +
      glsl_array("float", "TEXTON_MATERIAL_MEAN", model.mean(), glsl_float);
  const std::string atlas_read =
      "uniform sampler2D stochtex_texton_atlas;\n// The chunk texton_channels sums.\n"
      "int texton_chunk;\nvec4 texton_atlas_texel(ivec2 texel) {\n"
      "  return texelFetch(stochtex_texton_atlas, texel + ivec2(texton_chunk * "
      "TEXTON_CHUNK_WIDTH, 0), 0);\n}\n";
  std::ostringstream what;
  what << "Texton noise (" << model.channels() << " channels in " << chunks
       << " chunks of 4, texton " << model.support() << "x" << model.support() << ", MNI "
       << model.mean_impacts() << ")";
  std::vector<ShaderTexture> images;
  images.push_back({"texton_atlas", std::move(atlas)});
  ExportParts parts{
      texton::TextonModel::kMethodName,
      "texton noise",
      what.str(),
      texton_noise_source(glsl, atlas_read) + shader_source("methods/texton/channels.glsl"),
      std::move(images),
      "`texton_atlas.exr` holds the pyramid of each chunk of 4 channels, side by "
      "side, TEXTON_CHUNK_WIDTH\ncolumns each. Every chunk sums the same impulses. "
      "Keep |p| below ~1e4 for full float precision."};
  parts.channels_function = "texton_channels";
  return parts;
}

// The fast variant (order-1 models): texton hardware.glsl and level 0 of the pyramid as a
// mip-mapped float texture. Textons are signed and the texture's border must read zero: PNG's
// unsigned samples would need an offset that a transparent-black border (the only border colour
// every API has) breaks, so the texture is float32 OpenEXR (the data itself: nothing lost).
ExportParts fast_shader(const texton::TextonModel& model) {
  const TextonGlsl glsl = texton_glsl(model);
  const texton::PyramidLevel& base = model.pyramid().front();
  ShaderTexture texture{"texton_texture", ImageF(base.stride, base.stride, model.channels())};
  std::copy(base.coefficients.begin(), base.coefficients.end(), texture.image.pixels().begin());
  texture.filter = TextureFilter::mipmap;
  texture.wrap = TextureWrap::clamp_to_border;
  // The model's levels, as far as GL's chain for the texture's side goes.
  const auto levels = static_cast<int>(model.pyramid().size());
  while (texture.mip_levels < levels && (base.stride >> texture.mip_levels) > 0)
    ++texture.mip_levels;
  std::ostringstream what;
  what << "Texton noise, fast variant (" << model.channels() << " channels, texton "
       << model.support() << "x" << model.support() << ", MNI " << model.mean_impacts() << ")";
  std::vector<ShaderTexture> textures;
  textures.push_back(std::move(texture));
  return {texton::TextonModel::kMethodName,
          "texton noise",
          what.str(),
          "#define TEXTON_TEXTURE_FILTER\n" + random_source() +
              glsl_constants(Twin<texton::TextonModel>::kConstants) + glsl.constants +
              shader_source("methods/texton/evaluate.glsl") +
              shader_source("methods/texton/hardware.glsl") +
              shader_source("methods/texton/impulses.glsl") +
              shader_source("methods/texton/noise.glsl") +
              "#define stochtex_texton texton_at_level_of_detail\n" +
              shader_source("methods/texton/entry.glsl") + "#undef stochtex_texton\n" +
              shader_source("methods/texton/fast_entry.glsl"),
          std::move(textures),
          "Equal to the CPU render in distribution (mean, variance; tested), not pixel for pixel.\n"
          "`texton_texture.exr` is the texton (level 0 of the model's pyramid, padded with zeros): "
          "signed\nvalues, so float. Keep |p| below ~1e4 for full float precision.",
          ShaderVariant::fast};
}

}  // namespace

bool has_fast_variant(const texton::TextonModel& model) {
  return model.order() == 1;
}

ExportParts Twin<texton::TextonModel>::shader(const texton::TextonModel& model,
                                              ShaderVariant variant) {
  if (variant == ShaderVariant::fast && has_fast_variant(model)) {
    if (model.channels() > 4)
      throw Error(ErrorCode::invalid_input,
                  "texton: the fast variant reads the texton from one texture of at most 4 "
                  "channels and this material has " +
                      std::to_string(model.channels()) + "; export it with --variant exact");
    return fast_shader(model);
  }
  if (model.channels() > 4) return material_shader(model);
  TextonGlsl glsl = texton_glsl(model);
  std::ostringstream what;
  what << "Texton noise (" << model.channels() << " channels, texton " << model.support() << "x"
       << model.support() << ", MNI " << model.mean_impacts() << ")";
  std::vector<ShaderTexture> images;
  images.push_back({"texton_atlas", std::move(glsl.atlas)});
  return {texton::TextonModel::kMethodName,
          "texton noise",
          what.str(),
          texton_library_source(glsl),
          std::move(images),
          "Keep |p| below ~1e4 for full float precision."};
}

std::optional<SurfaceShader> Twin<texton::TextonModel>::surface_shader(
    const texton::TextonModel& model, const SurfaceOptions& options) {
  TextonGlsl glsl = texton_glsl(model);
  const auto texels = glsl.atlas.pixels();
  if (options.mapping == SurfaceMapping::triplanar_linear)
    return triplanar_linear_shader(texton::TextonModel::kMethodName,
                                   texton_library_source(glsl, DataSource::storage_buffers),
                                   std::vector<float>(texels.begin(), texels.end()));
  if (options.mapping != SurfaceMapping::surface) return std::nullopt;
  const texton::SurfaceConstants surface = model.surface_constants(options.surface_mni);
  const auto& cdf = surface.count.cdf();
  std::string& text = glsl.constants;
  text += "const float TEXTON_SURFACE_CELL_SIZE = " +
          glsl_float(static_cast<float>(surface.cell_size)) + ";\n";
  text +=
      glsl_array("float", "TEXTON_SURFACE_POISSON_CDF", std::span<const float>(cdf), glsl_float);
  text += "const uint TEXTON_SURFACE_POISSON_CHUNKS = " + std::to_string(surface.count.chunks()) +
          "u;\n";
  text += "const float TEXTON_SURFACE_DEPTH = " + glsl_float(surface.depth) + ";\n";
  text += "const float TEXTON_SURFACE_INVERSE_DEPTH = " + glsl_float(surface.inverse_depth) + ";\n";
  text += "const float TEXTON_SURFACE_SCALE = " + glsl_float(surface.scale) + ";\n";
  text += "const vec4 TEXTON_SURFACE_CONSTANT = " + glsl_vec4(surface.constant) + ";\n";
  text += "#define SURFACE_CONTEXT TextonFilter\n";
  std::string library = texton_library_source(glsl, DataSource::storage_buffers) +
                        shader_source("gl/surface_process.glsl") +
                        shader_source("methods/texton/surface.glsl");
  return SurfaceShader{std::move(library),
                       std::vector<float>(texels.begin(), texels.end()),
                       "stochtex_texton_surface(position, normal, tangent, dpdx, dpdy, seed)",
                       {}};
}

}  // namespace stochtex::gl
