// The generic pieces of the methods' GPU twins (twin.hpp): dispatching a tile and the textures the
// passes upload.

#include "gl/twin.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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
  return filter ? static_cast<float>(grid.scale / std::sqrt(3.0)) : 0.0f;
}

GLuint mipmapped_texture(int width, int height, const std::vector<std::vector<float>>& levels,
                         GLenum wrap) {
  int count = 1;
  while ((std::max(width, height) >> count) > 0) ++count;
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, count, GL_RGBA32F, width, height);
  for (std::size_t l = 0; l < levels.size() && static_cast<int>(l) < count; ++l)
    glTextureSubImage2D(texture, static_cast<GLint>(l), 0, 0, std::max(1, width >> l),
                        std::max(1, height >> l), GL_RGBA, GL_FLOAT, levels[l].data());
  if (static_cast<int>(levels.size()) < count) {
    glTextureParameteri(texture, GL_TEXTURE_BASE_LEVEL, static_cast<GLint>(levels.size()) - 1);
    glGenerateTextureMipmap(texture);
    glTextureParameteri(texture, GL_TEXTURE_BASE_LEVEL, 0);
  }
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTextureParameterf(texture, GL_TEXTURE_MAX_ANISOTROPY, max_anisotropy());
  return texture;
}

std::vector<float> to_rgba(const float* values, std::size_t texels, int channels) {
  std::vector<float> rgba(texels * 4, 0.0f);
  for (std::size_t i = 0; i < texels; ++i)
    for (int c = 0; c < channels; ++c)
      rgba[i * 4 + static_cast<std::size_t>(c)] =
          values[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)];
  return rgba;
}

GLuint data_texture(const ImageF& image) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, image.width(), image.height());
  glTextureSubImage2D(texture, 0, 0, 0, image.width(), image.height(), GL_RGBA, GL_FLOAT,
                      image.pixels().data());
  return texture;
}

}  // namespace stochtex::gl
