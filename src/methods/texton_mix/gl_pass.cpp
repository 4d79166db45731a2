// Texton noise mixing on the GL renderer: the exact program (this method's GLSL library followed
// by texton render.glsl, whose texton_noise it renames texton_mix_noise) and its data textures,
// for both --gl-filter values (gl_twin.hpp).

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/texton/gl_twin.hpp"
#include "methods/texton_mix/gl_twin.hpp"
#include "stochtex/error.hpp"

namespace stochtex::gl {
namespace {

// The program's source: the field at the origin cell's corner as a uniform (the exported library
// has it as a constant for cell 0), then the library and texton's compute pass.
std::string program_source(const TextonMixGlsl& glsl) {
  return "#version 450\nuniform vec2 texton_mix_field;\n#define TEXTON_MIX_FIELD "
         "texton_mix_field\n" +
         glsl.library + "#define texton_noise texton_mix_noise\n" +
         shader_source("methods/texton/render.glsl");
}

// The textures, refused with one sentence where the GPU's largest texture is smaller.
std::vector<GLuint> upload(const std::vector<ShaderTexture>& textures) {
  GLint largest = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  for (const ShaderTexture& texture : textures)
    if (texture.image.width() > largest || texture.image.height() > largest)
      throw Error(
          ErrorCode::invalid_input,
          "the texton_mix model's " + texture.name + " (" + std::to_string(texture.image.width()) +
              "x" + std::to_string(texture.image.height()) +
              " texels) exceeds this GPU's largest texture (" + std::to_string(largest) +
              "); mix with fewer --steps or a smaller support, or render with --backend cpu");
  std::vector<GLuint> ids;
  for (const ShaderTexture& texture : textures) ids.push_back(data_texture(texture.image));
  return ids;
}

class TextonMixPass final : public Pass {
 public:
  explicit TextonMixPass(const texton_mix::TextonMixModel& model)
      : TextonMixPass(model, texton_mix_glsl(model)) {}
  TextonMixPass(const texton_mix::TextonMixModel& model, const TextonMixGlsl& glsl)
      : model_(model), program_(program_source(glsl)), textures_(upload(glsl.textures)) {
    for (std::size_t unit = 0; unit < glsl.textures.size(); ++unit)
      program_.set(("stochtex_" + glsl.textures[unit].name).c_str(), static_cast<int>(unit));
    check_gl("uploading the texton_mix textures");
  }
  ~TextonMixPass() { glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data()); }
  TextonMixPass(const TextonMixPass&) = delete;
  TextonMixPass& operator=(const TextonMixPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    // As texton noise's pass, and the field at the origin cell's corner in double.
    const texton::TextonModel& shape = model_.texton(0);
    const std::array<double, 2> origin_cell =
        set_render_uniforms(program_, shape, grid, seed, options.filter);
    const std::array<float, 2> field =
        texton_mix_field_at(model_.field(), origin_cell[0], origin_cell[1], shape.cell_size());
    program_.set2("texton_mix_field", field[0], field[1]);
    check_gl("setting the texton_mix uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    for (std::size_t unit = 0; unit < textures_.size(); ++unit)
      glBindTextureUnit(static_cast<GLuint>(unit), textures_[unit]);
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  const texton_mix::TextonMixModel& model_;
  Program program_;
  std::vector<GLuint> textures_;
};

}  // namespace

std::unique_ptr<Pass> Twin<texton_mix::TextonMixModel>::pass(
    const texton_mix::TextonMixModel& model) {
  return std::make_unique<TextonMixPass>(model);
}

}  // namespace stochtex::gl
