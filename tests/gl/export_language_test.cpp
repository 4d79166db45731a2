// `export-shader --variant exact|fast --language ...`: every exported file of every export case, in
// both variants and every language, through glslang's front end (GLSL 4.50, GLSL ES 3.00 and HLSL;
// there is no Metal compiler here, so the Metal source is only checked for its signature), and
// the GLSL and GLSL ES exports of both variants run in a fragment shader on an OpenGL 4.5 and an
// OpenGL ES 3.0 context and matched against the CPU.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gl/context.hpp"
#include "gl/cross_compile.hpp"
#include "gl/gl_support.hpp"
#include "gl/program.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::export_language_test {
namespace {

using namespace gl_test;

constexpr std::uint32_t kSeed = 11;

// The caller's side of the GLSL and GLSL ES exports: a fragment shader evaluating the function at
// each pixel centre of a grid of `scale` from the origin, as render() samples it.
std::string fragment_shader(const std::string& version, const std::string& text,
                            const std::string& method) {
  std::string library = text;
  if (library.find("\nshader_type spatial;\n") != std::string::npos) {
    // Godot's spatial shader: its uniforms and functions, as GLSL ES 3.00.
    library.erase(library.find("\nvoid fragment()"));
    library.erase(0, library.find("\nshader_type spatial;\n") + 22);
    for (const char* uniform :
         {"uniform float stochtex_texture_scale", "uniform int stochtex_seed"}) {
      const std::size_t at = library.find(uniform);
      library.erase(at, library.find('\n', at) - at);
    }
  }
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

// How many identifiers of `source` are names that no GLSL gave: SPIRV-Cross's `_<id>` of a value
// without a name, and glslang's copies of a call's arguments, `param` and `param_<n>`
// (src/gl/spirv_names.hpp names both).
int unnamed_identifiers(std::string_view source) {
  const auto digits = [](std::string_view text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  int count = 0;
  for (std::size_t at = 0; at < source.size();) {
    if (!word(source[at])) {
      ++at;
      continue;
    }
    std::size_t end = at;
    while (end < source.size() && word(source[end])) ++end;
    const std::string_view name = source.substr(at, end - at);
    if ((name.starts_with('_') && digits(name.substr(1))) || name == "param" ||
        (name.starts_with("param_") && digits(name.substr(6))))
      ++count;
    at = end;
  }
  return count;
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

// `image` (3 channels) with a fourth channel of 1.
ImageF to_rgba(const ImageF& image) {
  ImageF rgba(image.width(), image.height(), 4);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      for (int c = 0; c < 3; ++c) rgba.at(x, y, c) = image.at(x, y, c);
      rgba.at(x, y, 3) = 1.0f;
    }
  return rgba;
}

// Makes `id` the texture of `t` as the README's table says (format, 2-D or 3-D, generated
// mip-maps, filter, wrap), with the file's values (bytes, 16-bit samples or floats), using only
// calls OpenGL 4.5 and OpenGL ES 3.2 share (llvmpipe's ES context is 3.2, which has the 16-bit
// formats of EXT_texture_norm16 and the border clamp that WebGL2 lacks).
void bind_texture(GLuint id, const ShaderTexture& t) {
  // Three channels as RGBA (the READMEs' formats for GLSL ES, HLSL and Metal): OpenGL ES
  // generates mip-maps only for colour-renderable formats, which RGB16 and RGB32F are not.
  const ImageF rgba = t.image.channels() == 3 ? to_rgba(t.image) : t.image;
  const auto channel = static_cast<std::size_t>(rgba.channels() - 1);
  constexpr std::array<std::array<GLenum, 4>, 3> kFormats = {{
      {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F},
      {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8},
      {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16},
  }};
  constexpr std::array<GLenum, 4> kLayouts = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  const GLenum format = kFormats[static_cast<std::size_t>(t.encoding)][channel];
  const int width = rgba.width();
  const int height = rgba.height() / t.depth;
  const GLenum target = t.depth == 1 ? GL_TEXTURE_2D : GL_TEXTURE_3D;
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint16_t> shorts;
  const void* data = rgba.pixels().data();
  GLenum type = GL_FLOAT;
  if (t.encoding == TextureEncoding::png8) {
    for (const float v : rgba.pixels())
      bytes.push_back(static_cast<std::uint8_t>(std::lround(v * 255.0f)));
    data = bytes.data();
    type = GL_UNSIGNED_BYTE;
  } else if (t.encoding == TextureEncoding::png16) {
    for (const float v : rgba.pixels())
      shorts.push_back(static_cast<std::uint16_t>(std::lround(v * 65535.0f)));
    data = shorts.data();
    type = GL_UNSIGNED_SHORT;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glBindTexture(target, id);
  if (t.depth == 1) {
    glTexStorage2D(target, t.mip_levels, format, width, height);
    glTexSubImage2D(target, 0, 0, 0, width, height, kLayouts[channel], type, data);
  } else {
    glTexStorage3D(target, t.mip_levels, format, width, height, t.depth);
    glTexSubImage3D(target, 0, 0, 0, 0, width, height, t.depth, kLayouts[channel], type, data);
  }
  if (t.mip_levels > 1) glGenerateMipmap(target);
  if (t.float_bytes) {
    // Godot's grey + alpha texture (LA8) reads as (L, L, L, A).
    for (const GLenum swizzle : {GL_TEXTURE_SWIZZLE_R, GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B})
      glTexParameteri(target, swizzle, GL_RED);
    glTexParameteri(target, GL_TEXTURE_SWIZZLE_A, GL_GREEN);
  }
  constexpr std::array<GLenum, 3> kMinFilters = {GL_NEAREST, GL_LINEAR, GL_LINEAR_MIPMAP_LINEAR};
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER,
                  static_cast<GLint>(kMinFilters[static_cast<std::size_t>(t.filter)]));
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER,
                  t.filter == TextureFilter::nearest ? GL_NEAREST : GL_LINEAR);
  constexpr std::array<GLenum, 3> kWraps = {GL_CLAMP_TO_EDGE, GL_CLAMP_TO_BORDER, GL_REPEAT};
  for (const GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(target, axis, static_cast<GLint>(kWraps[static_cast<std::size_t>(t.wrap)]));
}

// Renders the exported function over size x size pixels at `scale` with the export's images bound
// as the README asks (bind_texture), on the current context (OpenGL 4.5 or ES 3.x: only calls
// both have).
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
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(i));
    bind_texture(textures[i], files.textures[i]);
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

// The fixture (FIXTURES_SETUP gl_shared under CTest): the export cases' models, made once per run
// for the GL tests that use them (case_models()).
TEST(GlShared, ExportCaseModels) {
  const auto folder = test_support::shared_folder();
  if (!folder) GTEST_SKIP() << "STOCHTEX_TEST_CACHE is not set: the tests make their own";
  std::filesystem::create_directories(*folder);
  const std::vector<ExportCase> cases = export_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::array<Model, 2> models = make_case_models(cases[k]);
    // The srgb file last: case_models() loads both once it exists.
    save_model(models[0], case_model_path(*folder, k, false));
    save_model(models[1], case_model_path(*folder, k, true));
  }
}

bool uses_doubles(const ExportCase& c) {
  return std::string(c.method) == "gabor";
}

TEST(ExportLanguage, EveryFileCompilesInItsLanguage) {
  const std::vector<ExportCase> cases = export_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const ExportCase& c = cases[k];
    const std::string method = c.method;
    for (const Model& model : case_models()[k])
      for (const ShaderVariant variant : {ShaderVariant::exact, ShaderVariant::fast})
        for (const gl::LanguageRow& row : gl::kLanguageRows) {
          const ShaderLanguage language = row.language;
          const std::string name(row.name);
          SCOPED_TRACE(testing::Message()
                       << method << (variant == ShaderVariant::fast ? " fast " : " exact ") << name
                       << (&model == &case_models()[k][1] ? " srgb" : " data"));
          const ShaderExportOptions options{variant, language};
          if (language != ShaderLanguage::glsl && variant == ShaderVariant::exact &&
              uses_doubles(c)) {
            // Gabor's exact shader keeps positions and cell corners in double precision.
            try {
              export_shader(model, options);
              ADD_FAILURE() << "the export did not refuse the language";
            } catch (const std::invalid_argument& e) {
              const std::string message = e.what();
              EXPECT_NE(message.find("the gabor shader"), std::string::npos) << message;
              EXPECT_NE(message.find(row.title), std::string::npos) << message;
              EXPECT_NE(message.find("double precision"), std::string::npos) << message;
              EXPECT_NE(message.find("--variant fast"), std::string::npos) << message;
              EXPECT_NE(message.find("--language glsl"), std::string::npos) << message;
            }
            continue;
          }
          const ShaderExport files = export_shader(model, options);
          // The README names every data file the export holds.
          for (const ShaderTexture& t : files.textures) {
            std::string quoted = t.file_name();
            quoted.insert(quoted.begin(), '`');
            quoted.push_back('`');
            EXPECT_NE(files.readme.find(quoted), std::string::npos) << t.name;
          }
          // lrp and texton mixing export their exact shader for both variants.
          const bool fast = variant == ShaderVariant::fast && c.method != std::string_view("lrp") &&
                            c.method != std::string_view("texton_mix");
          if (fast) {
            EXPECT_NE(files.readme.find("fast variant"), std::string::npos);
          }
          // It ends with each engine's import settings, the exact variant's for texelFetch
          // (Godot's: its own, in its .import files).
          if (language != ShaderLanguage::godot) {
            EXPECT_NE(files.readme.find("Importing the data files, engine by engine."),
                      std::string::npos);
            EXPECT_EQ(files.readme.find("with one mip level (the shader reads texels with "
                                        "`texelFetch`)") != std::string::npos,
                      !fast);
          }
          const std::string extension(row.extension);
          EXPECT_EQ(files.shader.name, "stochtex_" + method + extension);
          // One signature in every language, the parameter names kept by SPIRV-Cross (GLSL ES:
          // highp is the default precision, so no qualifier is written); Metal's then takes each
          // texture and sampler (and, for the fast variant, the library's private variables).
          const std::vector<std::string> signatures = {
              "vec4 stochtex_" + method + "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)",
              "vec4 stochtex_" + method + "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)",
              "float4 stochtex_" + method + "(float2 p, float2 dpdx, float2 dpdy, uint seed)",
              "float4 stochtex_" + method +
                  "(thread const float2& p, thread const float2& dpdx, thread const float2& dpdy, "
                  "thread const uint& seed, ",
              "vec4 stochtex_" + method + "(vec2 p, vec2 dpdx, vec2 dpdy, uint seed)"};
          const std::string& signature = signatures[static_cast<std::size_t>(language)];
          EXPECT_NE(files.shader.text.find(signature), std::string::npos) << signature;
          EXPECT_NE(files.readme.find(signature), std::string::npos) << signature;
          if (language == ShaderLanguage::msl) {
            const std::size_t start = files.shader.text.find(signature);
            const std::string line =
                files.shader.text.substr(start, files.shader.text.find('\n', start) - start);
            for (const ShaderTexture& t : files.textures) {
              std::string parameters = t.depth == 1 ? "texture2d" : "texture3d";
              parameters += "<float> stochtex_" + t.name + ", sampler stochtex_" + t.name + "Smplr";
              EXPECT_NE(line.find(parameters), std::string::npos) << parameters;
            }
          }
          for (const char* entry : {"void main(", "frag_main", "main0("})
            EXPECT_EQ(files.shader.text.find(entry), std::string::npos) << "an entry point is left";
          // The manifest names the files and each texture with its settings.
          const nlohmann::json manifest = nlohmann::json::parse(files.manifest);
          EXPECT_EQ(manifest["format"], "stochtex-shader-export");
          EXPECT_EQ(manifest["language"], name);
          EXPECT_EQ(manifest["entry"], "stochtex_" + method);
          EXPECT_EQ(manifest["shader"], files.shader.name);
          EXPECT_EQ(manifest.contains("shader_graph"), language == ShaderLanguage::hlsl);
          EXPECT_EQ(manifest["outputs"][0]["colour"],
                    &model == &case_models()[k][1] ? "linear" : "data");
          ASSERT_EQ(manifest["textures"].size(), files.textures.size());
          for (std::size_t t = 0; t < files.textures.size(); ++t) {
            const ShaderTexture& texture = files.textures[t];
            const nlohmann::json& entry = manifest["textures"][t];
            EXPECT_EQ(entry["uniform"], "stochtex_" + texture.name);
            EXPECT_EQ(entry["file"], texture.file_name());
            EXPECT_EQ(entry["channels"], texture.image.channels());
            EXPECT_EQ(entry["height"].get<int>() * texture.depth, texture.image.height());
            EXPECT_EQ(entry["mip_levels"], texture.mip_levels);
            EXPECT_EQ(entry["filter"], std::string(filter_name(texture.filter)));
            EXPECT_EQ(entry["wrap"], std::string(wrap_name(texture.wrap)));
          }
          // Every argument's copy is named after its parameter (spirv_names.hpp).
          if (language != ShaderLanguage::glsl) {
            EXPECT_EQ(files.shader.text.find("param_"), std::string::npos);
          }
          switch (language) {
            case ShaderLanguage::glsl:
              EXPECT_EQ(gl::front_end_errors(
                            fragment_shader("#version 450", files.shader.text, method), language),
                        "");
              break;
            case ShaderLanguage::essl:
              EXPECT_EQ(
                  gl::front_end_errors(
                      fragment_shader("#version 300 es", files.shader.text, method), language),
                  "");
              break;
            case ShaderLanguage::hlsl:
              EXPECT_EQ(
                  gl::front_end_errors(hlsl_shader(files.shader.text, method, false), language),
                  "");
              ASSERT_EQ(files.wrappers.size(), 1u);
              EXPECT_EQ(files.wrappers[0].name, "stochtex_" + method + "_shadergraph.hlsl");
              EXPECT_EQ(
                  gl::front_end_errors(hlsl_shader(files.wrappers[0].text, method, true), language),
                  "");
              break;
            case ShaderLanguage::msl:
              break;  // no Metal compiler on Linux
            case ShaderLanguage::godot: {
              // No Godot front end here (tests/godot runs Godot itself; the text runs as GLSL ES
              // below): the files the README names, each data file with its import settings.
              std::vector<std::string> names;
              for (const TextFile& file : files.wrappers) names.push_back(file.name);
              for (const std::string& expected :
                   {"stochtex_" + method + "_canvas.shader", "stochtex_" + method + ".tscn",
                    "stochtex_" + method + ".gdshader"})
                EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
              for (const ShaderTexture& t : files.textures) {
                // Texel-read floats as bytes in grey + alpha PNGs, filtered data as OpenEXR.
                const bool bytes = t.filter == TextureFilter::nearest;
                EXPECT_EQ(t.float_bytes, bytes) << t.name;
                EXPECT_EQ(t.encoding, bytes ? TextureEncoding::png8 : TextureEncoding::exr_float32)
                    << t.name;
                EXPECT_EQ(t.image.channels() == 2, bytes) << t.name;
                EXPECT_NE(t.wrap, TextureWrap::clamp_to_border) << t.name;
                EXPECT_NE(std::find(names.begin(), names.end(), t.file_name() + ".import"),
                          names.end())
                    << t.name;
              }
              EXPECT_NE(files.shader.text.find("\nshader_type spatial;\n"), std::string::npos);
              for (const char* missing : {"struct ", "#define", "0x", "^="})
                EXPECT_EQ(files.shader.text.find(missing), std::string::npos) << missing;
              break;
            }
          }
          if (language != ShaderLanguage::hlsl && language != ShaderLanguage::godot) {
            EXPECT_TRUE(files.wrappers.empty());
          }
        }
  }
}

TEST(ExportLanguage, CrossCompiledLibrariesKeepTheGlslNames) {
  // A library whose SPIR-V has each unnamed kind: a constant array, a call's result, copies of
  // its arguments, a `?:`'s variable.
  const std::string library =
      "const float TEST_TABLE[3] = float[](0.5, 1.5, -2.5);\n"
      "float test_scaled(float x, int k) { return x * TEST_TABLE[k]; }\n"
      "vec4 stochtex_test(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {\n"
      "  float a = test_scaled(p.x, int(seed % 3u));\n"
      "  float b = p.y > 0.0 ? test_scaled(p.y, 1) : length(dpdy);\n"
      "  return vec4(a, b, test_scaled(length(dpdx), 2), 1.0);\n"
      "}\n";
  for (const ShaderLanguage language :
       {ShaderLanguage::essl, ShaderLanguage::hlsl, ShaderLanguage::msl}) {
    SCOPED_TRACE(gl::language_row(language).name);
    const std::string source = gl::cross_compile(library, "stochtex_test", "test", language);
    EXPECT_EQ(gl::cross_compile(library, "stochtex_test", "test", language), source);
    EXPECT_EQ(unnamed_identifiers(source), 0) << source;
    EXPECT_NE(source.find("TEST_TABLE[k]"), std::string::npos) << source;
    EXPECT_NE(source.find("test_scaled(x, k)"), std::string::npos) << source;
    EXPECT_NE(source.find("b_value"), std::string::npos) << source;
  }
  // A method's export: tiling's HLSL names its level table as the GLSL does, and is the same
  // bytes when exported again.
  const Model& tiling = case_models()[1][0];
  const ShaderExportOptions hlsl{ShaderVariant::exact, ShaderLanguage::hlsl};
  const std::string text = export_shader(tiling, hlsl).shader.text;
  EXPECT_NE(text.find("TILING_LEVEL_TEXELS["), std::string::npos);
  EXPECT_LE(unnamed_identifiers(text), 20);
  EXPECT_EQ(export_shader(tiling, hlsl).shader.text, text);
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

// The standard deviation of an image, all channels pooled.
double deviation(const ImageF& image) {
  double mean = 0.0;
  for (const float v : image.pixels()) mean += v;
  mean /= static_cast<double>(image.pixels().size());
  double variance = 0.0;
  for (const float v : image.pixels()) variance += (v - mean) * (v - mean);
  return std::sqrt(variance / static_cast<double>(image.pixels().size()));
}

// The GLSL and GLSL ES exports of both variants run in a fragment shader against the CPU
// reference.
//   exact (and lrp's and texton_mix's fast, which are exact): within the renderers' parity bound
//   (1e-4,
//     TextonMatchesTheCpuReference), which leaves room for drivers that fuse multiply-adds.
//     Measured on llvmpipe (Mesa 22.3.6): at most 2.4e-6 (tiling with transport 1), the same in
//     GLSL 4.50 and GLSL ES 3.00 for every case and scale.
//   fast texton and tiling: at scale 1 within 1/255 (hardware_filter_test.cpp,
//     TheFastExportIsWhatTheRendererRuns); minified they equal the CPU in distribution only, which
//     that file tests.
//   fast gabor: the float path's bound of gabor_gl_test.cpp, max 1e-3 of the CPU image's standard
//     deviation, at scales 1 and 3.
void expect_renders_match(gl::Api api, ShaderLanguage language, const std::string& version) {
  const gl::Context context(api);
  std::cout << context.description() << "\n";
  const std::vector<ExportCase> cases = export_cases();
  for (const ShaderVariant variant : {ShaderVariant::exact, ShaderVariant::fast})
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const ExportCase& c = cases[k];
      const std::string method = c.method;
      const bool fast = variant == ShaderVariant::fast;
      if (language != ShaderLanguage::glsl && !fast && uses_doubles(c)) continue;
      const bool filtered = fast && (method == "texton" || method == "tiling");
      for (const bool srgb : {false, true}) {
        const Model& model = case_models()[k][srgb ? 1 : 0];
        const ShaderExport files = export_shader(model, {variant, language});
        for (const float scale : {1.0f, 3.0f}) {
          if (filtered && scale != 1.0f) continue;
          const std::vector<float> values =
              render_fragments(files, version, c.method, c.size, scale);
          const float worst = worst_difference(model, values, c.size, scale);
          std::cout << version << (fast ? " fast " : " exact ") << c.method << " (" << c.exemplar
                    << (srgb ? ", srgb" : "") << "), scale " << scale
                    << ": max |cpu - fragment| = " << worst << "\n";
          float bound = 1e-4f;
          if (filtered) bound = 1.0f / 255.0f;
          if (fast && method == "gabor")
            bound = static_cast<float>(
                1e-3 * deviation(render_cpu(case_models()[k][0],
                                            Grid{{0.0, 0.0}, scale, c.size, c.size}, kSeed)));
          if (srgb) bound *= kDecodingSlope;
          EXPECT_LT(worst, bound) << c.method << (srgb ? " srgb" : "") << " scale " << scale;
        }
      }
    }
}

TEST(ExportLanguage, GlslRunsInAFragmentShaderAndMatchesTheCpu) {
  expect_renders_match(gl::Api::gl45, ShaderLanguage::glsl, "#version 450");
}

TEST(ExportLanguage, EsslRunsOnOpenGlEs30AndMatchesTheCpu) {
  expect_renders_match(gl::Api::gles30, ShaderLanguage::essl, "#version 300 es");
}

// Godot's text is GLSL ES 3.00 but for its first line, its fragment() and its uniforms'
// initialisers: run as such, it shows what the rewrites of godot_shader.cpp compute, apart from
// Godot (tests/godot runs it in Godot 3.2.3 itself).
TEST(ExportLanguage, GodotTextRunsOnOpenGlEs30AndMatchesTheCpu) {
  expect_renders_match(gl::Api::gles30, ShaderLanguage::godot,
                       "#version 300 es\nprecision highp float;\nprecision highp int;\n"
                       "precision highp sampler2D;\nprecision highp sampler3D;");
}

}  // namespace
}  // namespace stochtex::export_language_test
