// The GL renderer's skeleton: one method's Pass (its GPU twin, src/methods/<m>/gl_pass.cpp) made
// by visiting the model, the region cut into dispatches, GPU timing and the read-back.

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "gl/context.hpp"
#include "gl/program.hpp"
#include "gl/twin.hpp"
#include "model/model_colour.hpp"
#include "model/model_data.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex_gl_twins.hpp"

namespace stochtex {

static_assert(gl::kEveryMethodHasTwin<MethodModel>,
              "every method of MethodModel needs a GPU twin: gl::Twin<Model> in "
              "src/methods/<method>/gl_twin.hpp (see src/gl/twin.hpp)");

// Every method of the variant that has a twin.
bool gl_supports(std::string_view method) {
  return []<typename... MethodModels>(std::type_identity<std::variant<MethodModels...>>,
                                      std::string_view name) {
    return ((gl::HasTwin<MethodModels> && name == MethodModels::kMethodName) || ...);
  }(std::type_identity<MethodModel>{}, method);
}

struct GlRenderer::Impl {
  gl::Context context;
  const Model model;
  std::unique_ptr<gl::Pass> pass;
  GLuint timer = 0;
  double milliseconds = 0.0;

  explicit Impl(const Model& m)
      : model(m),
        pass(std::visit(
            [](const auto& method_model) -> std::unique_ptr<gl::Pass> {
              return gl::Twin<std::decay_t<decltype(method_model)>>::pass(method_model);
            },
            model.data().model)) {
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
  check_grid(grid, "render_gl: the grid");
  constexpr std::int64_t kMaxPixelIndex = std::int64_t{1} << 30;
  if (std::abs(grid.first_pixel_x) + grid.width > kMaxPixelIndex ||
      std::abs(grid.first_pixel_y) + grid.height > kMaxPixelIndex)
    throw std::invalid_argument(
        "render_gl: the region's pixel indices exceed 2^30; move the origin instead");
  gl::Pass& pass = *impl_->pass;
  pass.prepare(grid, seed, options);
  const ModelColour& colour = impl_->model.data().colour;
  const double width =
      options.filter ? footprint_area_width({{grid.scale, 0.0}, {0.0, grid.scale}}) : 0.0;
  const int tile_width = std::clamp(options.tile_size, 1, std::max(grid.width, 1));
  const int tile_height = std::clamp(options.tile_size, 1, std::max(grid.height, 1));
  const gl::Buffer result(static_cast<std::size_t>(tile_width) * tile_height * channels *
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
      gl::check_gl("running the shader");
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < channels; ++c)
            out.at(x0 + x, y0 + y, c) = values[(static_cast<std::size_t>(y) * w + x) * channels +
                                               static_cast<std::size_t>(c)];
      // The srgb channels that the shader returns encoded become linear light here, as render()
      // does after the CPU evaluators (model/model_colour.hpp): the same function of the same
      // values, so the GL render keeps the CPU's parity. One footprint width for the grid.
      decode_expectation_with(
          colour, static_cast<std::size_t>(w) * h, [&](std::size_t) { return width; },
          out.sub(x0, y0, w, h));
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
