// Histogram-preserving tiling on the GL renderer: the program (compiled with the model's
// constants) and the storage buffer of its pyramid and tables; for --gl-filter hardware, the fast
// export's program and textures (hardware.glsl, gl_data.cpp).

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/tiling/evaluate.hpp"
#include "methods/tiling/gl_twin.hpp"

namespace stochtex::gl {
namespace {

// The tiling evaluator's GPU state: the program (compiled with the model's constants) and the
// storage buffer of its pyramid and tables; for --gl-filter hardware, the program and textures of
// `export-shader --variant fast` (the Gaussianised exemplar as a mip-mapped texture, T^-1's 3-D
// tables as a 3-D texture), made on first use.
class TilingPass final : public Pass {
 public:
  explicit TilingPass(const tiling::TilingModel& model)
      : model_(model),
        glsl_(tiling_glsl(model)),
        exact_(std::string("#version 450\n") + tiling_library_source(glsl_) +
               shader_source("methods/tiling/render.glsl")),
        data_(glsl_.data.size() * sizeof(float), glsl_.data.data()) {
    check_gl("uploading the tiling model");
  }
  TilingPass(const TilingPass&) = delete;
  TilingPass& operator=(const TilingPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    active_ = &exact_;
    if (options.texture_filter == GlFilter::hardware) {
      if (!hardware_)
        hardware_ = std::make_unique<ExportedProgram>(
            Twin<tiling::TilingModel>::shader(model_, ShaderVariant::fast),
            shader_source("methods/tiling/render.glsl"));
      active_ = &hardware_->program();
    }
    const Program& program = *active_;
    const Footprint footprint{{grid.scale, 0.0}, {0.0, grid.scale}};
    const double width = tiling::TilingModel::footprint_width(filter ? &footprint : nullptr);
    const tiling::LevelOfDetail lod = model_.level_of_detail(width);
    // The origin's skewed lattice cell (low 32 bits, as cell_key takes them) and its fraction, and
    // the origin modulo the period, formed in double as triangle_lattice and wrap_position do.
    const Vec2d skewed = tiling::skewed_position(grid.origin, model_.lattice_edge());
    const double cell_x = std::floor(skewed.x);
    const double cell_y = std::floor(skewed.y);
    const tiling::Point2f wrapped =
        tiling::wrap_position(grid.origin, model_.data().width, model_.data().height);
    program.set2("origin_cell", low_bits(cell_x), low_bits(cell_y));
    program.set2("origin_skewed", static_cast<float>(skewed.x - cell_x),
                 static_cast<float>(skewed.y - cell_y));
    program.set2("origin_wrapped", wrapped.x, wrapped.y);
    program.set("scale", static_cast<float>(grid.scale));
    program.set("seed", static_cast<unsigned>(seed));
    program.set("lod_level", lod.level);
    program.set("lod_blend", lod.blend);
    program.set("footprint_width", static_cast<float>(width));
    program.set("filter_scale", hardware_footprint(grid, filter));
    check_gl("setting the tiling uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    if (active_ == &exact_)
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data_.id());
    else
      hardware_->bind_textures();
    run_tile(*active_, first_x, first_y, width, height, result);
  }

 private:
  const tiling::TilingModel& model_;
  TilingGlsl glsl_;
  Program exact_;
  Buffer data_;
  std::unique_ptr<ExportedProgram> hardware_;
  const Program* active_ = &exact_;
};

}  // namespace

std::unique_ptr<Pass> Twin<tiling::TilingModel>::pass(const tiling::TilingModel& model) {
  return std::make_unique<TilingPass>(model);
}

}  // namespace stochtex::gl
