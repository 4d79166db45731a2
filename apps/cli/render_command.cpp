// `stochtex render MODEL -o IMAGE --size WxH`: model file -> image, on the CPU reference or the
// OpenGL backend.

#include "render_command.hpp"

#include <fmt/core.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "progress.hpp"
#include "renderer/backends.hpp"
#include "renderer/render_file.hpp"

namespace stochtex::cli {

void add_render_options(CLI::App* command, RenderSettings& settings, std::string& output) {
  command
      ->add_option("-o,--output", output,
                   "image to write (.png, .exr or .pfm); .png and .pfm are rendered in memory "
                   "(at most 64 Mpixel, 32768 a side), .exr beyond that or with --tiled, "
                   "--mipmap or --half is a tiled OpenEXR file rendered and written strip by "
                   "strip with bounded memory; a material's maps go to one file each, named "
                   "with {map} (e.g. out_{map}.png)")
      ->required();
  command
      ->add_option("--size", settings.size,
                   "output size WIDTHxHEIGHT in pixels (sides up to 1048576)")
      ->required();
  command->add_option("--region", settings.region,
                      "X,Y,WIDTH,HEIGHT: write only these pixels of the --size image, equal to "
                      "the same pixels of the whole render (batch jobs render regions apart)");
  command->add_flag("--tiled", settings.tiled,
                    "write .exr as a tiled OpenEXR file (64x64 tiles), streamed strip by strip");
  command->add_flag("--mipmap", settings.mipmap,
                    "tiled .exr with mip levels (round down): level k is the render at --scale "
                    "times 2^k, the texture zoomed out with the method's own filtering");
  command->add_flag("--half", settings.half,
                    "tiled .exr with 16-bit half floats (float32 otherwise)");
  command
      ->add_option("--origin", settings.origin, "model-space position X,Y of the top-left corner")
      ->capture_default_str();
  command->add_option("--scale", settings.scale, "exemplar pixels per output pixel (zoom out > 1)")
      ->capture_default_str()
      ->check(CLI::Range(renderer::kMinScale, renderer::kMaxScale));  // NaN: plan_render refuses
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
  command
      ->add_option(
          "--cpu-target", settings.cpu_target,
          "the CPU evaluators' instruction set: best (this machine's), reference (the "
          "scalar evaluator), portable, sse4, avx2 or avx512; speed only, never the output")
      ->capture_default_str()
      ->check(CLI::IsMember({"best", "reference", "portable", "sse4", "avx2", "avx512"}));
  command->add_flag(
      "--periodic", settings.periodic,
      "a tileable bake: the texture repeats with the --size image (seamless when the image is "
      "repeated, not repetitive inside it), for engines that can only repeat a bitmap; --region "
      "renders pixels of that whole image, CPU backend only (docs/render.md)");
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

// The settings as the renderer takes them: the text of --size, --region and --origin parsed (their
// ranges are the renderer's to check), each kept for its refusals.
renderer::RenderRequest render_request(const RenderSettings& settings) {
  renderer::RenderRequest request;
  const Size size = size_option(settings.size);
  request.width = size.width;
  request.height = size.height;
  if (!settings.region.empty()) request.region = parse_region(settings.region);
  const std::optional<Vec2d> origin = parse_number_pair(settings.origin);
  if (!origin)
    throw std::invalid_argument("--origin must be X,Y in exemplar pixels, e.g. 1000,-250.5, not '" +
                                settings.origin + "'");
  request.origin = *origin;
  request.scale = settings.scale;
  request.seed = settings.seed;
  request.threads = settings.threads;
  request.supersample = settings.supersample;
  request.tile = settings.tile;
  request.filter = !settings.no_filter;
  if (settings.cpu_target != "best") request.cpu_target = available_cpu_target(settings.cpu_target);
  request.backend = settings.backend == "gl" ? renderer::Backend::gl : renderer::Backend::cpu;
  request.gl_filter = settings.gl_filter == "hardware" ? GlFilter::hardware : GlFilter::exact;
  request.tiled = settings.tiled;
  request.mipmap = settings.mipmap;
  request.half = settings.half;
  request.bit_depth = settings.bit_depth;
  request.periodic = settings.periodic;
  request.text = {settings.size, settings.region, settings.origin};
  return request;
}

}  // namespace

void render_to_file(const std::function<Model()>& make_model, const RenderSettings& settings,
                    const std::string& output, const std::string& input) {
  const renderer::RenderRequest request = render_request(settings);
  std::vector<std::string> written;
  {
    Progress progress("render ");
    written = renderer::render_to_file(make_model, request, output, input, renderer::make_backend,
                                       [&](double fraction) { progress(fraction); });
  }
  for (const std::string& file : written) fmt::print(stderr, "wrote {}\n", file);
}

Command add_render_command(CLI::App& app) {
  struct Options {
    std::string model;
    RenderSettings settings;
    std::string output;
    std::string colour_space;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("render", "model file -> image");
  command->add_option("MODEL", options->model, "model file (.stx)")->required();
  add_render_options(command, options->settings, options->output);
  command
      ->add_option("--colour-space", options->colour_space,
                   "render the model as if analysed with this colour space (srgb, linear or "
                   "data) instead of its own, without analysing again: srgb for a photo's "
                   "model written before colour spaces, data for today's averages of encoded "
                   "values (a model of one image)")
      ->check(CLI::IsMember({"srgb", "linear", "data"}));
  return {command, [options] {
            render_to_file(
                [&] {
                  const Model model = load_model(options->model);
                  if (options->colour_space.empty()) return model;
                  if (!model.maps().empty())
                    throw std::invalid_argument(
                        "--colour-space is for a model of one image; a material's maps each "
                        "have theirs (stochtex analyze --map NAME:KIND:COLOUR_SPACE=FILE)");
                  return with_colour_space(model, *colour_space_from_name(options->colour_space));
                },
                options->settings, options->output, options->model);
            return 0;
          }};
}

}  // namespace stochtex::cli
