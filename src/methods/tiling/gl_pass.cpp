// Histogram-preserving tiling on the GL renderer: the program (compiled with the model's
// constants) and the storage buffer of its pyramid and tables; for --gl-filter hardware, a second
// program with the exemplar and T^-1's tables as filtered textures (hardware.glsl).

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
// storage buffer of its pyramid and tables; for --gl-filter hardware, a second program, the
// Gaussianised exemplar as a mip-mapped texture and T^-1's 3-D tables as a 3-D texture, made on
// first use.
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
  ~TilingPass() {
    glDeleteTextures(1, &exemplar_);
    glDeleteTextures(1, &lut_);
  }
  TilingPass(const TilingPass&) = delete;
  TilingPass& operator=(const TilingPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    active_ = &exact_;
    if (options.texture_filter == GlFilter::hardware) {
      if (!hardware_) make_hardware();
      active_ = hardware_.get();
    }
    const Program& program = *active_;
    const Footprint footprint{{grid.scale, 0.0}, {0.0, grid.scale}};
    const tiling::LevelOfDetail lod = model_.level_of_detail(filter ? &footprint : nullptr);
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
    program.set("filter_scale", hardware_footprint(grid, filter));
    check_gl("setting the tiling uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data_.id());
    glBindTextureUnit(0, exemplar_);
    glBindTextureUnit(1, lut_);
    run_tile(*active_, first_x, first_y, width, height, result);
  }

 private:
  void make_hardware() {
    hardware_ = std::make_unique<Program>(
        std::string("#version 450\n#define TILING_TEXTURE_FILTER\n") +
        tiling_library_source(glsl_) + shader_source("methods/tiling/hardware.glsl") +
        shader_source("methods/tiling/render.glsl"));
    // The model's pyramid where its level sizes are GL's mip chain (power-of-two exemplars);
    // glGenerateTextureMipmap (a 2 x 2 box, as the model's) for the levels beyond.
    const int width = model_.data().width;
    const int height = model_.data().height;
    const int channels = model_.channels();
    std::vector<std::vector<float>> levels;
    for (int l = 0; l < model_.level_count(); ++l) {
      const tiling::MipLevel mip = model_.level(l);
      if (mip.width != std::max(1, width >> l) || mip.height != std::max(1, height >> l)) break;
      levels.push_back(
          to_rgba(mip.texels, static_cast<std::size_t>(mip.width) * mip.height, channels));
    }
    exemplar_ = mipmapped_texture(width, height, levels, GL_REPEAT);
    hardware_->set("stochtex_tiling_exemplar", 0);
    if (model_.layout().colour_lut && !model_.level_lut(0).empty()) {
      // Each level's 3-D table (lut_size^3 RGB, x fastest) as lut_size slices of one 3-D texture.
      const int n = model_.data().lut_size;
      glCreateTextures(GL_TEXTURE_3D, 1, &lut_);
      glTextureStorage3D(lut_, 1, GL_RGBA32F, n, n, n * model_.level_count());
      for (int l = 0; l < model_.level_count(); ++l) {
        const std::vector<float> rgba =
            to_rgba(model_.level_lut(l).data(), static_cast<std::size_t>(n) * n * n, 3);
        glTextureSubImage3D(lut_, 0, 0, 0, l * n, n, n, n, GL_RGBA, GL_FLOAT, rgba.data());
      }
      glTextureParameteri(lut_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(lut_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      for (const GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(lut_, axis, GL_CLAMP_TO_EDGE);
      hardware_->set("stochtex_tiling_lut", 1);
    }
    check_gl("uploading the tiling exemplar texture");
  }

  const tiling::TilingModel& model_;
  TilingGlsl glsl_;
  Program exact_;
  Buffer data_;
  std::unique_ptr<Program> hardware_;
  GLuint exemplar_ = 0;
  GLuint lut_ = 0;
  const Program* active_ = &exact_;
};

}  // namespace

std::unique_ptr<Pass> Twin<tiling::TilingModel>::pass(const tiling::TilingModel& model) {
  return std::make_unique<TilingPass>(model);
}

}  // namespace stochtex::gl
