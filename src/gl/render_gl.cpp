#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "core/hash.hpp"
#include "gl/context.hpp"
#include "gl/gabor_glsl.hpp"
#include "gl/lrp_glsl.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "gl/texton_glsl.hpp"
#include "gl/tiling_glsl.hpp"
#include "methods/texton/evaluate.hpp"
#include "model/model_data.hpp"
#include "stochtex/error.hpp"
#include "stochtex/gpu.hpp"

namespace stochtex {
namespace {

using gl::Buffer;
using gl::check_gl;
using gl::Program;

// One method's GPU state, made once per model: prepare() sets a render's uniforms (and picks the
// program for options.texture_filter), dispatch() evaluates one tile of it into `result`. (A
// virtual call per dispatch, never per sample.)
class Pass {
 public:
  virtual ~Pass() = default;
  virtual void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) = 0;
  virtual void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                        const Buffer& result) const = 0;
};

// The footprint side given to textureGrad by --gl-filter hardware: the grid's scale over sqrt(3),
// so that the hardware's level of detail log2(scale / sqrt(3)) is the CPU pyramids' (see
// kLodBias in texton and tiling), or zero for point samples.
float hardware_footprint(const Grid& grid, bool filter) {
  return filter ? static_cast<float>(grid.scale / std::sqrt(3.0)) : 0.0f;
}

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

// An RGBA32F texture with a full mip chain for hardware filtering: `levels[l]` (RGBA texels of
// max(1, width >> l) x max(1, height >> l)) where the caller has the level, glGenerateTextureMipmap
// for the rest. Trilinear, anisotropic where available, `wrap` on both axes.
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

// `values` with `channels` floats per texel as RGBA (missing channels zero).
std::vector<float> to_rgba(const float* values, std::size_t texels, int channels) {
  std::vector<float> rgba(texels * 4, 0.0f);
  for (std::size_t i = 0; i < texels; ++i)
    for (int c = 0; c < channels; ++c)
      rgba[i * 4 + static_cast<std::size_t>(c)] =
          values[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)];
  return rgba;
}

// Runs `program` over width x height pixels of the grid, writing into `result` (binding 1).
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

// The texton evaluator's GPU state: the program (compiled with the model's constants) and the
// texel atlas; for --gl-filter hardware (order-1 models), a second program and level 0 of the
// pyramid as a mip-mapped texture, made on first use.
class TextonPass final : public Pass {
 public:
  explicit TextonPass(const texton::TextonModel& model)
      : model_(model),
        glsl_(gl::texton_glsl(model)),
        exact_(std::string("#version 450\n") + gl::texton_library_source(glsl_) +
               gl::kTextonRenderGlsl) {
    glCreateTextures(GL_TEXTURE_2D, 1, &atlas_);
    glTextureStorage2D(atlas_, 1, GL_RGBA32F, glsl_.atlas.width(), glsl_.atlas.height());
    glTextureSubImage2D(atlas_, 0, 0, 0, glsl_.atlas.width(), glsl_.atlas.height(), GL_RGBA,
                        GL_FLOAT, glsl_.atlas.pixels().data());
    exact_.set("stochtex_texton_atlas", 0);
    check_gl("uploading the texton");
  }
  ~TextonPass() {
    glDeleteTextures(1, &atlas_);
    glDeleteTextures(1, &texture_);
  }
  TextonPass(const TextonPass&) = delete;
  TextonPass& operator=(const TextonPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    active_ = &exact_;
    // Hardware bilinear reconstruction is the order-1 B-spline only: other orders stay exact.
    if (options.texture_filter == GlFilter::hardware && model_.order() == 1) {
      if (!hardware_) make_hardware();
      active_ = hardware_.get();
    }
    const Program& program = *active_;
    const int top_level = static_cast<int>(model_.pyramid().size()) - 1;
    const texton::FilterSetup setup =
        filter ? texton::filter_setup(Footprint{{grid.scale, 0.0}, {0.0, grid.scale}}, top_level)
               : texton::FilterSetup{};
    // The grid origin splits into a cell (64-bit here, its low 32 bits in the shader, as
    // cell_key uses them) and a small float offset: far origins are as precise as near ones.
    const double cell_size = model_.cell_size();
    const double origin_cell_x = std::floor(grid.origin.x / cell_size);
    const double origin_cell_y = std::floor(grid.origin.y / cell_size);
    const auto low_bits = [](double cell) {
      return static_cast<unsigned>(static_cast<std::uint64_t>(static_cast<std::int64_t>(cell)));
    };
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
    program.set("filter_scale", hardware_footprint(grid, filter));
    check_gl("setting the texton uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindTextureUnit(0, atlas_);
    glBindTextureUnit(1, texture_);
    run_tile(*active_, first_x, first_y, width, height, result);
  }

 private:
  void make_hardware() {
    hardware_ = std::make_unique<Program>(
        std::string("#version 450\n#define TEXTON_TEXTURE_FILTER\n") +
        gl::texton_library_source(glsl_) + gl::kTextonHardwareGlsl + gl::kTextonRenderGlsl);
    const texton::PyramidLevel& base = model_.pyramid().front();
    const std::size_t texels = static_cast<std::size_t>(base.stride) * base.stride;
    texture_ = mipmapped_texture(base.stride, base.stride,
                                 {to_rgba(base.coefficients.data(), texels, model_.channels())},
                                 GL_CLAMP_TO_BORDER);
    glTextureParameterf(texture_, GL_TEXTURE_MAX_LOD,
                        static_cast<float>(model_.pyramid().size() - 1));
    hardware_->set("stochtex_texton_atlas", 0);
    hardware_->set("stochtex_texton_texture", 1);
    check_gl("uploading the texton texture");
  }

  const texton::TextonModel& model_;
  gl::TextonGlsl glsl_;
  Program exact_;
  GLuint atlas_ = 0;
  std::unique_ptr<Program> hardware_;
  GLuint texture_ = 0;
  const Program* active_ = &exact_;
};

// The tiling evaluator's GPU state: the program (compiled with the model's constants) and the
// storage buffer of its pyramid and tables; for --gl-filter hardware, a second program, the
// Gaussianised exemplar as a mip-mapped texture and T^-1's 3-D tables as a 3-D texture, made on
// first use.
class TilingPass final : public Pass {
 public:
  explicit TilingPass(const tiling::TilingModel& model)
      : model_(model),
        glsl_(gl::tiling_glsl(model)),
        exact_(std::string("#version 450\n") + gl::tiling_library_source(glsl_) +
               gl::kTilingRenderGlsl),
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
    constexpr double kInverseSqrt3 = 0.57735026918962576;
    const double edge = model_.lattice_edge();
    const double skewed_x = (grid.origin.x - grid.origin.y * kInverseSqrt3) / edge;
    const double skewed_y = (2.0 * kInverseSqrt3 * grid.origin.y) / edge;
    const double cell_x = std::floor(skewed_x);
    const double cell_y = std::floor(skewed_y);
    const auto low_bits = [](double cell) {
      return static_cast<unsigned>(static_cast<std::uint64_t>(static_cast<std::int64_t>(cell)));
    };
    const tiling::Point2f wrapped =
        tiling::wrap_position(grid.origin, model_.data().width, model_.data().height);
    program.set2("origin_cell", low_bits(cell_x), low_bits(cell_y));
    program.set2("origin_skewed", static_cast<float>(skewed_x - cell_x),
                 static_cast<float>(skewed_y - cell_y));
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
        gl::tiling_library_source(glsl_) + gl::kTilingHardwareGlsl + gl::kTilingRenderGlsl);
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
  gl::TilingGlsl glsl_;
  Program exact_;
  Buffer data_;
  std::unique_ptr<Program> hardware_;
  GLuint exemplar_ = 0;
  GLuint lut_ = 0;
  const Program* active_ = &exact_;
};

// The LRP evaluator's GPU state: the program (compiled with the model's constants) and the
// frequency and sub-stratum tables.
class LrpPass final : public Pass {
 public:
  explicit LrpPass(const lrp::LrpModel& model)
      : model_(model),
        glsl_(gl::lrp_glsl(model)),
        program_(std::string("#version 450\n") + gl::lrp_library_source(glsl_) +
                 gl::kLrpRenderGlsl),
        frequencies_(glsl_.frequencies.size() * sizeof(float), glsl_.frequencies.data()),
        substrata_(glsl_.substrata.size() * sizeof(std::uint32_t), glsl_.substrata.data()),
        structure_(glsl_.structure.size() * sizeof(float), glsl_.structure.data()),
        turbulence_frequencies_(glsl_.turbulence_frequencies.size() * sizeof(float),
                                glsl_.turbulence_frequencies.data()),
        turbulence_substrata_(glsl_.turbulence_substrata.size() * sizeof(std::uint32_t),
                              glsl_.turbulence_substrata.data()) {
    check_gl("uploading the lrp model");
  }

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    // Per stratum, as the CPU evaluator: the nearest lattice node of the origin (in double) and
    // the stratum's stream cell_key(channel, stratum, seed, phases).
    const lrp::LrpData& d = model_.data();
    const std::size_t strata = d.strata_table.size();
    std::vector<GLuint> nodes(2 * strata);
    std::vector<float> offsets(2 * strata);
    std::vector<GLuint> seeds(strata);
    for (std::size_t s = 0; s < strata; ++s) {
      const double inverse_spacing = 1.0 / static_cast<double>(d.strata_table[s].spacing);
      const double u = grid.origin.x * inverse_spacing;
      const double v = grid.origin.y * inverse_spacing;
      const double node_x = std::floor(u + 0.5);
      const double node_y = std::floor(v + 0.5);
      nodes[2 * s] =
          static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(node_x)));
      nodes[2 * s + 1] =
          static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(node_y)));
      offsets[2 * s] = static_cast<float>(u - node_x);
      offsets[2 * s + 1] = static_cast<float>(v - node_y);
      seeds[s] = cell_key(static_cast<std::int64_t>(s) / d.strata,
                          static_cast<std::int64_t>(s) % d.strata, seed, Stream::phases);
    }
    const auto count = static_cast<GLsizei>(strata);
    glProgramUniform2uiv(program_.id(), program_.location("origin_node"), count, nodes.data());
    glProgramUniform2fv(program_.id(), program_.location("origin_offset"), count, offsets.data());
    glProgramUniform1uiv(program_.id(), program_.location("stratum_seed"), count, seeds.data());
    program_.set("scale", static_cast<float>(grid.scale));
    program_.set("filtered", filter ? 1 : 0);
    if (!d.structure.empty()) prepare_structure(grid, seed);
    check_gl("setting the lrp uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, frequencies_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, substrata_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, structure_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, turbulence_frequencies_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, turbulence_substrata_.id());
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  const lrp::LrpModel& model_;
  gl::LrpGlsl glsl_;
  Program program_;
  Buffer frequencies_;
  Buffer substrata_;
  Buffer structure_;
  Buffer turbulence_frequencies_;
  Buffer turbulence_substrata_;

  // Section 5: the grid origin's far part, formed in double as add_structure does (the structure
  // is T-periodic, placement blocks and turbulence nodes are 64-bit indices).
  void prepare_structure(const Grid& grid, std::uint32_t seed) const {
    const lrp::StructureData& st = model_.data().structure;
    const double period = st.period;
    program_.set2("structure_origin",
                  static_cast<float>(grid.origin.x - period * std::floor(grid.origin.x / period)),
                  static_cast<float>(grid.origin.y - period * std::floor(grid.origin.y / period)));
    const double gx = grid.origin.x / (0.5 * period) - 0.5;
    const double gy = grid.origin.y / (0.5 * period) - 0.5;
    const double base_x = std::floor(gx);
    const double base_y = std::floor(gy);
    program_.set2(
        "placement_block",
        static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(base_x))),
        static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(base_y))));
    program_.set2("placement_offset", static_cast<float>(gx - base_x),
                  static_cast<float>(gy - base_y));
    program_.set("seed", static_cast<unsigned>(seed));
    const std::size_t strata = st.turbulence_strata.size();
    if (strata == 0) return;
    std::vector<GLuint> nodes(2 * strata);
    std::vector<float> offsets(2 * strata);
    std::vector<GLuint> seeds(2 * strata);
    for (std::size_t t = 0; t < strata; ++t) {
      const double u = grid.origin.x / static_cast<double>(st.turbulence_strata[t].spacing);
      const double v = grid.origin.y / static_cast<double>(st.turbulence_strata[t].spacing);
      const double node_x = std::floor(u + 0.5);
      const double node_y = std::floor(v + 0.5);
      nodes[2 * t] =
          static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(node_x)));
      nodes[2 * t + 1] =
          static_cast<GLuint>(static_cast<std::uint64_t>(static_cast<std::int64_t>(node_y)));
      offsets[2 * t] = static_cast<float>(u - node_x);
      offsets[2 * t + 1] = static_cast<float>(v - node_y);
      for (std::size_t axis = 0; axis < 2; ++axis)
        seeds[axis * strata + t] =
            cell_key(lrp::kTurbulenceStreamBase + static_cast<std::int64_t>(axis),
                     static_cast<std::int64_t>(t), seed, Stream::phases);
    }
    const auto count = static_cast<GLsizei>(strata);
    glProgramUniform2uiv(program_.id(), program_.location("turbulence_node"), count, nodes.data());
    glProgramUniform2fv(program_.id(), program_.location("turbulence_offset"), count,
                        offsets.data());
    glProgramUniform1uiv(program_.id(), program_.location("turbulence_seed"), 2 * count,
                         seeds.data());
  }
};

// The Gabor noise evaluator's GPU state: the program (compiled with the model's per-grid
// constants) and the texture of its Gaussians, alias tables and Poisson tables.
class GaborPass final : public Pass {
 public:
  explicit GaborPass(const gabor::GaborModel& model)
      : glsl_(gl::gabor_glsl(model)),
        program_(std::string("#version 450\n") + gl::gabor_library_source(glsl_) +
                 gl::kGaborRenderGlsl) {
    glCreateTextures(GL_TEXTURE_2D, 1, &data_);
    glTextureStorage2D(data_, 1, GL_RGBA32F, glsl_.data.width(), glsl_.data.height());
    glTextureSubImage2D(data_, 0, 0, 0, glsl_.data.width(), glsl_.data.height(), GL_RGBA, GL_FLOAT,
                        glsl_.data.pixels().data());
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
  gl::GaborGlsl glsl_;
  Program program_;
  GLuint data_ = 0;
};

}  // namespace

bool gl_supports(std::string_view method) {
  return method == texton::TextonModel::kMethodName || method == tiling::TilingModel::kMethodName ||
         method == lrp::LrpModel::kMethodName || method == gabor::GaborModel::kMethodName;
}

struct GlRenderer::Impl {
  gl::Context context;
  const Model model;
  std::unique_ptr<Pass> pass;
  GLuint timer = 0;
  double milliseconds = 0.0;

  explicit Impl(const Model& m) : model(m) {
    std::visit(
        [&](const auto& method_model) {
          using Method = std::decay_t<decltype(method_model)>;
          if constexpr (std::is_same_v<Method, texton::TextonModel>)
            pass = std::make_unique<TextonPass>(method_model);
          else if constexpr (std::is_same_v<Method, tiling::TilingModel>)
            pass = std::make_unique<TilingPass>(method_model);
          else if constexpr (std::is_same_v<Method, lrp::LrpModel>)
            pass = std::make_unique<LrpPass>(method_model);
          else if constexpr (std::is_same_v<Method, gabor::GaborModel>)
            pass = std::make_unique<GaborPass>(method_model);
        },
        model.data().model);
    glCreateQueries(GL_TIME_ELAPSED, 1, &timer);
  }
  ~Impl() {
    pass.reset();
    glDeleteQueries(1, &timer);
  }
};

namespace {

const Model& checked_model(const Model& model) {
  if (model.empty()) throw std::invalid_argument("GlRenderer: the model is empty");
  if (!gl_supports(model.method()))
    throw Error(ErrorCode::invalid_input, "the gl backend has no GLSL evaluator for method '" +
                                              std::string(model.method()) + "'; use --backend cpu");
  return model;
}

}  // namespace

GlRenderer::GlRenderer(const Model& model) : impl_(new Impl(checked_model(model))) {}

GlRenderer::~GlRenderer() = default;

void GlRenderer::render(const Grid& grid, std::uint32_t seed, ImageView<float> out,
                        const GpuRenderOptions& options) {
  const int channels = impl_->model.channels();
  if (out.width != grid.width || out.height != grid.height || out.channels != channels)
    throw std::invalid_argument("render_gl: the output view does not match the grid and model");
  constexpr std::int64_t kMaxPixelIndex = std::int64_t{1} << 30;
  if (std::abs(grid.first_pixel_x) + grid.width > kMaxPixelIndex ||
      std::abs(grid.first_pixel_y) + grid.height > kMaxPixelIndex)
    throw std::invalid_argument(
        "render_gl: the region's pixel indices exceed 2^30; move the origin instead");
  Pass& pass = *impl_->pass;
  pass.prepare(grid, seed, options);
  const int tile_width = std::clamp(options.tile_size, 1, std::max(grid.width, 1));
  const int tile_height = std::clamp(options.tile_size, 1, std::max(grid.height, 1));
  const Buffer result(static_cast<std::size_t>(tile_width) * tile_height * channels *
                      sizeof(float));
  std::vector<float> values(static_cast<std::size_t>(tile_width) * tile_height * channels);
  impl_->milliseconds = 0.0;
  for (int y0 = 0; y0 < grid.height; y0 += tile_height)
    for (int x0 = 0; x0 < grid.width; x0 += tile_width) {
      const int w = std::min(tile_width, grid.width - x0);
      const int h = std::min(tile_height, grid.height - y0);
      glBeginQuery(GL_TIME_ELAPSED, impl_->timer);
      pass.dispatch(grid.first_pixel_x + x0, grid.first_pixel_y + y0, w, h, result);
      glEndQuery(GL_TIME_ELAPSED);
      GLuint64 nanoseconds = 0;
      glGetQueryObjectui64v(impl_->timer, GL_QUERY_RESULT, &nanoseconds);
      impl_->milliseconds += static_cast<double>(nanoseconds) * 1e-6;
      const std::size_t count = static_cast<std::size_t>(w) * h * channels;
      glGetNamedBufferSubData(result.id(), 0, static_cast<GLsizeiptr>(count * sizeof(float)),
                              values.data());
      check_gl("running the shader");
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < channels; ++c)
            out.at(x0 + x, y0 + y, c) = values[(static_cast<std::size_t>(y) * w + x) * channels +
                                               static_cast<std::size_t>(c)];
    }
}

double GlRenderer::last_gpu_milliseconds() const {
  return impl_->milliseconds;
}

std::string GlRenderer::device() const {
  return impl_->context.description();
}

void render_gl(const Model& model, const Grid& grid, std::uint32_t seed, ImageView<float> out,
               const GpuRenderOptions& options) {
  GlRenderer(model).render(grid, seed, out, options);
}

std::string gl_device_description() {
  return gl::Context().description();
}

}  // namespace stochtex
