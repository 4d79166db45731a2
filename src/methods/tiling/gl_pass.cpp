// Histogram-preserving tiling on the GL renderer: the program (compiled with the model's
// constants) and the storage buffer of its pyramid and tables; for --gl-filter hardware, the fast
// export's program and textures (hardware.glsl, gl_data.cpp). A model whose channels go through
// T^-1 in groups of their own (a material) renders its Gaussian in chunks of up to 4 channels,
// then each group's T^-1 (groups.glsl).

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
// tables as a 3-D texture), made on first use. `output` is the defines of blend.glsl and
// render.glsl, before the library: empty for a model of one image, a chunk's place in the result
// for TilingGroupsPass.
class TilingPass final : public Pass {
 public:
  TilingPass(const tiling::TilingModel& model, const std::string& output)
      : model_(model),
        glsl_(tiling_glsl(model)),
        output_(output),
        exact_(std::string("#version 450\n") + output + tiling_library_source(glsl_) +
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
      if (!hardware_) {
        ExportParts parts = Twin<tiling::TilingModel>::shader(model_, ShaderVariant::fast);
        parts.library = output_ + parts.library;
        hardware_ =
            std::make_unique<ExportedProgram>(parts, shader_source("methods/tiling/render.glsl"));
      }
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
  std::string output_;
  Program exact_;
  Buffer data_;
  std::unique_ptr<ExportedProgram> hardware_;
  const Program* active_ = &exact_;
};

// Channels [first, first + count) of the Gaussian of `model` as a model of their own: the same
// lattice, controls and pyramid levels (the pyramid is built channel by channel, so its levels
// are the model's channels), with the variance-preserving blend of eq. (13) in place of the
// histogram-preserving one: the same blend without T^-1, which the groups pass applies. The
// variance and linear blends stay themselves (they have no T^-1).
tiling::TilingModel gaussian_chunk(const tiling::TilingModel& model, int first, int count) {
  const tiling::TilingData& d = model.data();
  std::vector<float> gaussian;
  gaussian.reserve(d.gaussian.size() / static_cast<std::size_t>(d.channels) *
                   static_cast<std::size_t>(count));
  for (auto pixel = d.gaussian.begin(); pixel != d.gaussian.end(); pixel += d.channels)
    gaussian.insert(gaussian.end(), pixel + first, pixel + first + count);
  tiling::TilingData chunk = d;  // the sizes, the lattice and the controls; the arrays below
  chunk.channels = count;
  chunk.gaussian = std::move(gaussian);
  chunk.blend_mean =
      std::vector<float>(d.blend_mean.begin() + first, d.blend_mean.begin() + first + count);
  if (chunk.blend == tiling::Blend::histogram) chunk.blend = tiling::Blend::variance;
  chunk.lut = std::vector<float>();
  chunk.tables = std::vector<float>();
  chunk.colour_basis = std::vector<float>();
  chunk.colour_mean = std::vector<float>();
  chunk.groups = std::vector<tiling::GroupSpec>();
  chunk.height_blend = 0.0;  // applied by groups.glsl to the patches kept apart
  chunk.height_channel = -1;
  return tiling::TilingModel(std::move(chunk));
}

// render.glsl's defines for the chunk of `model` from channel `first`: its place in the result
// and, for the first chunk of a model with T^-1, the levels of detail that groups.glsl reads;
// with the patches kept apart, where they go.
std::string chunk_output(const tiling::TilingModel& model, int first) {
  std::string text = "#define TILING_RESULT_STRIDE " + std::to_string(model.channels()) +
                     "\n#define TILING_RESULT_FIRST " + std::to_string(first) + "\n";
  if (first == 0 && !model.layout().groups.empty()) text += "#define TILING_RESULT_LEVELS\n";
  if (blends_patches_apart(model))
    text += "#define TILING_PATCH_OUTPUT\n#define TILING_PATCH_STRIDE " +
            std::to_string(patch_stride(model)) + "\n";
  return text;
}

// A model that renders_in_groups: one TilingPass per chunk of up to 4 channels of its Gaussian
// (gaussian_chunk), each drawing the same patches (same lattice, seed, offsets, rotations and
// levels) and writing its channels of every pixel, the first also each pixel's level of detail;
// then groups.glsl replaces the Gaussian by each group's T^-1 in place. --gl-filter hardware runs
// each chunk's fast program (a texture of the chunk's Gaussian); the groups' 1-D tables are read
// exactly on both paths, as the fast variant of an image reads its 1-D tables.
class TilingGroupsPass final : public Pass {
 public:
  explicit TilingGroupsPass(const tiling::TilingModel& model)
      : patch_stride_(blends_patches_apart(model) ? patch_stride(model) : 0) {
    // First: it refuses a group without a GLSL case.
    if (!model.layout().groups.empty()) groups_ = std::make_unique<Groups>(model);
    for (int first = 0; first < model.channels(); first += 4)
      chunk_models_.push_back(gaussian_chunk(model, first, std::min(4, model.channels() - first)));
    for (std::size_t k = 0; k < chunk_models_.size(); ++k)
      chunks_.push_back(std::make_unique<TilingPass>(chunk_models_[k],
                                                     chunk_output(model, static_cast<int>(k) * 4)));
  }

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    for (const auto& chunk : chunks_) chunk->prepare(grid, seed, options);
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    if (groups_) {
      const std::size_t bytes = 2 * sizeof(float) * static_cast<std::size_t>(width) * height;
      if (bytes > levels_bytes_) {
        levels_ = std::make_unique<Buffer>(bytes);
        levels_bytes_ = bytes;
      }
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, levels_->id());
      if (patch_stride_ > 0) {
        const std::size_t patch_bytes = static_cast<std::size_t>(patch_stride_) * sizeof(float) *
                                        static_cast<std::size_t>(width) * height;
        if (patch_bytes > patches_bytes_) {
          patches_ = std::make_unique<Buffer>(patch_bytes);
          patches_bytes_ = patch_bytes;
        }
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, patches_->id());
      }
    }
    for (const auto& chunk : chunks_) chunk->dispatch(first_x, first_y, width, height, result);
    if (!groups_) return;
    // groups.glsl reads what the chunks wrote.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, groups_->data.id());
    run_tile(groups_->program, first_x, first_y, width, height, result);
  }

 private:
  // T^-1 of the groups: groups.glsl compiled with their constants, and the levels' 1-D tables.
  struct Groups {
    explicit Groups(const tiling::TilingModel& model)
        : glsl(tiling_groups_glsl(model)),
          program(tiling_groups_source(glsl)),
          data(glsl.data.size() * sizeof(float), glsl.data.data()) {
      check_gl("uploading the tiling groups");
    }
    TilingGlsl glsl;
    Program program;
    Buffer data;
  };

  std::vector<tiling::TilingModel> chunk_models_;  // TilingPass keeps a reference
  std::vector<std::unique_ptr<TilingPass>> chunks_;
  std::unique_ptr<Groups> groups_;
  // Each pixel's level and level blend from the first chunk, grown to the largest tile; with the
  // patches kept apart, their values (patch_stride_ floats a pixel, 0 otherwise).
  mutable std::unique_ptr<Buffer> levels_;
  mutable std::size_t levels_bytes_ = 0;
  int patch_stride_ = 0;
  mutable std::unique_ptr<Buffer> patches_;
  mutable std::size_t patches_bytes_ = 0;
};

}  // namespace

std::unique_ptr<Pass> Twin<tiling::TilingModel>::pass(const tiling::TilingModel& model) {
  if (renders_in_groups(model)) return std::make_unique<TilingGroupsPass>(model);
  return std::make_unique<TilingPass>(model, std::string());
}

}  // namespace stochtex::gl
