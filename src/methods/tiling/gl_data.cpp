// Histogram-preserving tiling as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <span>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "methods/tiling/gl_twin.hpp"

namespace stochtex::gl {

TilingGlsl tiling_glsl(const tiling::TilingModel& model) {
  const tiling::TilingData& d = model.data();
  const tiling::TilingLayout& layout = model.layout();
  TilingGlsl glsl;
  std::vector<int> widths;
  std::vector<int> heights;
  std::vector<int> texels;
  std::vector<int> luts;
  std::vector<int> tables;
  const auto append = [&](std::span<const float> values) {
    const auto offset = static_cast<int>(glsl.data.size());
    glsl.data.insert(glsl.data.end(), values.begin(), values.end());
    return offset;
  };
  for (int level = 0; level < model.level_count(); ++level) {
    const tiling::MipLevel mip = model.level(level);
    widths.push_back(mip.width);
    heights.push_back(mip.height);
    texels.push_back(append({mip.texels, static_cast<std::size_t>(mip.width) * mip.height *
                                             static_cast<std::size_t>(d.channels)}));
    luts.push_back(append(model.level_lut(level)));
    tables.push_back(append(model.level_tables(level)));
  }
  std::string& text = glsl.constants;
  const auto constant = [&](const char* type, const char* name, const std::string& value) {
    text += "const " + std::string(type) + " " + name + " = " + value + ";\n";
  };
  const auto flag = [](bool value) { return std::string(value ? "true" : "false"); };
  constant("int", "TILING_CHANNELS", glsl_int(d.channels));
  constant("int", "TILING_WIDTH", glsl_int(d.width));
  constant("int", "TILING_HEIGHT", glsl_int(d.height));
  constant("float", "TILING_EDGE", glsl_float(static_cast<float>(model.lattice_edge())));
  constant("int", "TILING_BLEND", glsl_int(static_cast<int>(d.blend)));
  constant("vec4", "TILING_BLEND_MEAN", glsl_vec4(d.blend_mean));
  constant("int", "TILING_LEVELS", glsl_int(model.level_count()));
  constant("bool", "TILING_COLOUR_LUT", flag(layout.colour_lut));
  constant("bool", "TILING_HAS_ALPHA", flag(layout.has_alpha));
  constant("int", "TILING_COLOUR_CHANNELS", glsl_int(layout.colour_channels));
  constant("int", "TILING_FIRST_ALPHA_TABLE", glsl_int(layout.first_alpha_table));
  constant("int", "TILING_LUT_SIZE", glsl_int(d.lut_size));
  constant("int", "TILING_TABLE_SIZE", glsl_int(d.table_size));
  text += glsl_array("float", "TILING_COLOUR_BASIS", std::span<const float>(d.colour_basis),
                     glsl_float);
  text +=
      glsl_array("float", "TILING_COLOUR_MEAN", std::span<const float>(d.colour_mean), glsl_float);
  text += glsl_array("int", "TILING_LEVEL_WIDTH", std::span<const int>(widths), glsl_int);
  text += glsl_array("int", "TILING_LEVEL_HEIGHT", std::span<const int>(heights), glsl_int);
  text += glsl_array("int", "TILING_LEVEL_TEXELS", std::span<const int>(texels), glsl_int);
  text += glsl_array("int", "TILING_LEVEL_LUT", std::span<const int>(luts), glsl_int);
  text += glsl_array("int", "TILING_LEVEL_TABLES", std::span<const int>(tables), glsl_int);
  return glsl;
}

std::string tiling_library_source(const TilingGlsl& glsl, DataSource source) {
  const std::string reader =
      source == DataSource::storage_buffers
          ? "layout(std430, binding = 0) readonly buffer TilingData { float tiling_data[]; };\n"
            "float tiling_data_at(int index) { return tiling_data[index]; }\n"
          : glsl_packed_read("stochtex_tiling_data", "tiling_data_at");
  return random_source() + glsl_constants(Twin<tiling::TilingModel>::kConstants) + glsl.constants +
         reader + shader_source("methods/tiling/evaluate.glsl");
}

ExportParts Twin<tiling::TilingModel>::shader(const tiling::TilingModel& model) {
  const TilingGlsl glsl = tiling_glsl(model);
  std::vector<NamedImage> images;
  images.push_back({"tiling_data", pack_rgba(glsl.data)});
  return {tiling::TilingModel::kMethodName,
          "histogram-preserving tiling",
          "Histogram-preserving tiling and blending (" + std::to_string(model.channels()) +
              " channels)",
          tiling_library_source(glsl, DataSource::textures),
          std::move(images),
          "`tiling_data.exr` is one float array (the exemplar's pyramid and look-up tables) packed "
          "four floats\nper texel, 1024 texels per row. Keep |p| below ~1e4 for full float "
          "precision."};
}

}  // namespace stochtex::gl
