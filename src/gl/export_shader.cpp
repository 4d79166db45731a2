// `stochtex export-shader`: each method's GLSL library (the renderer's own code, with its data
// read from textures instead of storage buffers), the data as RGBA float images and a README.

#include <algorithm>
#include <sstream>
#include <string>
#include <variant>

#include "gl/gabor_glsl.hpp"
#include "gl/lrp_glsl.hpp"
#include "gl/texton_glsl.hpp"
#include "gl/tiling_glsl.hpp"
#include "model/model_data.hpp"
#include "stochtex/error.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex {
namespace {

// One exported texture: the image's file stem and the sampler uniform it binds to.
struct Texture {
  std::string stem;
  std::string sampler;
};

// README.md of an export: files, entry point, binding in plain OpenGL 4.5, and method notes.
std::string export_readme(const std::string& method, const std::string& title,
                          const std::string& glsl_file, const std::vector<Texture>& textures,
                          const std::string& notes) {
  std::ostringstream text;
  text << "# stochtex " << title << " shader\n\nFiles: `" << glsl_file
       << "` (the noise, self-contained)\nand";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " `" : ", `") << textures[i].stem << ".exr`";
  text << " (the model's data, RGBA float32).\nThe GLSL declares";
  for (const Texture& t : textures) text << " `uniform sampler2D " << t.sampler << ";`";
  text << " and exposes\n\n    vec4 stochtex_" << method
       << "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed);\n\n"
       << "`p` is in exemplar pixels (1 unit = 1 pixel of the analysed image), `dpdx`/`dpdy` its "
          "screen\nderivatives (`dFdx(p)`, `dFdy(p)` in a fragment shader; `vec2(0)` for no "
          "filtering) and `seed`\npicks the random pattern. The result's first `channels` "
          "components are the colour.\n\n"
       << "Binding it in a plain OpenGL 4.5 program (load each EXR with any EXR reader into "
          "`texels`,\n`width` x `height` RGBA floats):\n\n```c\n";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << "// " << textures[i].stem << ".exr on texture unit " << i << "\n"
         << "GLuint texture" << i << ";\nglCreateTextures(GL_TEXTURE_2D, 1, &texture" << i
         << ");\nglTextureStorage2D(texture" << i << ", 1, GL_RGBA32F, width, height);\n"
         << "glTextureSubImage2D(texture" << i
         << ", 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels);\nglBindTextureUnit(" << i
         << ", texture" << i << ");\nglProgramUniform1i(program, glGetUniformLocation(program, \""
         << textures[i].sampler << "\"), " << i << ");\n";
  text << "```\n\n```glsl\n#version 450\n// ... contents of " << glsl_file
       << " ...\nin vec2 uv;  // your surface coordinate\nout vec4 colour;\nvoid main() {\n"
          "  vec2 p = uv * 512.0;  // scaled to exemplar pixels\n  colour = vec4(stochtex_"
       << method << "(p, dFdx(p), dFdy(p), 7u).rgb, 1.0);\n}\n```\n\n"
       << "The textures are read with `texelFetch` (exact texels, no sampler filtering needed): "
          "the shader\ndoes its own interpolation and footprint filtering, the same as the CPU "
          "reference, whose output\nit matches to float rounding (tested).\n";
  if (!notes.empty()) text << "\n" << notes << "\n";
  return text.str();
}

std::string export_header(const std::string& what, const std::string& glsl_file,
                          const std::vector<Texture>& textures) {
  std::ostringstream text;
  text << "// " << what << " exported by `stochtex export-shader`.\n"
       << "// Paste or include after `#version 450`.\n// Bind";
  for (std::size_t i = 0; i < textures.size(); ++i)
    text << (i == 0 ? " " : ",\n// ") << textures[i].stem << ".exr as an RGBA32F texture to `"
         << textures[i].sampler << "`";
  text << ",\n// then call " << glsl_file.substr(0, glsl_file.size() - 5)
       << "(p, dpdx, dpdy, seed). See README.md.\n\n";
  return text.str();
}

ShaderExport export_texton(const texton::TextonModel& model) {
  gl::TextonGlsl glsl = gl::texton_glsl(model);
  const std::vector<Texture> textures = {{"texton_atlas", "stochtex_texton_atlas"}};
  ShaderExport result;
  result.glsl_file_name = "stochtex_texton.glsl";
  std::ostringstream what;
  what << "Texton noise (" << model.channels() << " channels, texton " << model.support() << "x"
       << model.support() << ", MNI " << model.mean_impacts() << ")";
  result.glsl =
      export_header(what.str(), result.glsl_file_name, textures) + gl::texton_library_source(glsl);
  result.images.push_back({"texton_atlas", std::move(glsl.atlas)});
  result.readme = export_readme("texton", "texton noise", result.glsl_file_name, textures,
                                "Keep |p| below ~1e4 for full float precision.");
  return result;
}

ShaderExport export_tiling(const tiling::TilingModel& model) {
  const gl::TilingGlsl glsl = gl::tiling_glsl(model);
  const std::vector<Texture> textures = {{"tiling_data", "stochtex_tiling_data"}};
  ShaderExport result;
  result.glsl_file_name = "stochtex_tiling.glsl";
  result.glsl = export_header("Histogram-preserving tiling and blending (" +
                                  std::to_string(model.channels()) + " channels)",
                              result.glsl_file_name, textures) +
                gl::tiling_library_source(glsl, gl::DataSource::textures);
  result.images.push_back({"tiling_data", gl::pack_rgba(glsl.data)});
  result.readme = export_readme(
      "tiling", "histogram-preserving tiling", result.glsl_file_name, textures,
      "`tiling_data.exr` is one float array (the exemplar's pyramid and look-up tables) packed "
      "four floats\nper texel, 1024 texels per row. Keep |p| below ~1e4 for full float "
      "precision.");
  return result;
}

ShaderExport export_lrp(const lrp::LrpModel& model) {
  const gl::LrpGlsl glsl = gl::lrp_glsl(model);
  constexpr std::uint32_t kExactFloatIntegers = 1u << 24;
  const auto too_large = [](std::uint32_t value) { return value >= kExactFloatIntegers; };
  if (std::any_of(glsl.substrata.begin(), glsl.substrata.end(), too_large) ||
      std::any_of(glsl.turbulence_substrata.begin(), glsl.turbulence_substrata.end(), too_large))
    throw Error(ErrorCode::invalid_input,
                "export-shader: this lrp model has more than 2^24 frequencies, which a float "
                "texture cannot index exactly");
  const std::vector<Texture> textures = {{"lrp_tables", "stochtex_lrp_tables"}};
  ShaderExport result;
  result.glsl_file_name = "stochtex_lrp.glsl";
  result.glsl =
      export_header("Local random-phase noise (" + std::to_string(model.channels()) + " channels)",
                    result.glsl_file_name, textures) +
      gl::lrp_library_source(glsl, gl::DataSource::textures);
  result.images.push_back({"lrp_tables", gl::lrp_tables_image(glsl)});
  result.readme = export_readme(
      "lrp", "local random-phase noise", result.glsl_file_name, textures,
      "`lrp_tables.exr` holds one table entry per texel, the tables one after the other from\n"
      "the texels LRP_SUBSTRATA_TEXEL, LRP_STRUCTURE_TEXEL, ... of the shader: frequencies\n"
      "(R, G: cycles per pixel; B: weight), sub-strata (R, G: first frequency and count), and\n"
      "for a model that keeps structure (ratio > 0) its cosines and turbulence tables. Keep |p|\n"
      "below ~1e4 for full float precision.");
  return result;
}

ShaderExport export_gabor(const gabor::GaborModel& model) {
  gl::GaborGlsl glsl = gl::gabor_glsl(model);
  const std::vector<Texture> textures = {{"gabor_data", "stochtex_gabor_data"}};
  ShaderExport result;
  result.glsl_file_name = "stochtex_gabor.glsl";
  result.glsl =
      export_header("Gabor noise by example (" + std::to_string(model.channels()) + " channels, " +
                        std::to_string(model.grids().size()) + " grids, " +
                        std::to_string(static_cast<int>(model.impulses())) + " impulses)",
                    result.glsl_file_name, textures) +
      gl::gabor_library_source(glsl);
  result.images.push_back({"gabor_data", std::move(glsl.data)});
  result.readme = export_readme(
      "gabor", "Gabor noise", result.glsl_file_name, textures,
      "Texel i < GABOR_GAUSSIANS of `gabor_data.exr` is Gaussian i (frequency x, y, alias "
      "probability,\nalias index); then 24 texels per grid hold its Poisson table. The shader "
      "uses double precision\n(core since OpenGL 4.0) for positions and cell corners, as the CPU "
      "reference does.");
  return result;
}

}  // namespace

ShaderExport export_shader(const Model& model) {
  if (model.empty()) throw std::invalid_argument("export_shader: the model is empty");
  return std::visit(
      [](const auto& method_model) -> ShaderExport {
        using Method = std::decay_t<decltype(method_model)>;
        if constexpr (std::is_same_v<Method, texton::TextonModel>)
          return export_texton(method_model);
        else if constexpr (std::is_same_v<Method, tiling::TilingModel>)
          return export_tiling(method_model);
        else if constexpr (std::is_same_v<Method, lrp::LrpModel>)
          return export_lrp(method_model);
        else
          return export_gabor(method_model);
      },
      model.data().model);
}

}  // namespace stochtex
