// The generic pieces of the methods' GPU twins (twin.hpp): dispatching a tile and the textures the
// passes upload.

#include "gl/twin.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "gl/shaders.hpp"
#include "io/png_sample.hpp"
#include "model/model_data.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {
namespace {

// The anisotropy a mip-mapped texture may use: the driver's maximum up to 16 (GL 4.6 core or
// GL_EXT/ARB_texture_filter_anisotropic), 1 without the extension. Not on Mesa llvmpipe: its
// anisotropic sampling (Mesa 22.3) blurs even isotropic and magnified reads (measured: texels
// off by 0.03 at level 0, variance of the scale-8 renders 0.2-0.5x the trilinear one).
float max_anisotropy() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer != nullptr && std::string(renderer).find("llvmpipe") != std::string::npos)
    return 1.0f;
  GLint extensions = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
  bool available = false;
  for (GLint i = 0; i < extensions; ++i) {
    const std::string name(
        reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i))));
    available = available || name == "GL_EXT_texture_filter_anisotropic" ||
                name == "GL_ARB_texture_filter_anisotropic";
  }
  if (!available) return 1.0f;
  GLfloat maximum = 1.0f;
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maximum);
  return std::min(maximum, 16.0f);
}

}  // namespace

void run_tile(const Program& program, std::int64_t first_x, std::int64_t first_y, int width,
              int height, const Buffer& result) {
  program.set2("first_pixel", static_cast<int>(first_x), static_cast<int>(first_y));
  program.set2("dispatch_size", width, height);
  glUseProgram(program.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, result.id());
  glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
}

float hardware_footprint(const Grid& grid, bool filter) {
  return filter ? static_cast<float>(grid.scale) : 0.0f;
}

ImageF quantized(ImageF image, int bits) {
  const unsigned maximum = bits == 16 ? 65535 : 255;
  for (float& value : image.pixels())
    value = static_cast<float>(png_sample(value, maximum)) / static_cast<float>(maximum);
  return image;
}

GLuint texture_of(const ShaderTexture& texture) {
  const ImageF& image = texture.image;
  const auto channel = static_cast<std::size_t>(image.channels() - 1);
  constexpr std::array<std::array<GLenum, 4>, 3> kFormats = {{
      {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F},  // exr_float32
      {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8},          // png8
      {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16},      // png16
  }};
  constexpr std::array<GLenum, 4> kLayouts = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  const GLenum format = kFormats[static_cast<std::size_t>(texture.encoding)][channel];
  const int width = image.width();
  const int height = image.height() / texture.depth;
  GLuint id = 0;
  if (texture.depth == 1) {
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, texture.mip_levels, format, width, height);
    glTextureSubImage2D(id, 0, 0, 0, width, height, kLayouts[channel], GL_FLOAT,
                        image.pixels().data());
  } else {
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    glTextureStorage3D(id, texture.mip_levels, format, width, height, texture.depth);
    glTextureSubImage3D(id, 0, 0, 0, 0, width, height, texture.depth, kLayouts[channel], GL_FLOAT,
                        image.pixels().data());
  }
  if (texture.mip_levels > 1) glGenerateTextureMipmap(id);
  glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, texture.mip_levels - 1);
  const bool nearest = texture.filter == TextureFilter::nearest;
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER,
                      nearest                                   ? GL_NEAREST
                      : texture.filter == TextureFilter::mipmap ? GL_LINEAR_MIPMAP_LINEAR
                                                                : GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
  if (texture.filter == TextureFilter::mipmap)
    glTextureParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, max_anisotropy());
  constexpr std::array<GLenum, 3> kWraps = {GL_CLAMP_TO_EDGE, GL_CLAMP_TO_BORDER, GL_REPEAT};
  for (const GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(id, axis,
                        static_cast<GLint>(kWraps[static_cast<std::size_t>(texture.wrap)]));
  return id;
}

ProgramTextures::ProgramTextures(const Program& program, std::span<const ShaderTexture> textures) {
  for (const ShaderTexture& texture : textures) {
    program.set(("stochtex_" + texture.name).c_str(), static_cast<int>(ids_.size()));
    ids_.push_back(texture_of(texture));
  }
  check_gl("uploading the exported textures");
}

ProgramTextures::~ProgramTextures() {
  glDeleteTextures(static_cast<GLsizei>(ids_.size()), ids_.data());
}

void ProgramTextures::bind() const {
  for (std::size_t unit = 0; unit < ids_.size(); ++unit)
    glBindTextureUnit(static_cast<GLuint>(unit), ids_[unit]);
}

ExportedProgram::ExportedProgram(const ExportParts& parts, const std::string& render_source)
    : program_("#version 450\n" + parts.library + render_source),
      textures_(program_, parts.textures) {}

GLuint data_texture(const ImageF& image) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, image.width(), image.height());
  glTextureSubImage2D(texture, 0, 0, 0, image.width(), image.height(), GL_RGBA, GL_FLOAT,
                      image.pixels().data());
  return texture;
}

SurfaceShader triplanar_linear_shader(std::string_view method, std::string library,
                                      std::vector<float> data) {
  library += shader_source("gl/triplanar.glsl") + "#define STOCHTEX_PLANAR stochtex_" +
             std::string(method) + "\n" + shader_source("gl/triplanar_linear.glsl");
  return SurfaceShader{std::move(library),
                       std::move(data),
                       "stochtex_triplanar_linear(position, normal, dpdx, dpdy, parameter, seed)",
                       {}};
}

}  // namespace stochtex::gl
