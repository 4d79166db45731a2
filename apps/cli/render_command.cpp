// `stochtex render MODEL -o IMAGE --size WxH`: model file -> image, on the CPU reference or the
// OpenGL backend.

#include "render_command.hpp"

#include <fmt/core.h>

#include <memory>
#include <optional>
#include <stdexcept>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "io/image_io.hpp"
#include "progress.hpp"
#ifdef STOCHTEX_WITH_GL
#include "stochtex/gpu.hpp"
#endif

namespace stochtex::cli {

void add_render_options(CLI::App* command, RenderSettings& settings, std::string& output) {
  command->add_option("-o,--output", output, "image to write (.png, .exr or .pfm)")->required();
  command->add_option("--size", settings.size, "output size WIDTHxHEIGHT in pixels")->required();
  command
      ->add_option("--origin", settings.origin, "model-space position X,Y of the top-left corner")
      ->capture_default_str();
  command->add_option("--scale", settings.scale, "exemplar pixels per output pixel (zoom out > 1)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e6));
  command->add_option("--seed", settings.seed, "32-bit seed of the random pattern")
      ->capture_default_str();
  command->add_option("--threads", settings.threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, kMaxThreads));
  command
      ->add_option("--supersample", settings.supersample,
                   "average KxK point samples per pixel (filtering reference)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  command->add_option("--tile", settings.tile, "tile side in pixels (speed only, never the output)")
      ->capture_default_str()
      ->check(CLI::Range(1, 4096));
  command->add_flag("--no-filter", settings.no_filter,
                    "point-sample even when zoomed out (aliases)");
  command->add_option("--bit-depth", settings.bit_depth, "PNG output bits per channel")
      ->capture_default_str()
      ->check(CLI::IsMember({8, 16}));
  command
      ->add_option("--backend", settings.backend,
                   "cpu (the reference) or gl (OpenGL 4.5 compute, headless; every method)")
      ->capture_default_str()
      ->check(CLI::IsMember({"cpu", "gl"}));
  command
      ->add_option(
          "--gl-filter", settings.gl_filter,
          "with --backend gl: exact (the CPU's filter, to float rounding) or hardware "
          "(texton order 1, tiling: mip-mapped textures, trilinear + anisotropic; equal to the "
          "CPU in distribution)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "hardware"}));
}

namespace {

Grid render_grid(const RenderSettings& settings) {
  const Size size = output_size(settings.size);
  const std::optional<Vec2d> origin = parse_number_pair(settings.origin);
  if (!origin)
    throw std::invalid_argument("--origin must be X,Y in exemplar pixels, e.g. 1000,-250.5, not '" +
                                settings.origin + "'");
  // CLI11's range check lets NaN through (every comparison with it is false): the grid check
  // refuses it with the origin and positions beyond the precise range (render.hpp).
  const Grid grid{*origin, settings.scale, size.width, size.height, 0, 0};
  check_grid(grid, fmt::format("--origin {} with --scale {} and --size {}", settings.origin,
                               settings.scale, settings.size));
  return grid;
}

// Each thread holds one tile's samples (docs/design.md §9): with --threads 0 as many cores work
// as the memory budget allows; a request beyond it is refused before the model is loaded or
// analysed.
int render_threads(const RenderSettings& settings, const Grid& grid) {
  const auto peak = [&](int threads) {
    return render_peak_bytes(grid.width, grid.height, settings.tile, settings.supersample, threads);
  };
  int threads = resolve_thread_count(settings.threads);
  if (settings.threads == 0)
    while (threads > 1 && peak(threads) > kMemoryBudgetBytes) --threads;
  check_memory_budget(
      peak(threads),
      fmt::format("rendering {}x{} pixels with --supersample {}, --tile {} and {} "
                  "threads",
                  grid.width, grid.height, settings.supersample, settings.tile, threads),
      "use fewer --threads or a smaller --supersample, --tile or --size");
  return threads;
}

void render_model(const Model& model, const Grid& grid, int threads, const RenderSettings& settings,
                  const std::string& output) {
  ImageF image(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.threads = threads;
  options.tile_size = settings.tile;
  options.supersample = settings.supersample;
  options.filter = !settings.no_filter;
  if (settings.backend == "gl") {
#ifdef STOCHTEX_WITH_GL
    GpuRenderOptions gpu_options;
    gpu_options.filter = options.filter;
    gpu_options.texture_filter =
        settings.gl_filter == "hardware" ? GlFilter::hardware : GlFilter::exact;
    if (options.supersample != 1)
      throw std::invalid_argument("--supersample is a CPU reference: use it with --backend cpu");
    render_gl(model, grid, settings.seed, image.view(), gpu_options);
#else
    throw Error(ErrorCode::io,
                "this stochtex was built without the OpenGL backend "
                "(STOCHTEX_BUILD_GL=OFF); use --backend cpu");
#endif
  } else {
    Progress progress("render ");
    options.progress = [&](double fraction) { progress(fraction); };
    render(model, grid, settings.seed, image.view(), options);
  }
  write_image(output, image.view(), settings.bit_depth);
}

}  // namespace

void render_to_file(const std::function<Model()>& make_model, const RenderSettings& settings,
                    const std::string& output, const std::string& input) {
  const Grid grid = render_grid(settings);
  const int threads = render_threads(settings, grid);
  check_output_path(output, true, input);
  const Model model = make_model();
  check_output_channels(output, model.channels());
  render_model(model, grid, threads, settings, output);
  fmt::print(stderr, "wrote {}\n", output);
}

Command add_render_command(CLI::App& app) {
  struct Options {
    std::string model;
    RenderSettings settings;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("render", "model file -> image");
  command->add_option("MODEL", options->model, "model file (.stx)")->required();
  add_render_options(command, options->settings, options->output);
  return {command, [options] {
            render_to_file([&] { return load_model(options->model); }, options->settings,
                           options->output, options->model);
            return 0;
          }};
}

}  // namespace stochtex::cli
