// The GL surface evaluator (stochtex/gpu.hpp): evaluate_surface() on the GPU through the method's
// GLSL surface function (gl::Twin<M>::surface_shader, HasSurfaceTwin in twin.hpp): the points in
// a storage buffer, one compute invocation per point (surface.glsl), the values read back. A method
// whose twin has no surface_shader, or returns none for a mapping, is refused with one sentence.

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "gl/colour.hpp"
#include "gl/context.hpp"
#include "gl/program.hpp"
#include "gl/shaders.hpp"
#include "gl/surface_shader.hpp"
#include "gl/twin.hpp"
#include "model/model_data.hpp"
#include "render/surface_arguments.hpp"
#include "stochtex/error.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex {

std::optional<gl::SurfaceShader> gl::model_surface_shader(const Model& model,
                                                          const SurfaceOptions& options) {
  // The surface functions return a vec4 (gl/surface.glsl).
  if (model.empty() || model.channels() > kMaxImageChannels) return std::nullopt;
  std::optional<gl::SurfaceShader> shader = std::visit(
      [&](const auto& m) -> std::optional<gl::SurfaceShader> {
        using M = std::decay_t<decltype(m)>;
        if constexpr (gl::HasSurfaceTwin<M>)
          return gl::Twin<M>::surface_shader(m, options);
        else
          return std::nullopt;
      },
      model.data().model);
  // A model of sRGB colour returns linear light, as evaluate_surface does.
  if (shader) add_colour(*shader, model.data().colour, model.channels(), options.mapping);
  return shader;
}

namespace {

constexpr int kFloatsPerPoint = 15;
// Points per dispatch: bounds the staging buffers (15 + 4 floats per point), never the output.
constexpr int kBatch = 1 << 16;

}  // namespace

// One mapping's compiled surface function and its data, for the options it was made for.
struct GlSurfaceEvaluator::Compiled {
  SurfaceOptions options;
  gl::Program program;
  gl::Buffer data;
  gl::ProgramTextures textures;
  Compiled(const SurfaceOptions& made_for, const gl::SurfaceShader& shader, int channels)
      : options(made_for),
        program("#version 450\n#define STOCHTEX_CHANNELS " + std::to_string(channels) +
                "\n#define STOCHTEX_SURFACE_CALL " + shader.call + "\n" + shader.library +
                gl::shader_source("gl/surface.glsl")),
        data(std::max<std::size_t>(shader.data.size(), 1) * sizeof(float), shader.data.data()),
        textures(program, shader.textures) {}
};

struct GlSurfaceEvaluator::Impl {
  gl::Context context;  // first: destroyed after the programs and buffers

  const Model model;
  std::array<std::unique_ptr<Compiled>, 3> compiled;
  explicit Impl(const Model& m) : model(m) {}
};

bool gl_supports_mapping(const Model& model, SurfaceMapping mapping) {
  SurfaceOptions options;
  options.mapping = mapping;
  return gl::model_surface_shader(model, options).has_value();
}

GlSurfaceEvaluator::GlSurfaceEvaluator(const Model& model) : impl_(new Impl(model)) {}

GlSurfaceEvaluator::~GlSurfaceEvaluator() = default;

void GlSurfaceEvaluator::evaluate(std::span<const SurfacePoint> points,
                                  const SurfaceOptions& options, std::uint32_t seed,
                                  ImageView<float> out) {
  const Model& model = impl_->model;
  check_surface_arguments(model, points, options, out);
  auto& compiled = impl_->compiled[static_cast<std::size_t>(options.mapping)];
  // The library may depend on the options (the constants of texton surface noise's MNI).
  if (!compiled || compiled->options.surface_mni != options.surface_mni ||
      compiled->options.triplanar_sharpness != options.triplanar_sharpness) {
    const std::optional<gl::SurfaceShader> shader = gl::model_surface_shader(model, options);
    if (!shader)
      throw Error(ErrorCode::invalid_input,
                  "the gl backend has no GLSL " + std::string(mapping_name(options.mapping)) +
                      " mapping for " + std::string(model.method()) + " models; use --backend cpu");
    compiled = std::make_unique<Compiled>(options, *shader, model.channels());
  }
  const gl::Program& program = compiled->program;
  const int channels = model.channels();
  const float parameter =
      static_cast<float>(options.mapping == SurfaceMapping::surface ? options.surface_mni
                                                                    : options.triplanar_sharpness);
  program.set("seed", static_cast<unsigned>(seed));
  program.set("parameter", parameter);
  const gl::Buffer input(static_cast<std::size_t>(kBatch) * kFloatsPerPoint * sizeof(float));
  const gl::Buffer result(static_cast<std::size_t>(kBatch) * channels * sizeof(float));
  std::vector<float> staging(static_cast<std::size_t>(kBatch) * kFloatsPerPoint);
  std::vector<float> values(static_cast<std::size_t>(kBatch) * channels);
  for (std::size_t first = 0; first < points.size(); first += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, points.size() - first));
    for (int i = 0; i < count; ++i) {
      const SurfacePoint& p = points[first + static_cast<std::size_t>(i)];
      const std::array<Vec3d, 5> vectors = {p.position, p.normal, p.tangent, p.dpdx, p.dpdy};
      float* to = staging.data() + static_cast<std::ptrdiff_t>(i) * kFloatsPerPoint;
      for (const Vec3d& v : vectors) {
        *to++ = static_cast<float>(v.x);
        *to++ = static_cast<float>(v.y);
        *to++ = static_cast<float>(v.z);
      }
    }
    glNamedBufferSubData(input.id(), 0,
                         static_cast<GLsizeiptr>(count) * kFloatsPerPoint * sizeof(float),
                         staging.data());
    program.set("point_count", count);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, compiled->data.id());
    compiled->textures.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, result.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, input.id());
    glDispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    glGetNamedBufferSubData(
        result.id(), 0, static_cast<GLsizeiptr>(count) * channels * sizeof(float), values.data());
    gl::check_gl("evaluating the surface points");
    for (int i = 0; i < count; ++i) {
      const auto index = static_cast<std::int64_t>(first) + i;
      for (int c = 0; c < channels; ++c)
        out.at(static_cast<int>(index % out.width), static_cast<int>(index / out.width), c) =
            values[static_cast<std::size_t>(i) * channels + static_cast<std::size_t>(c)];
    }
  }
}

void evaluate_surface_gl(const Model& model, std::span<const SurfacePoint> points,
                         const SurfaceOptions& options, std::uint32_t seed, ImageView<float> out) {
  GlSurfaceEvaluator(model).evaluate(points, options, seed, out);
}

}  // namespace stochtex
