// Gabor noise on the GL renderer: the program (compiled with the model's per-grid constants) and
// the texture of its Gaussians, alias tables and Poisson tables.

#include <memory>
#include <string>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/gabor/gl_twin.hpp"

namespace stochtex::gl {
namespace {

// The Gabor noise evaluator's GPU state: the program (compiled with the model's per-grid
// constants) and the texture of its Gaussians, alias tables and Poisson tables.
class GaborPass final : public Pass {
 public:
  explicit GaborPass(const gabor::GaborModel& model)
      : glsl_(gabor_glsl(model)),
        program_(std::string("#version 450\n") + gabor_library_source(glsl_) +
                 shader_source("methods/gabor/render.glsl")) {
    data_ = data_texture(glsl_.data);
    program_.set("stochtex_gabor_data", 0);
    check_gl("uploading the gabor model");
  }
  ~GaborPass() { glDeleteTextures(1, &data_); }
  GaborPass(const GaborPass&) = delete;
  GaborPass& operator=(const GaborPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    // Positions are formed in double on the GPU as on the CPU (see gabor evaluate.glsl).
    glProgramUniform2d(program_.id(), program_.location("origin"), grid.origin.x, grid.origin.y);
    glProgramUniform1d(program_.id(), program_.location("scale"), grid.scale);
    program_.set("seed", static_cast<unsigned>(seed));
    program_.set("filtered", options.filter ? 1 : 0);
    check_gl("setting the gabor uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindTextureUnit(0, data_);
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  GaborGlsl glsl_;
  Program program_;
  GLuint data_ = 0;
};

}  // namespace

std::unique_ptr<Pass> Twin<gabor::GaborModel>::pass(const gabor::GaborModel& model) {
  return std::make_unique<GaborPass>(model);
}

}  // namespace stochtex::gl
