#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "core/hash.hpp"
#include "gl/context.hpp"
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

// One method's GPU state, made once per model: prepare() sets a render's uniforms, dispatch()
// evaluates one tile of it into `result`. (A virtual call per dispatch, never per sample.)
class Pass {
 public:
  virtual ~Pass() = default;
  virtual void prepare(const Grid& grid, std::uint32_t seed, bool filter) const = 0;
  virtual void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                        const Buffer& result) const = 0;
};

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
// texel atlas.
class TextonPass final : public Pass {
 public:
  explicit TextonPass(const texton::TextonModel& model)
      : model_(model),
        glsl_(gl::texton_glsl(model)),
        program_(std::string("#version 450\n") + gl::texton_library_source(glsl_) +
                 gl::kTextonRenderGlsl) {
    glCreateTextures(GL_TEXTURE_2D, 1, &atlas_);
    glTextureStorage2D(atlas_, 1, GL_RGBA32F, glsl_.atlas.width(), glsl_.atlas.height());
    glTextureSubImage2D(atlas_, 0, 0, 0, glsl_.atlas.width(), glsl_.atlas.height(), GL_RGBA,
                        GL_FLOAT, glsl_.atlas.pixels().data());
    program_.set("stochtex_texton_atlas", 0);
    check_gl("uploading the texton");
  }
  ~TextonPass() { glDeleteTextures(1, &atlas_); }
  TextonPass(const TextonPass&) = delete;
  TextonPass& operator=(const TextonPass&) = delete;

  void prepare(const Grid& grid, std::uint32_t seed, bool filter) const override {
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
    program_.set2("origin_cell", low_bits(origin_cell_x), low_bits(origin_cell_y));
    program_.set2("origin_offset", static_cast<float>(grid.origin.x - origin_cell_x * cell_size),
                  static_cast<float>(grid.origin.y - origin_cell_y * cell_size));
    program_.set("scale", static_cast<float>(grid.scale));
    program_.set("seed", static_cast<unsigned>(seed));
    program_.set("filter_level", setup.level);
    program_.set("filter_level_blend", setup.level_blend);
    program_.set("filter_probes", setup.probes);
    program_.set2("filter_probe_step", setup.probe_x, setup.probe_y);
    program_.set("filter_fade", setup.fade);
    check_gl("setting the texton uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindTextureUnit(0, atlas_);
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  const texton::TextonModel& model_;
  gl::TextonGlsl glsl_;
  Program program_;
  GLuint atlas_ = 0;
};

// The tiling evaluator's GPU state: the program (compiled with the model's constants) and the
// storage buffer of its pyramid and tables.
class TilingPass final : public Pass {
 public:
  explicit TilingPass(const tiling::TilingModel& model)
      : model_(model),
        glsl_(gl::tiling_glsl(model)),
        program_(std::string("#version 450\n") + gl::tiling_library_source(glsl_) +
                 gl::kTilingRenderGlsl),
        data_(glsl_.data.size() * sizeof(float), glsl_.data.data()) {
    check_gl("uploading the tiling model");
  }

  void prepare(const Grid& grid, std::uint32_t seed, bool filter) const override {
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
    program_.set2("origin_cell", low_bits(cell_x), low_bits(cell_y));
    program_.set2("origin_skewed", static_cast<float>(skewed_x - cell_x),
                  static_cast<float>(skewed_y - cell_y));
    program_.set2("origin_wrapped", wrapped.x, wrapped.y);
    program_.set("scale", static_cast<float>(grid.scale));
    program_.set("seed", static_cast<unsigned>(seed));
    program_.set("lod_level", lod.level);
    program_.set("lod_blend", lod.blend);
    check_gl("setting the tiling uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data_.id());
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  const tiling::TilingModel& model_;
  gl::TilingGlsl glsl_;
  Program program_;
  Buffer data_;
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

  void prepare(const Grid& grid, std::uint32_t seed, bool filter) const override {
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

// How to use an exported shader (written as README.md beside it).
constexpr const char* kExportReadme = R"md(# stochtex texton noise shader

Files: `stochtex_texton.glsl` (the noise, self-contained) and `texton_atlas.exr` (the texton
pyramid, RGBA float32). The GLSL declares `uniform sampler2D stochtex_texton_atlas;` and exposes

    vec4 stochtex_texton(vec2 p, vec2 dpdx, vec2 dpdy, uint seed);

`p` is in exemplar pixels (1 unit = 1 pixel of the analysed image), `dpdx`/`dpdy` its screen
derivatives (`dFdx(p)`, `dFdy(p)` in a fragment shader; `vec2(0)` for no filtering) and `seed`
picks the random pattern. The result's first `channels` components are the colour.

Binding it in a plain OpenGL 4.5 program (load the EXR with any EXR reader into `texels`):

```c
GLuint atlas;
glCreateTextures(GL_TEXTURE_2D, 1, &atlas);
glTextureStorage2D(atlas, 1, GL_RGBA32F, width, height);
glTextureSubImage2D(atlas, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels);
glBindTextureUnit(0, atlas);
glProgramUniform1i(program, glGetUniformLocation(program, "stochtex_texton_atlas"), 0);
```

```glsl
#version 450
// ... contents of stochtex_texton.glsl ...
in vec2 uv;  // your surface coordinate
out vec4 colour;
void main() {
  vec2 p = uv * 512.0;  // scaled to exemplar pixels
  colour = vec4(stochtex_texton(p, dFdx(p), dFdy(p), 7u).rgb, 1.0);
}
```

The atlas is read with `texelFetch` (exact texels, no sampler filtering needed): the shader does
its own B-spline interpolation and footprint filtering, the same as the CPU reference.
)md";

}  // namespace

bool gl_supports(std::string_view method) {
  return method == texton::TextonModel::kMethodName || method == tiling::TilingModel::kMethodName ||
         method == lrp::LrpModel::kMethodName;
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
    throw Error(ErrorCode::invalid_input,
                "the gl backend does not evaluate method '" + std::string(model.method()) +
                    "' yet (texton, tiling and lrp only); use --backend cpu");
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
  const Pass& pass = *impl_->pass;
  pass.prepare(grid, seed, options.filter);
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

ShaderExport export_shader(const Model& model) {
  if (model.empty()) throw std::invalid_argument("export_shader: the model is empty");
  if (model.method() != texton::TextonModel::kMethodName)
    throw Error(ErrorCode::invalid_input, "export-shader does not support method '" +
                                              std::string(model.method()) + "' yet (only texton)");
  const auto& texton_model = std::get<texton::TextonModel>(model.data().model);
  gl::TextonGlsl glsl = gl::texton_glsl(texton_model);
  ShaderExport result;
  result.glsl_file_name = "stochtex_texton.glsl";
  std::ostringstream header;
  header << "// Texton noise exported by `stochtex export-shader` (" << texton_model.channels()
         << " channels, texton " << texton_model.support() << "x" << texton_model.support()
         << ", MNI " << texton_model.mean_impacts() << ").\n"
         << "// Paste or include after `#version 450` (GLSL 4.30+). Bind texton_atlas.exr as an "
            "RGBA32F texture to\n// `stochtex_texton_atlas`, then call stochtex_texton(p, dpdx, "
            "dpdy, seed). See README.md.\n\n";
  result.glsl = header.str() + gl::texton_library_source(glsl);
  result.images.push_back({"texton_atlas", std::move(glsl.atlas)});
  result.readme = kExportReadme;
  return result;
}

}  // namespace stochtex
