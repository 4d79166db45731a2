// Gabor noise as GLSL data (gl_twin.hpp) and its `stochtex export-shader` files.

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "gl/shaders.hpp"
#include "methods/gabor/gl_twin.hpp"

namespace stochtex::gl {

GaborGlsl gabor_glsl(const gabor::GaborModel& model, GlslPrecision precision) {
  const auto& grids = model.grids();
  const std::span<const float> probability = model.alias_probability();
  const std::span<const std::uint32_t> alias = model.alias_index();
  const std::size_t gaussians = probability.size();
  const std::size_t texels = gaussians + grids.size() * GaborGlsl::kCdfTexels;
  GaborGlsl glsl;
  glsl.precision = precision;
  glsl.data = ImageF(
      GaborGlsl::kDataWidth,
      std::max(1, static_cast<int>((texels + GaborGlsl::kDataWidth - 1) / GaborGlsl::kDataWidth)),
      4);
  const auto texel = [&](std::size_t index, int c) -> float& {
    return glsl.data.at(static_cast<int>(index % GaborGlsl::kDataWidth),
                        static_cast<int>(index / GaborGlsl::kDataWidth), c);
  };
  for (std::size_t i = 0; i < gaussians; ++i) {
    texel(i, 0) = model.frequency_x()[i];
    texel(i, 1) = model.frequency_y()[i];
    texel(i, 2) = probability[i];
    texel(i, 3) = static_cast<float>(alias[i]);  // < kMaxGaussians = 2^22: exact in a float
  }
  std::vector<int> channel, first, cdf_texel;
  std::vector<unsigned> count, chunks;
  std::vector<float> bandwidth, amplitude, min_frequency_squared;
  std::vector<double> radius, cell_size;
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const gabor::GaborModel::Grid& grid = grids[g];
    channel.push_back(grid.channel);
    first.push_back(static_cast<int>(grid.first));
    count.push_back(grid.count);
    bandwidth.push_back(grid.bandwidth);
    amplitude.push_back(grid.amplitude);
    min_frequency_squared.push_back(grid.min_frequency_squared);
    radius.push_back(grid.radius);
    cell_size.push_back(grid.cell_size);
    chunks.push_back(grid.cell_count.chunks());
    const std::size_t cdf_first = gaussians + g * GaborGlsl::kCdfTexels;
    cdf_texel.push_back(static_cast<int>(cdf_first));
    const auto& cdf = grid.cell_count.cdf();
    for (std::size_t k = 0; k < cdf.size(); ++k)
      texel(cdf_first + k / 4, static_cast<int>(k % 4)) = cdf[k];
  }
  // 1 to 4 channels: a vec4 mean and a 4 x 4 array of the mixing matrix's rows, zero-padded
  // (noise.glsl); more: arrays of the channels' means and the channels^2 mixing matrix
  // (colour_channels.glsl).
  const int channels = model.channels();
  glsl.channels = channels;
  const bool beyond_vec4 = channels > 4;
  std::vector<float> mixing(beyond_vec4 ? model.mixing().size() : 16, 0.0f);
  for (std::size_t i = 0; i < model.mixing().size(); ++i) mixing[i] = model.mixing()[i];

  std::string& text = glsl.constants;
  const auto constant = [&](const char* type, const char* name, const std::string& value) {
    text += "const " + std::string(type) + " " + name + " = " + value + ";\n";
  };
  const auto glsl_uint = [](unsigned value) { return std::to_string(value) + "u"; };
  constant("int", "GABOR_CHANNELS", glsl_int(channels));
  constant("int", "GABOR_GRIDS", glsl_int(static_cast<int>(grids.size())));
  constant("int", "GABOR_GAUSSIANS", glsl_int(static_cast<int>(gaussians)));
  constant("int", "GABOR_DATA_WIDTH", glsl_int(GaborGlsl::kDataWidth));
  if (beyond_vec4)
    text += glsl_array("float", "GABOR_MEAN", model.mean(), glsl_float);
  else
    constant("vec4", "GABOR_MEAN", glsl_vec4(model.mean()));
  text += glsl_array("float", "GABOR_MIXING", std::span<const float>(mixing), glsl_float);
  text += glsl_array("int", "GABOR_GRID_CHANNEL", std::span<const int>(channel), glsl_int);
  text += glsl_array("int", "GABOR_GRID_FIRST", std::span<const int>(first), glsl_int);
  text += glsl_array("uint", "GABOR_GRID_COUNT", std::span<const unsigned>(count), glsl_uint);
  text +=
      glsl_array("float", "GABOR_GRID_BANDWIDTH", std::span<const float>(bandwidth), glsl_float);
  text +=
      glsl_array("float", "GABOR_GRID_AMPLITUDE", std::span<const float>(amplitude), glsl_float);
  text += glsl_array("float", "GABOR_GRID_MIN_FREQUENCY_SQUARED",
                     std::span<const float>(min_frequency_squared), glsl_float);
  if (precision == GlslPrecision::doubles) {
    text += glsl_array("double", "GABOR_GRID_RADIUS", std::span<const double>(radius), glsl_double);
    text += glsl_array("double", "GABOR_GRID_CELL_SIZE", std::span<const double>(cell_size),
                       glsl_double);
  } else {
    // The floats the C++ rounds them to (cell_size_f in GaborModel::evaluate), and the size of
    // gabor_noise's per-grid arrays (never 0).
    const auto to_float = [](double value) { return glsl_float(static_cast<float>(value)); };
    text += glsl_array("float", "GABOR_GRID_RADIUS", std::span<const double>(radius), to_float);
    text +=
        glsl_array("float", "GABOR_GRID_CELL_SIZE", std::span<const double>(cell_size), to_float);
    constant("int", "GABOR_GRID_ARRAY", glsl_int(std::max(1, static_cast<int>(grids.size()))));
  }
  text +=
      glsl_array("uint", "GABOR_GRID_POISSON_CHUNKS", std::span<const unsigned>(chunks), glsl_uint);
  text += glsl_array("int", "GABOR_GRID_CDF", std::span<const int>(cdf_texel), glsl_int);
  return glsl;
}

std::string gabor_library_source(const GaborGlsl& glsl) {
  const std::string reader =
      "uniform sampler2D stochtex_gabor_data;\nvec4 gabor_texel(int index) {\n  return "
      "texelFetch(stochtex_gabor_data, ivec2(index % GABOR_DATA_WIDTH, index / "
      "GABOR_DATA_WIDTH), 0);\n}\n";
  return random_source() + float_math_source() +
         glsl_constants(Twin<gabor::GaborModel>::kConstants, glsl.precision) + glsl.constants +
         reader +
         glsl_precision_variant(
             shader_source("methods/gabor/evaluate.glsl") +
                 shader_source(glsl.channels > 4 ? "methods/gabor/colour_channels.glsl"
                                                 : "methods/gabor/colour.glsl") +
                 shader_source("methods/gabor/noise.glsl"),
             glsl.precision);
}

std::optional<SurfaceShader> Twin<gabor::GaborModel>::surface_shader(
    const gabor::GaborModel& model, const SurfaceOptions& options) {
  // The data image, read with texelFetch rather than from a storage buffer (SurfaceShader).
  GaborGlsl glsl = gabor_glsl(model);
  const auto shader = [&](SurfaceShader made) {
    made.textures.push_back({"gabor_data", std::move(glsl.data)});
    return made;
  };
  if (options.mapping == SurfaceMapping::triplanar_linear)
    return shader(
        triplanar_linear_shader(gabor::GaborModel::kMethodName, gabor_library_source(glsl), {}));
  if (options.mapping != SurfaceMapping::surface) return std::nullopt;
  // Each grid's 3-D process (GaborModel::surface_grid): its CDF appended to the data image.
  const auto texels = glsl.data.pixels();
  std::vector<float> data(texels.begin(), texels.end());
  std::vector<int> cdf_texel;
  std::vector<unsigned> chunks;
  std::vector<double> cell_size;
  for (const gabor::GaborModel::Grid& grid : model.grids()) {
    const gabor::GaborModel::SurfaceGrid surface =
        gabor::GaborModel::surface_grid(grid, options.surface_mni);
    cdf_texel.push_back(static_cast<int>(data.size() / 4));
    chunks.push_back(surface.count.chunks());
    cell_size.push_back(surface.cell_size);
    data.insert(data.end(), surface.count.cdf().begin(), surface.count.cdf().end());
  }
  constexpr std::size_t kRow = std::size_t{GaborGlsl::kDataWidth} * 4;
  glsl.data = ImageF(GaborGlsl::kDataWidth, static_cast<int>((data.size() + kRow - 1) / kRow), 4);
  std::copy(data.begin(), data.end(), glsl.data.pixels().begin());
  std::string& text = glsl.constants;
  text += glsl_array("int", "GABOR_SURFACE_CDF", std::span<const int>(cdf_texel), glsl_int);
  text += glsl_array("uint", "GABOR_SURFACE_POISSON_CHUNKS", std::span<const unsigned>(chunks),
                     [](unsigned value) { return std::to_string(value) + "u"; });
  text += glsl_array("double", "GABOR_SURFACE_CELL_SIZE", std::span<const double>(cell_size),
                     glsl_double);
  text += "const double GABOR_SURFACE_AMPLITUDE_GAIN = " +
          glsl_double(gabor::GaborModel::surface_amplitude_gain(options.surface_mni)) + ";\n";
  std::string library =
      gabor_library_source(glsl) + shader_source("methods/gabor/surface_impulse.glsl") +
      "#define SURFACE_CONTEXT GaborSurfacePoint\n" + shader_source("gl/surface_process.glsl") +
      shader_source("methods/gabor/surface.glsl");
  return shader(SurfaceShader{std::move(library),
                              {},
                              "stochtex_gabor_surface(position, normal, tangent, dpdx, dpdy, seed)",
                              {}});
}

ExportParts Twin<gabor::GaborModel>::shader(const gabor::GaborModel& model, ShaderVariant variant) {
  const bool fast = variant == ShaderVariant::fast;
  GaborGlsl glsl = gabor_glsl(model, fast ? GlslPrecision::floats : GlslPrecision::doubles);
  std::vector<ShaderTexture> images;
  images.push_back({"gabor_data", std::move(glsl.data)});
  ExportParts parts{
      gabor::GaborModel::kMethodName,
      "Gabor noise",
      std::string("Gabor noise by example") + (fast ? ", fast variant (" : " (") +
          std::to_string(model.channels()) + " channels, " + std::to_string(model.grids().size()) +
          " grids, " + std::to_string(static_cast<int>(model.impulses())) + " impulses)",
      gabor_library_source(glsl),
      std::move(images),
      std::string("Texel i < GABOR_GAUSSIANS of `gabor_data.exr` is Gaussian i (frequency x, "
                  "y, alias probability,\nalias index); then 24 texels per grid hold its "
                  "Poisson table. ") +
          (fast ? "The shader is float-only (the `--gl-filter hardware` GLSL): positions are "
                  "split per grid\ninto a cell and a float offset, so it runs where doubles "
                  "are missing (GLSL ES, HLSL, Metal),\nwithin about 1e-3 of the image's "
                  "standard deviation of the exact variant."
                : "The shader uses double precision\n(core since OpenGL 4.0) for positions "
                  "and cell corners, as the CPU reference does."),
      variant};
  // Beyond 4 channels (a material), noise.glsl's gabor_channels instead of the vec4
  // entry point.
  if (model.channels() > 4) parts.channels_function = "gabor_channels";
  return parts;
}

}  // namespace stochtex::gl
