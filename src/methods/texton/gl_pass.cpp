// Texton noise on the GL renderer: the program (compiled with the model's constants) and the texel
// atlas, per chunk of 4 channels; for --gl-filter hardware (order-1 models), the fast export's
// program and texture (hardware.glsl, gl_data.cpp).

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/texton/evaluate.hpp"
#include "methods/texton/gl_twin.hpp"

namespace stochtex::gl {
namespace {

// One chunk of up to 4 channels of the exact evaluator: the program, compiled with the chunk's
// constants (texton_glsl), and its texel atlas. A model of 1 to 4 channels is one chunk; a wider
// one (a material, issue 18) renders chunk after chunk into the same result, each chunk drawing
// the same impulses (same cells, seed and draws) and writing its channels of every pixel
// (TEXTON_RESULT_STRIDE, TEXTON_RESULT_FIRST in render.glsl).
class TextonChunk {
 public:
  TextonChunk(const texton::TextonModel& model, int first_channel)
      : TextonChunk(texton_glsl(model, first_channel), result_layout(model, first_channel)) {}
  ~TextonChunk() { glDeleteTextures(1, &atlas_); }
  TextonChunk(const TextonChunk&) = delete;
  TextonChunk& operator=(const TextonChunk&) = delete;

  const Program& program() const { return program_; }
  GLuint atlas() const { return atlas_; }

 private:
  static std::string result_layout(const texton::TextonModel& model, int first_channel) {
    if (model.channels() <= 4) return {};
    return "#define TEXTON_RESULT_STRIDE " + std::to_string(model.channels()) +
           "\n#define TEXTON_RESULT_FIRST " + std::to_string(first_channel) + "\n";
  }

  TextonChunk(const TextonGlsl& glsl, const std::string& layout)
      : program_(std::string("#version 450\n") + layout + texton_library_source(glsl) +
                 shader_source("methods/texton/render.glsl")),
        atlas_(data_texture(glsl.atlas)) {
    program_.set("stochtex_texton_atlas", 0);
    check_gl("uploading the texton");
  }

  Program program_;
  GLuint atlas_ = 0;
};

// The texton evaluator's GPU state: the exact evaluator's chunks; for --gl-filter hardware
// (order-1 models of 1 to 4 channels), the program and texture of `export-shader --variant fast`
// (level 0 of the pyramid as a mip-mapped texture), made on first use.
class TextonPass final : public Pass {
 public:
  explicit TextonPass(const texton::TextonModel& model) : model_(model) {
    for (int first = 0; first < model.channels(); first += 4)
      chunks_.push_back(std::make_unique<TextonChunk>(model, first));
  }

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    hardware_active_ = false;
    if (options.texture_filter == GlFilter::hardware && has_fast_variant(model_)) {
      refuse_beyond_four_channels(model_, "--gl-filter hardware");
      if (!hardware_)
        hardware_ = std::make_unique<ExportedProgram>(
            Twin<texton::TextonModel>::shader(model_, ShaderVariant::fast),
            shader_source("methods/texton/render.glsl"));
      hardware_active_ = true;
      const Program& program = hardware_->program();
      set_render_uniforms(program, model_, grid, seed, filter);
      program.set("filter_scale", hardware_footprint(grid, filter));
    } else {
      for (const auto& chunk : chunks_) {
        set_render_uniforms(chunk->program(), model_, grid, seed, filter);
        chunk->program().set("filter_scale", hardware_footprint(grid, filter));
      }
    }
    check_gl("setting the texton uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    if (hardware_active_) {
      hardware_->bind_textures();
      run_tile(hardware_->program(), first_x, first_y, width, height, result);
      return;
    }
    for (const auto& chunk : chunks_) {
      glBindTextureUnit(0, chunk->atlas());
      run_tile(chunk->program(), first_x, first_y, width, height, result);
    }
  }

 private:
  const texton::TextonModel& model_;
  std::vector<std::unique_ptr<TextonChunk>> chunks_;
  std::unique_ptr<ExportedProgram> hardware_;
  bool hardware_active_ = false;
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
