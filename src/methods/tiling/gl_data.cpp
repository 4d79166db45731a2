// Histogram-preserving tiling as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gl/shaders.hpp"
#include "methods/tiling/gl_twin.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {

namespace {

// The constants of the lattice and its patches (patches.glsl): the exemplar's size, the lattice
// edge and the artist controls.
std::string patch_constants(const tiling::TilingModel& model) {
  const tiling::TilingData& d = model.data();
  return "const int TILING_WIDTH = " + glsl_int(d.width) +
         ";\nconst int TILING_HEIGHT = " + glsl_int(d.height) +
         ";\nconst float TILING_EDGE = " + glsl_float(static_cast<float>(model.lattice_edge())) +
         ";\nconst float TILING_ROTATION = " +
         glsl_float(static_cast<float>(d.rotation * (std::numbers::pi / 180.0))) +
         ";\nconst float TILING_SCALE_JITTER = " + glsl_float(static_cast<float>(d.scale_jitter)) +
         ";\nconst float TILING_SHARPNESS = " + glsl_float(static_cast<float>(d.sharpness)) +
         ";\nconst bool TILING_TRANSFORMED = " + (model.transformed() ? "true" : "false") + ";\n";
}

}  // namespace

TilingGlsl tiling_glsl(const tiling::TilingModel& model, ShaderVariant variant) {
  const bool exact = variant == ShaderVariant::exact;
  const tiling::TilingData& d = model.data();
  const tiling::TilingLayout& layout = model.layout();
  // This GLSL reads an image's colour and alpha (blend.glsl): the renderer takes other models in
  // groups (renders_in_groups) and export-shader as a material (material_export); the surface
  // and mesh shaders do not.
  if (renders_in_groups(model))
    throw Error(ErrorCode::invalid_input,
                "tiling: the GL surface and mesh shaders take an image's colour and alpha (1 to 4 "
                "channels), and this model's " +
                    std::to_string(d.channels) + " channels go through T^-1 in " +
                    std::to_string(layout.groups.size()) +
                    " groups of their own; render it with --backend cpu");
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
    if (exact) {
      const tiling::MipLevel mip = model.level(level);
      widths.push_back(mip.width);
      heights.push_back(mip.height);
      texels.push_back(append({mip.texels, static_cast<std::size_t>(mip.width) * mip.height *
                                               static_cast<std::size_t>(d.channels)}));
      luts.push_back(append(model.level_lut(level)));
    }
    tables.push_back(append(model.level_tables(level)));
  }
  std::string& text = glsl.constants;
  const auto constant = [&](const char* type, const char* name, const std::string& value) {
    text += "const " + std::string(type) + " " + name + " = " + value + ";\n";
  };
  const auto flag = [](bool value) { return std::string(value ? "true" : "false"); };
  constant("int", "TILING_CHANNELS", glsl_int(d.channels));
  text += patch_constants(model);
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
  if (exact) {
    text += glsl_array("int", "TILING_LEVEL_WIDTH", std::span<const int>(widths), glsl_int);
    text += glsl_array("int", "TILING_LEVEL_HEIGHT", std::span<const int>(heights), glsl_int);
    text += glsl_array("int", "TILING_LEVEL_TEXELS", std::span<const int>(texels), glsl_int);
    text += glsl_array("int", "TILING_LEVEL_LUT", std::span<const int>(luts), glsl_int);
  }
  text += glsl_array("int", "TILING_LEVEL_TABLES", std::span<const int>(tables), glsl_int);
  return glsl;
}

namespace {

// tiling_data_at(), the read of the model's float array: the storage buffer at binding 0, or the
// texture `stochtex_tiling_data` of pack_rgba(data).
std::string data_reader(DataSource source) {
  return source == DataSource::storage_buffers
             ? "layout(std430, binding = 0) readonly buffer TilingData { float tiling_data[]; };\n"
               "float tiling_data_at(int index) { return tiling_data[index]; }\n"
             : glsl_packed_read("stochtex_tiling_data", "tiling_data_at");
}

// What groups.glsl has no case for, in words, or nullptr: the 3-D table (an image's colour,
// blend.glsl).
const char* missing_group_case(tiling::GroupTransform transform) {
  switch (transform) {
    case tiling::GroupTransform::decorrelated:
    case tiling::GroupTransform::direct:
    case tiling::GroupTransform::radial:
      return nullptr;
    case tiling::GroupTransform::lut:
      return "the 3-D colour table";
  }
  return "an unknown transform";
}

// The README's word on the triplanar entry point (triplanar.glsl, docs/shaders.md).
constexpr std::string_view kTriplanarNote =
    "The GLSL file also has `vec4 stochtex_tiling_triplanar(vec3 position, vec3 normal, vec3 "
    "dpdx, vec3 dpdy,\nfloat sharpness, uint seed)`: triplanar histogram-preserving blending of a "
    "surface point in exemplar\npixels (model space) with its unit normal, the screen derivatives "
    "of the position and the weights'\nsharpness (4 by default); GLSL only (the other languages "
    "keep what stochtex_tiling calls).";

// An image of values in [0, 1] as a PNG of `bits` bits, or as float32 EXR where a value falls
// outside (an HDR exemplar's table).
ShaderTexture png_or_exr(std::string name, ImageF image, int bits) {
  const auto pixels = image.pixels();
  if (!std::all_of(pixels.begin(), pixels.end(), [](float v) { return v >= 0.0f && v <= 1.0f; }))
    return {std::move(name), std::move(image)};
  return {std::move(name), quantized(std::move(image), bits),
          bits == 16 ? TextureEncoding::png16 : TextureEncoding::png8};
}

// The fast variant: tiling hardware.glsl's textures and the 1-D tables as exact float reads.
ExportParts fast_shader(const tiling::TilingModel& model) {
  const TilingGlsl glsl = tiling_glsl(model, ShaderVariant::fast);
  const tiling::TilingData& d = model.data();
  const tiling::MipLevel base = model.level(0);
  // The Gaussianised exemplar (mean 1/2, deviation 1/6; the exemplar itself for the variance and
  // linear blends) shrunk about 1/2 into [0, 1] where it spills over: the paper's 8-bit texture
  // clamps the Gaussian's tails beyond 3 deviations (section 4.2), which moves the extreme
  // colours of a render (measured: 0.007 at scale 1); this loses nothing (the clamp below only
  // catches float rounding).
  ImageF exemplar(base.width, base.height, d.channels);
  float spread = 0.5f;
  for (std::size_t i = 0; i < exemplar.pixels().size(); ++i)
    spread = std::max(spread, std::abs(base.texels[i] - 0.5f));
  const float scale = spread / 0.5f;
  for (std::size_t i = 0; i < exemplar.pixels().size(); ++i)
    exemplar.pixels()[i] = std::clamp((base.texels[i] - 0.5f) / scale + 0.5f, 0.0f, 1.0f);
  std::vector<ShaderTexture> textures;
  ShaderTexture& texture =
      textures.emplace_back(png_or_exr("tiling_exemplar", std::move(exemplar), kExemplarBits));
  texture.filter = TextureFilter::mipmap;
  texture.wrap = TextureWrap::repeat;
  while ((std::max(base.width, base.height) >> texture.mip_levels) > 0) ++texture.mip_levels;
  const std::string constants =
      glsl.constants + "const float TILING_TEXTURE_SCALE = " + glsl_float(scale) + ";\n";
  std::string defines = "#define TILING_TEXTURE_FILTER\n";
  if (model.layout().colour_lut && !model.level_lut(0).empty()) {
    // Each level's 3-D table (lut_size^3 RGB, x fastest): lut_size slices of lut_size rows per
    // level, the levels one after the other, as one lut_size x lut_size x lut_size levels texture.
    const int n = d.lut_size;
    ImageF lut(n, n * n * model.level_count(), 3);
    auto out = lut.pixels().begin();
    for (int l = 0; l < model.level_count(); ++l)
      out = std::copy(model.level_lut(l).begin(), model.level_lut(l).end(), out);
    ShaderTexture& table =
        textures.emplace_back(png_or_exr("tiling_lut", std::move(lut), kLutBits));
    table.depth = n * model.level_count();
    table.filter = TextureFilter::linear;
    defines += "#define TILING_LUT_TEXTURE\n";
  }
  std::string reader =
      "// This model has no 1-D tables (its colour goes through the 3-D table, no alpha): never "
      "called.\nfloat tiling_data_at(int index) {\n  return 0.0;\n}\n";
  if (!glsl.data.empty()) {
    textures.push_back({"tiling_tables", pack_rgba(glsl.data)});
    reader = glsl_packed_read("stochtex_tiling_tables", "tiling_data_at");
  }
  const std::string library =
      defines + random_source() + glsl_constants(Twin<tiling::TilingModel>::kConstants) +
      constants + reader + shader_source("methods/tiling/evaluate.glsl") +
      shader_source("methods/tiling/patches.glsl") + shader_source("methods/tiling/blend.glsl") +
      shader_source("methods/tiling/hardware.glsl") +
      "#define stochtex_tiling tiling_at_level_of_detail\n" +
      shader_source("methods/tiling/entry.glsl") + "#undef stochtex_tiling\n" +
      shader_source("methods/tiling/fast_entry.glsl") + shader_source("gl/triplanar.glsl") +
      shader_source("methods/tiling/triplanar.glsl");
  std::string notes =
      "Equal to the CPU render in distribution (mean, variance; tested), not pixel for pixel.\n"
      "`tiling_exemplar` is the Gaussianised exemplar (histogram blend; the exemplar itself for "
      "the variance\nand linear blends)";
  if (textures.back().name == "tiling_tables")
    notes +=
        "; `tiling_tables.exr` holds the 1-D tables of T^-1, one float array packed four "
        "floats per\ntexel, 1024 texels per row, read with texelFetch";
  notes += ". Keep |p| below ~1e4 for full float precision.\n" + std::string(kTriplanarNote);
  return {tiling::TilingModel::kMethodName,
          "histogram-preserving tiling",
          "Histogram-preserving tiling and blending, fast variant (" +
              std::to_string(model.channels()) + " channels)",
          library,
          std::move(textures),
          notes,
          ShaderVariant::fast};
}

}  // namespace

namespace {

// The model turns a normal map's slopes with its patches (GroupTransform::radial).
bool turns_slopes(const tiling::TilingModel& model) {
  const auto& groups = model.layout().groups;
  return model.transformed() &&
         std::any_of(groups.begin(), groups.end(), [](const tiling::TableGroup& group) {
           return group.transform == tiling::GroupTransform::radial;
         });
}

}  // namespace

bool blends_patches_apart(const tiling::TilingModel& model) {
  return model.data().height_blend > 0.0 || turns_slopes(model);
}

int patch_stride(const tiling::TilingModel& model) {
  return 3 * model.channels() + 15;
}

bool renders_in_groups(const tiling::TilingModel& model) {
  return !model.layout().image_layout || model.channels() > 4;
}

namespace {

// Appends the groups' T^-1 to `glsl` (inverse_groups.glsl): their constants (TILING_GROUP_*, the
// bases and means, the per-patch blend's controls) and each pyramid level's 1-D tables after its
// data (the TILING_LEVEL_TABLES offsets). Throws a sentence for a group of a kind groups.glsl has
// no case for (the 3-D table).
void append_groups(const tiling::TilingModel& model, TilingGlsl& glsl) {
  const tiling::TilingData& d = model.data();
  const tiling::TilingLayout& layout = model.layout();
  std::vector<int> transforms;
  std::vector<int> firsts;
  std::vector<int> counts;
  std::vector<int> tables;
  std::vector<int> bases;
  std::vector<int> means;
  for (const tiling::TableGroup& group : layout.groups) {
    if (const char* missing = missing_group_case(group.transform))
      throw Error(ErrorCode::invalid_input,
                  "tiling: the GPU twin takes groups of channels on their principal axes or of one "
                  "channel, and channels " +
                      std::to_string(group.first) + " to " +
                      std::to_string(group.first + group.channels - 1) +
                      " of this model go through " + missing + "; render it with --backend cpu");
    transforms.push_back(static_cast<int>(group.transform));
    firsts.push_back(group.first);
    counts.push_back(group.channels);
    tables.push_back(group.first_table);
    bases.push_back(group.first_basis);
    means.push_back(group.first_mean);
  }
  std::vector<int> level_tables;
  for (int level = 0; level < model.level_count(); ++level) {
    level_tables.push_back(static_cast<int>(glsl.data.size()));
    const std::span<const float> values = model.level_tables(level);
    glsl.data.insert(glsl.data.end(), values.begin(), values.end());
  }
  std::string& text = glsl.constants;
  const auto constant = [&](const char* name, int value) {
    text += "const int " + std::string(name) + " = " + glsl_int(value) + ";\n";
  };
  const auto array = [&](const char* name, const std::vector<int>& values) {
    text += glsl_array("int", name, std::span<const int>(values), glsl_int);
  };
  constant("TILING_CHANNELS", d.channels);
  constant("TILING_LEVELS", model.level_count());
  constant("TILING_TABLE_SIZE", d.table_size);
  constant("TILING_GROUP_DECORRELATED", static_cast<int>(tiling::GroupTransform::decorrelated));
  constant("TILING_GROUP_DIRECT", static_cast<int>(tiling::GroupTransform::direct));
  constant("TILING_GROUP_RADIAL", static_cast<int>(tiling::GroupTransform::radial));
  // The per-patch blend (TILING_PATCH_INPUT): the controls that need every channel.
  const auto flag = [&](const char* name, bool value) {
    text += "const bool " + std::string(name) + " = " + (value ? "true" : "false") + ";\n";
  };
  flag("TILING_TURNED", turns_slopes(model));
  flag("TILING_SCALE_JITTER_ON", d.scale_jitter > 0.0);
  constant("TILING_HEIGHT_CHANNEL", std::max(d.height_channel, 0));
  text += "const float TILING_HEIGHT_DEPTH = " + glsl_float(static_cast<float>(d.height_blend)) +
          ";\nconst float TILING_GAUSSIAN_DEVIATION = " + glsl_float(tiling::kGaussianDeviation) +
          ";\n";
  text +=
      glsl_array("float", "TILING_BLEND_MEANS", std::span<const float>(d.blend_mean), glsl_float);
  constant("TILING_GROUPS", static_cast<int>(layout.groups.size()));
  array("TILING_GROUP_TRANSFORM", transforms);
  array("TILING_GROUP_FIRST", firsts);
  array("TILING_GROUP_CHANNELS", counts);
  array("TILING_GROUP_TABLE", tables);
  array("TILING_GROUP_BASIS", bases);
  array("TILING_GROUP_MEAN", means);
  text += glsl_array("float", "TILING_COLOUR_BASIS", std::span<const float>(d.colour_basis),
                     glsl_float);
  text +=
      glsl_array("float", "TILING_COLOUR_MEAN", std::span<const float>(d.colour_mean), glsl_float);
  array("TILING_LEVEL_TABLES", level_tables);
}

}  // namespace

TilingGlsl tiling_groups_glsl(const tiling::TilingModel& model) {
  TilingGlsl glsl;
  if (blends_patches_apart(model))
    glsl.constants = "#define TILING_PATCH_INPUT\n#define TILING_PATCH_STRIDE " +
                     std::to_string(patch_stride(model)) + "\n";
  append_groups(model, glsl);
  return glsl;
}

TilingGlsl tiling_material_glsl(const tiling::TilingModel& model) {
  TilingGlsl glsl;
  std::vector<int> widths;
  std::vector<int> heights;
  std::vector<int> texels;
  for (int level = 0; level < model.level_count(); ++level) {
    const tiling::MipLevel mip = model.level(level);
    widths.push_back(mip.width);
    heights.push_back(mip.height);
    texels.push_back(static_cast<int>(glsl.data.size()));
    glsl.data.insert(glsl.data.end(), mip.texels,
                     mip.texels + static_cast<std::size_t>(mip.width) * mip.height *
                                      static_cast<std::size_t>(model.channels()));
  }
  glsl.constants = patch_constants(model);
  glsl.constants += glsl_array("int", "TILING_LEVEL_WIDTH", std::span<const int>(widths), glsl_int);
  glsl.constants +=
      glsl_array("int", "TILING_LEVEL_HEIGHT", std::span<const int>(heights), glsl_int);
  glsl.constants +=
      glsl_array("int", "TILING_LEVEL_TEXELS", std::span<const int>(texels), glsl_int);
  append_groups(model, glsl);
  return glsl;
}

std::string tiling_groups_source(const TilingGlsl& glsl) {
  return "#version 450\n" + glsl_constants(Twin<tiling::TilingModel>::kConstants) + glsl.constants +
         data_reader(DataSource::storage_buffers) + shader_source("methods/tiling/evaluate.glsl") +
         shader_source("methods/tiling/inverse_groups.glsl") +
         shader_source("methods/tiling/groups.glsl");
}

std::string tiling_library_source(const TilingGlsl& glsl, DataSource source) {
  return random_source() + glsl_constants(Twin<tiling::TilingModel>::kConstants) + glsl.constants +
         data_reader(source) + shader_source("methods/tiling/evaluate.glsl") +
         shader_source("methods/tiling/exact_fetch.glsl") +
         shader_source("methods/tiling/patches.glsl") + shader_source("methods/tiling/blend.glsl") +
         shader_source("methods/tiling/entry.glsl") + shader_source("gl/triplanar.glsl") +
         shader_source("methods/tiling/triplanar.glsl");
}

namespace {

// export-shader of a material (a model that renders_in_groups): tiling_channels (material.glsl),
// which the material function of export_material.cpp calls; its data, each pyramid level's texels
// of every channel and the groups' tables, in one float array.
ExportParts material_export(const tiling::TilingModel& model) {
  const TilingGlsl glsl = tiling_material_glsl(model);
  std::vector<ShaderTexture> images;
  images.push_back({"tiling_data", pack_rgba(glsl.data)});
  const std::string library =
      random_source() + glsl_constants(Twin<tiling::TilingModel>::kConstants) + glsl.constants +
      data_reader(DataSource::textures) + shader_source("methods/tiling/evaluate.glsl") +
      shader_source("methods/tiling/exact_fetch.glsl") +
      shader_source("methods/tiling/patches.glsl") +
      shader_source("methods/tiling/inverse_groups.glsl") +
      shader_source("methods/tiling/material.glsl");
  ExportParts parts{tiling::TilingModel::kMethodName,
                    "histogram-preserving tiling",
                    "Histogram-preserving tiling and blending of a material (" +
                        std::to_string(model.channels()) + " channels)",
                    library,
                    std::move(images),
                    "`tiling_data.exr` is one float array (the exemplar's pyramid, every channel, "
                    "and each map's look-up tables) packed four floats\nper texel, 1024 texels "
                    "per row. Keep |p| below ~1e4 for full float precision.\n"};
  parts.channels_function = "tiling_channels";
  return parts;
}

}  // namespace

ExportParts Twin<tiling::TilingModel>::shader(const tiling::TilingModel& model,
                                              ShaderVariant variant) {
  if (renders_in_groups(model)) {
    if (variant == ShaderVariant::fast)
      throw Error(ErrorCode::invalid_input,
                  "tiling: the fast variant reads an image's colour and alpha through its "
                  "textures, and this model's " +
                      std::to_string(model.channels()) + " channels go through T^-1 in " +
                      std::to_string(model.layout().groups.size()) +
                      " groups of their own; export it with --variant exact");
    return material_export(model);
  }
  if (variant == ShaderVariant::fast) return fast_shader(model);
  const TilingGlsl glsl = tiling_glsl(model);
  std::vector<ShaderTexture> images;
  images.push_back({"tiling_data", pack_rgba(glsl.data)});
  return {tiling::TilingModel::kMethodName,
          "histogram-preserving tiling",
          "Histogram-preserving tiling and blending (" + std::to_string(model.channels()) +
              " channels)",
          tiling_library_source(glsl, DataSource::textures),
          std::move(images),
          "`tiling_data.exr` is one float array (the exemplar's pyramid and look-up tables) packed "
          "four floats\nper texel, 1024 texels per row. Keep |p| below ~1e4 for full float "
          "precision.\n" +
              std::string(kTriplanarNote)};
}

std::optional<SurfaceShader> Twin<tiling::TilingModel>::surface_shader(
    const tiling::TilingModel& model, const SurfaceOptions& options) {
  TilingGlsl glsl = tiling_glsl(model);
  if (options.mapping == SurfaceMapping::triplanar_linear)
    return triplanar_linear_shader(tiling::TilingModel::kMethodName, tiling_library_source(glsl),
                                   std::move(glsl.data));
  if (options.mapping != SurfaceMapping::triplanar) return std::nullopt;
  return SurfaceShader{tiling_library_source(glsl),
                       std::move(glsl.data),
                       "stochtex_tiling_triplanar(position, normal, dpdx, dpdy, parameter, seed)",
                       {}};
}

}  // namespace stochtex::gl
