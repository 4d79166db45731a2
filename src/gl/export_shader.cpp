// `stochtex export-shader`: each method's GLSL library (the renderer's own code, with its data
// read from textures instead of storage buffers; Twin::shader in src/methods/<m>/gl_data.cpp), the
// data as RGBA float images and a README written here the same for every method.

#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "gl/twin.hpp"
#include "model/model_data.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex {
namespace gl {
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

}  // namespace

ShaderExport assemble_export(ExportParts parts) {
  const std::string method(parts.method);
  std::vector<Texture> textures;
  for (const NamedImage& image : parts.images)
    textures.push_back({image.name, "stochtex_" + image.name});
  ShaderExport result;
  result.glsl_file_name = "stochtex_" + method + ".glsl";
  result.glsl = export_header(parts.what, result.glsl_file_name, textures) + parts.library;
  result.images = std::move(parts.images);
  result.readme = export_readme(method, parts.title, result.glsl_file_name, textures, parts.notes);
  return result;
}

}  // namespace gl

ShaderExport export_shader(const Model& model) {
  if (model.empty()) throw std::invalid_argument("export_shader: the model is empty");
  return std::visit(
      [](const auto& method_model) {
        return gl::Twin<std::decay_t<decltype(method_model)>>::shader(method_model);
      },
      model.data().model);
}

}  // namespace stochtex
