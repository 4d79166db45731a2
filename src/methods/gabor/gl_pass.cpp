// Gabor noise on the GL renderer: the program (compiled with the model's per-grid constants) and
// the texture of its Gaussians, alias tables and Poisson tables; for --gl-filter hardware, the
// float-only program (the same GLSL without doubles, gabor evaluate.glsl), made on first use.

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/gabor/gl_twin.hpp"

namespace stochtex::gl {
namespace {

// The program of the Gabor evaluator in glsl.precision, from the model's data for it.
std::unique_ptr<Program> gabor_program(const GaborGlsl& glsl) {
  auto program = std::make_unique<Program>(
      std::string("#version 450\n") + gabor_library_source(glsl) +
      glsl_precision_variant(shader_source("methods/gabor/render.glsl"), glsl.precision));
  program->set("stochtex_gabor_data", 0);
  return program;
}

// The Gabor noise evaluator's GPU state: the program (compiled with the model's per-grid
// constants) and the texture of its Gaussians, alias tables and Poisson tables. The texture is
// already the smallest exact format: every texel's four 32-bit channels are used (a Gaussian's
// frequency x, y, alias probability and alias index, or four Poisson CDF values).
class GaborPass final : public Pass {
 public:
  explicit GaborPass(const gabor::GaborModel& model)
      : model_(model), glsl_(gabor_glsl(model)), exact_(gabor_program(glsl_)) {
    data_ = data_texture(glsl_.data);
    check_gl("uploading the gabor model");
  }
  ~GaborPass() { glDeleteTextures(1, &data_); }
  GaborPass(const GaborPass&) = delete;
  GaborPass& operator=(const GaborPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    active_ = exact_.get();
    if (options.texture_filter == GlFilter::hardware) {
      if (!float_) float_ = gabor_program(gabor_glsl(model_, GlslPrecision::floats));
      active_ = float_.get();
      prepare_float(grid);
    } else {
      // Positions are formed in double on the GPU as on the CPU (see gabor evaluate.glsl).
      glProgramUniform2d(exact_->id(), exact_->location("origin"), grid.origin.x, grid.origin.y);
      glProgramUniform1d(exact_->id(), exact_->location("scale"), grid.scale);
    }
    active_->set("seed", static_cast<unsigned>(seed));
    active_->set("filtered", options.filter ? 1 : 0);
    check_gl("setting the gabor uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindTextureUnit(0, data_);
    run_tile(*active_, first_x, first_y, width, height, result);
  }

 private:
  // The float program's position: per grid, the level-0 cell holding the grid origin (64-bit, two
  // words per axis) and the origin's offset from its corner, in double as GaborModel::evaluate
  // splits its positions.
  void prepare_float(const Grid& grid) const {
    const auto& grids = model_.grids();
    std::vector<GLuint> cells;
    std::vector<float> offsets;
    for (const gabor::GaborModel::Grid& g : grids)
      for (const double origin : {grid.origin.x, grid.origin.y}) {
        const double cell = std::floor(origin / g.cell_size);
        const auto index = static_cast<std::uint64_t>(static_cast<std::int64_t>(cell));
        cells.push_back(static_cast<GLuint>(index));
        cells.push_back(static_cast<GLuint>(index >> 32));
        offsets.push_back(static_cast<float>(origin - cell * g.cell_size));
      }
    const auto count = static_cast<GLsizei>(grids.size());
    if (count > 0) {
      glProgramUniform4uiv(float_->id(), float_->location("origin_cell"), count, cells.data());
      glProgramUniform2fv(float_->id(), float_->location("origin_offset"), count, offsets.data());
    }
    float_->set("scale", static_cast<float>(grid.scale));
  }

  const gabor::GaborModel& model_;
  GaborGlsl glsl_;
  std::unique_ptr<Program> exact_;
  GLuint data_ = 0;
  std::unique_ptr<Program> float_;
  const Program* active_ = exact_.get();
};

}  // namespace

std::unique_ptr<Pass> Twin<gabor::GaborModel>::pass(const gabor::GaborModel& model) {
  return std::make_unique<GaborPass>(model);
}

}  // namespace stochtex::gl
