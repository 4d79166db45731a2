// Texton noise on the GL renderer: the program (compiled with the model's constants) and the texel
// atlas; for --gl-filter hardware (order-1 models), the fast export's program and texture
// (hardware.glsl, gl_data.cpp).

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/gl_twin.hpp"

namespace stochtex::gl {
namespace {

// The texton evaluator's GPU state: the program (compiled with the model's constants) and the
// texel atlas; for --gl-filter hardware (order-1 models), the program and texture of
// `export-shader --variant fast` (level 0 of the pyramid as a mip-mapped texture), made on first
// use.
class TextonPass final : public Pass {
 public:
  explicit TextonPass(const texton::TextonModel& model)
      : model_(model),
        glsl_(texton_glsl(model)),
        exact_(std::string("#version 450\n") + texton_library_source(glsl_) +
               shader_source("methods/texton/render.glsl")) {
    atlas_ = data_texture(glsl_.atlas);
    exact_.set("stochtex_texton_atlas", 0);
    check_gl("uploading the texton");
  }
  ~TextonPass() { glDeleteTextures(1, &atlas_); }
  TextonPass(const TextonPass&) = delete;
  TextonPass& operator=(const TextonPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    active_ = &exact_;
    if (options.texture_filter == GlFilter::hardware && has_fast_variant(model_)) {
      if (!hardware_)
        hardware_ = std::make_unique<ExportedProgram>(
            Twin<texton::TextonModel>::shader(model_, ShaderVariant::fast),
            shader_source("methods/texton/render.glsl"));
      active_ = &hardware_->program();
    }
    const Program& program = *active_;
    set_render_uniforms(program, model_, grid, seed, filter);
    program.set("filter_scale", hardware_footprint(grid, filter));
    check_gl("setting the texton uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    if (active_ == &exact_)
      glBindTextureUnit(0, atlas_);
    else
      hardware_->bind_textures();
    run_tile(*active_, first_x, first_y, width, height, result);
  }

 private:
  const texton::TextonModel& model_;
  TextonGlsl glsl_;
  Program exact_;
  GLuint atlas_ = 0;
  std::unique_ptr<ExportedProgram> hardware_;
  const Program* active_ = &exact_;
};

}  // namespace

std::array<double, 2> set_render_uniforms(const Program& program, const texton::TextonModel& shape,
                                          const Grid& grid, std::uint32_t seed, bool filter) {
  const int top_level = static_cast<int>(shape.pyramid().size()) - 1;
  const texton::FilterSetup setup =
      filter ? texton::filter_setup(Footprint{{grid.scale, 0.0}, {0.0, grid.scale}}, top_level)
             : texton::FilterSetup{};
  // The grid origin splits into a cell (64-bit here, its low 32 bits in the shader, as cell_key
  // uses them) and a small float offset: far origins are as precise as near ones.
  const double cell_size = shape.cell_size();
  const double origin_cell_x = std::floor(grid.origin.x / cell_size);
  const double origin_cell_y = std::floor(grid.origin.y / cell_size);
  program.set2("origin_cell", low_bits(origin_cell_x), low_bits(origin_cell_y));
  program.set2("origin_offset", static_cast<float>(grid.origin.x - origin_cell_x * cell_size),
               static_cast<float>(grid.origin.y - origin_cell_y * cell_size));
  program.set("scale", static_cast<float>(grid.scale));
  program.set("seed", static_cast<unsigned>(seed));
  program.set("filter_level", setup.level);
  program.set("filter_level_blend", setup.level_blend);
  program.set("filter_probes", setup.probes);
  program.set2("filter_probe_step", setup.probe_x, setup.probe_y);
  program.set("filter_fade", setup.fade);
  return {origin_cell_x, origin_cell_y};
}

std::unique_ptr<Pass> Twin<texton::TextonModel>::pass(const texton::TextonModel& model) {
  return std::make_unique<TextonPass>(model);
}

}  // namespace stochtex::gl
