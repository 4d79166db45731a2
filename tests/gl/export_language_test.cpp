// `export-shader --language`: every exported file of every export case, in every language, through
// glslang's front end (GLSL 4.50, GLSL ES 3.00 and HLSL; there is no Metal compiler here, so the
// Metal source is only checked for its signature), and the GLSL and GLSL ES exports run in a
// fragment shader on an OpenGL 4.5 and an OpenGL ES 3.0 context and matched against the CPU.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/context.hpp"
#include "gl/cross_compile.hpp"
#include "gl/gl_support.hpp"
#include "gl/program.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

using namespace gl_test;

constexpr std::uint32_t kSeed = 11;

// The caller's side of the GLSL and GLSL ES exports: a fragment shader evaluating the function at
// each pixel centre of a grid of `scale` from the origin, as render() samples it.
std::string fragment_shader(const std::string& version, const std::string& library,
                            const std::string& method) {
  return version + "\n" + library +
         "uniform highp float scale;\nuniform highp uint seed;\nout highp vec4 colour;\n"
         "void main() {\n  highp vec2 p = scale * gl_FragCoord.xy;\n  colour = stochtex_" +
         method + "(p, vec2(scale, 0.0), vec2(0.0, scale), seed);\n}\n";
}

// The caller's side of an HLSL export (`function` is stochtex_<method> or its _float wrapper).
std::string hlsl_shader(const std::string& library, const std::string& method, bool wrapper) {
  const std::string call = "stochtex_" + method + (wrapper ? "_float" : "");
  return library + "float4 main(float4 position : SV_Position) : SV_Target {\n" +
         "  float2 p = 2.0 * position.xy;\n" +
         (wrapper ? "  float4 colour;\n  " + call + "(p, ddx(p), ddy(p), 7u, colour);\n"
                  : "  float4 colour = " + call + "(p, ddx(p), ddy(p), 7u);\n") +
         "  return colour;\n}\n";
}

GLuint compile_stage(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  std::string log(4096, '\0');
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  EXPECT_EQ(ok, GL_TRUE) << log.c_str();
  return shader;
}

// Renders the exported function over size x size pixels at `scale` with the export's images bound
// as RGBA32F textures of one level and nearest filtering (what the README asks for), on the
// current context (OpenGL 4.5 or ES 3.0: only calls both have).
std::vector<float> render_fragments(const ShaderExport& files, const std::string& version,
                                    const std::string& method, int size, float scale) {
  const std::string vertex = version +
                             "\nvoid main() {\n  gl_Position = vec4(float((gl_VertexID & 1) << 2) "
                             "- 1.0, float((gl_VertexID & 2) << 1) - 1.0, 0.0, 1.0);\n}\n";
  const GLuint program = glCreateProgram();
  const GLuint vertex_shader = compile_stage(GL_VERTEX_SHADER, vertex);
  const GLuint fragment =
      compile_stage(GL_FRAGMENT_SHADER, fragment_shader(version, files.shader.text, method));
  glAttachShader(program, vertex_shader);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  EXPECT_EQ(linked, GL_TRUE);
  glUseProgram(program);

  std::vector<GLuint> textures(files.textures.size());
  glGenTextures(static_cast<GLsizei>(textures.size()), textures.data());
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const ImageF& image = files.textures[i].image;
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(i));
    glBindTexture(GL_TEXTURE_2D, textures[i]);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, image.width(), image.height());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width(), image.height(), GL_RGBA, GL_FLOAT,
                    image.pixels().data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glUniform1i(glGetUniformLocation(program, ("stochtex_" + files.textures[i].name).c_str()),
                static_cast<GLint>(i));
  }
  glUniform1f(glGetUniformLocation(program, "scale"), scale);
  glUniform1ui(glGetUniformLocation(program, "seed"), kSeed);

  GLuint target = 0, framebuffer = 0, vertex_array = 0;
  glGenRenderbuffers(1, &target);
  glBindRenderbuffer(GL_RENDERBUFFER, target);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, size, size);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target);
  EXPECT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
  glGenVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
  glViewport(0, 0, size, size);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  // Row y of the read-back is gl_FragCoord.y = y + 0.5, the grid's row y.
  std::vector<float> values(static_cast<std::size_t>(size) * size * 4);
  glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, values.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

  glDeleteVertexArrays(1, &vertex_array);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(1, &target);
  glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
  glDeleteShader(vertex_shader);
  glDeleteShader(fragment);
  glDeleteProgram(program);
  return values;
}

// The largest difference over the model's channels between a fragment render and the CPU's.
float worst_difference(const Model& model, const std::vector<float>& values, int size,
                       float scale) {
  const ImageF cpu = render_cpu(model, Grid{{0.0, 0.0}, scale, size, size}, kSeed);
  float worst = 0.0f;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < model.channels(); ++c)
        worst = std::max(
            worst, std::abs(cpu.at(x, y, c) - values[(static_cast<std::size_t>(y) * size + x) * 4 +
                                                     static_cast<std::size_t>(c)]));
  return worst;
}

// A model of each export case, analysed once.
const std::vector<Model>& case_models() {
  static const std::vector<Model> models = [] {
    std::vector<Model> made;
    for (const ExportCase& c : export_cases())
      made.push_back(
          analyze(c.method, read_image(kTextureDir + "/" + c.exemplar).view(), c.params, 0));
    return made;
  }();
  return models;
}

bool uses_doubles(const ExportCase& c) {
  return std::string(c.method) == "gabor";
}

TEST(ExportLanguage, EveryFileCompilesInItsLanguage) {
  const std::vector<ExportCase> cases = export_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const ExportCase& c = cases[k];
    const std::string method = c.method;
    for (const ShaderLanguage language :
         {ShaderLanguage::glsl, ShaderLanguage::essl, ShaderLanguage::hlsl, ShaderLanguage::msl}) {
      const std::string name(gl::language_row(language).option);
      SCOPED_TRACE(method + " " + name);
      if (language != ShaderLanguage::glsl && uses_doubles(c)) {
        // Gabor's exact shader keeps positions and cell corners in double precision.
        try {
          export_shader(case_models()[k], {.language = language});
          ADD_FAILURE() << "the export did not refuse the language";
        } catch (const std::invalid_argument& e) {
          const std::string message = e.what();
          EXPECT_NE(message.find("the gabor shader"), std::string::npos) << message;
          EXPECT_NE(message.find(gl::language_row(language).title), std::string::npos) << message;
          EXPECT_NE(message.find("double precision"), std::string::npos) << message;
          EXPECT_NE(message.find("--language glsl"), std::string::npos) << message;
        }
        continue;
      }
      const ShaderExport files = export_shader(case_models()[k], {.language = language});
      const std::string extension = language == ShaderLanguage::msl ? ".metal" : "." + name;
      EXPECT_EQ(files.shader.name, "stochtex_" + method + extension);
      // One signature in every language, the parameter names kept by SPIRV-Cross (GLSL ES: highp
      // is the default precision, so no qualifier is written).
      const std::vector<std::string> signatures = {
          "vec4 stochtex_" + method + "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)",
          "vec4 stochtex_" + method + "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)",
          "float4 stochtex_" + method + "(float2 p, float2 dpdx, float2 dpdy, uint seed)",
          "float4 stochtex_" + method +
              "(thread const float2& p, thread const float2& dpdx, thread const float2& dpdy, "
              "thread const uint& seed, texture2d<float> stochtex_" +
              files.textures.front().name + ", sampler stochtex_" + files.textures.front().name +
              "Smplr"};
      const std::string& signature = signatures[static_cast<std::size_t>(language)];
      EXPECT_NE(files.shader.text.find(signature), std::string::npos) << signature;
      EXPECT_NE(files.readme.find(signature), std::string::npos) << signature;
      for (const char* entry : {"void main(", "frag_main", "main0("})
        EXPECT_EQ(files.shader.text.find(entry), std::string::npos) << "an entry point is left";
      switch (language) {
        case ShaderLanguage::glsl:
          EXPECT_EQ(gl::front_end_errors(fragment_shader("#version 450", files.shader.text, method),
                                         language),
                    "");
          break;
        case ShaderLanguage::essl:
          EXPECT_EQ(gl::front_end_errors(
                        fragment_shader("#version 300 es", files.shader.text, method), language),
                    "");
          break;
        case ShaderLanguage::hlsl:
          EXPECT_EQ(gl::front_end_errors(hlsl_shader(files.shader.text, method, false), language),
                    "");
          ASSERT_EQ(files.wrappers.size(), 1u);
          EXPECT_EQ(files.wrappers[0].name, "stochtex_" + method + "_shadergraph.hlsl");
          EXPECT_EQ(
              gl::front_end_errors(hlsl_shader(files.wrappers[0].text, method, true), language),
              "");
          break;
        case ShaderLanguage::msl:
          break;  // no Metal compiler on Linux
      }
      if (language != ShaderLanguage::hlsl) {
        EXPECT_TRUE(files.wrappers.empty());
      }
    }
  }
}

TEST(ExportLanguage, FrontEndRefusesBrokenShaders) {
  // The check above can fail: glslang refuses what the targets lack.
  const std::string call = "void main() { uint high, low; umulExtended(1u, 2u, high, low); }\n";
  EXPECT_EQ(gl::front_end_errors("#version 450\n" + call, ShaderLanguage::glsl), "");
  EXPECT_NE(gl::front_end_errors("#version 300 es\n" + call, ShaderLanguage::essl), "");
  EXPECT_NE(gl::front_end_errors("float4 main() : SV_Target { return undefined_name; }\n",
                                 ShaderLanguage::hlsl),
            "");
}

// The GLSL and GLSL ES exports run in a fragment shader against the CPU reference, within the
// renderers' parity bound (1e-4, TextonMatchesTheCpuReference), which leaves room for drivers
// that fuse multiply-adds. Measured on llvmpipe (Mesa 22.3.6): at most 2.4e-6 (tiling with
// transport 1), the same in GLSL 4.50 and GLSL ES 3.00 for every case and scale.
void expect_renders_match(gl::Api api, ShaderLanguage language, const std::string& version) {
  const gl::Context context(api);
  std::cout << context.description() << "\n";
  const std::vector<ExportCase> cases = export_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const ExportCase& c = cases[k];
    if (language != ShaderLanguage::glsl && uses_doubles(c)) continue;
    const ShaderExport files = export_shader(case_models()[k], {.language = language});
    for (const float scale : {1.0f, 3.0f}) {
      const std::vector<float> values = render_fragments(files, version, c.method, c.size, scale);
      const float worst = worst_difference(case_models()[k], values, c.size, scale);
      std::cout << version << " " << c.method << " (" << c.exemplar << "), scale " << scale
                << ": max |cpu - fragment| = " << worst << "\n";
      EXPECT_LT(worst, 1e-4f) << c.method << " scale " << scale;
    }
  }
}

TEST(ExportLanguage, GlslRunsInAFragmentShaderAndMatchesTheCpu) {
  expect_renders_match(gl::Api::gl45, ShaderLanguage::glsl, "#version 450");
}

TEST(ExportLanguage, EsslRunsOnOpenGlEs30AndMatchesTheCpu) {
  expect_renders_match(gl::Api::gles30, ShaderLanguage::essl, "#version 300 es");
}

}  // namespace
}  // namespace stochtex
