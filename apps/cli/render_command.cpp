// `stochtex render MODEL -o IMAGE --size WxH`: model file -> image, on the CPU reference or the
// OpenGL backend.

#include "render_command.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "io/image_io.hpp"
#include "io/tiled_exr.hpp"
#include "progress.hpp"
#include "stochtex/material.hpp"
#ifdef STOCHTEX_WITH_GL
#include "stochtex/gpu.hpp"
#endif

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
  command
      ->add_option(
          "--cpu-target", settings.cpu_target,
          "the CPU evaluators' instruction set: best (this machine's), reference (the "
          "scalar evaluator), portable, sse4, avx2 or avx512; speed only, never the output")
      ->capture_default_str()
      ->check(CLI::IsMember({"best", "reference", "portable", "sse4", "avx2", "avx512"}));
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

// Sets the CPU target named by --cpu-target; refuses one this machine cannot run.
void use_cpu_target(const std::string& name) {
  set_cpu_target(name == "best" ? available_cpu_targets().back() : available_cpu_target(name));
}

// What a render writes: the grid of its region of the --size image and, for a tiled OpenEXR
// output, the file's options (streamed set).
struct RenderPlan {
  Grid grid;
  bool streamed = false;
  TiledExrOptions exr;
};

RenderPlan render_plan(const RenderSettings& settings, const std::string& output) {
  const Size size = render_size(settings.size);
  const Region region = settings.region.empty() ? Region{0, 0, size.width, size.height}
                                                : parse_region(settings.region, size);
  const std::optional<Vec2d> origin = parse_number_pair(settings.origin);
  if (!origin)
    throw std::invalid_argument("--origin must be X,Y in exemplar pixels, e.g. 1000,-250.5, not '" +
                                settings.origin + "'");
  RenderPlan plan;
  plan.grid = {*origin, settings.scale, region.width, region.height, region.x, region.y};
  const std::string what = settings.region.empty() ? fmt::format("--size {}", settings.size)
                                                   : fmt::format("--region {}", settings.region);
  const bool exr = is_exr_output(output);
  const bool in_memory = fits_in_memory(region.width, region.height);
  plan.streamed = exr && (settings.tiled || settings.mipmap || settings.half || !in_memory);
  if ((settings.tiled || settings.mipmap || settings.half) && !exr)
    throw std::invalid_argument(
        "--tiled, --mipmap and --half write a tiled OpenEXR file: name the output .exr, not '" +
        output + "'");
  if (settings.mipmap && !settings.region.empty())
    throw std::invalid_argument(
        "--mipmap cannot be combined with --region: a region has no mip levels of its own; render "
        "the whole --size image with --mipmap");
  if (!plan.streamed && !in_memory)
    throw std::invalid_argument(fmt::format(
        "{} is {} pixels; {} output is rendered in memory and holds at most {} pixels and {} a "
        "side: write a .exr file, which is streamed tile by tile",
        what, static_cast<std::int64_t>(region.width) * region.height,
        std::filesystem::path(output).extension().string(), kMaxInMemoryPixels, kMaxInMemorySide));
  if (plan.streamed && settings.backend == "gl" && !in_memory)
    throw std::invalid_argument(fmt::format(
        "{} is {}x{} pixels, more than --backend gl renders ({} pixels and {} a side); use "
        "--backend cpu, which streams it tile by tile",
        what, region.width, region.height, kMaxInMemoryPixels, kMaxInMemorySide));
  plan.exr.mipmap = settings.mipmap;
  plan.exr.half = settings.half;
  // CLI11's range check lets NaN through (every comparison with it is false): the grid check
  // refuses it with the origin and positions beyond the precise range (render.hpp); each mip
  // level's grid too, since its last pixels may reach further than level 0's.
  const std::string request =
      fmt::format("--origin {} with --scale {} and {}", settings.origin, settings.scale, what);
  for (const Grid& level : tiled_exr_levels(plan.grid, plan.streamed && settings.mipmap))
    check_grid(level, request);
  return plan;
}

// Each thread holds one tile's samples (docs/design.md §9): with --threads 0 as many cores work
// as the memory budget allows; a request beyond it is refused before the model is loaded or
// analysed. A streamed render holds one strip of kExrTileSide rows, not the image.
int render_threads(const RenderSettings& settings, const RenderPlan& plan) {
  const int held_rows = plan.streamed ? std::min(kExrTileSide, plan.grid.height) : plan.grid.height;
  const auto peak = [&](int threads) {
    return render_peak_bytes(plan.grid.width, held_rows, settings.tile, settings.supersample,
                             threads);
  };
  int threads = resolve_thread_count(settings.threads);
  if (settings.threads == 0)
    while (threads > 1 && peak(threads) > kMemoryBudgetBytes) --threads;
  check_memory_budget(
      peak(threads),
      fmt::format("rendering {}x{} pixels with --supersample {}, --tile {} and {} "
                  "threads",
                  plan.grid.width, held_rows, settings.supersample, settings.tile, threads),
      "use fewer --threads or a smaller --supersample, --tile or --size");
  return threads;
}

// A tiled file is refused before any work when its pixels, uncompressed, do not fit in the free
// space of the output's folder: float pixels are written uncompressed, half ones compress by a
// third (docs/large-renders.md).
void check_disk_space(const RenderPlan& plan, int channels, const std::string& output) {
  const std::filesystem::path folder = std::filesystem::absolute(output).parent_path();
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(folder, error);
  const std::uint64_t bytes = tiled_exr_pixels(plan.grid, plan.exr.mipmap) *
                              static_cast<std::uint64_t>(channels) * (plan.exr.half ? 2 : 4);
  if (!error && bytes > space.available)
    throw Error(
        ErrorCode::io,
        fmt::format("cannot write '{}': its {}x{} pixels{} take {:.1f} GB uncompressed, "
                    "more than the {:.1f} GB free in '{}'; free disk space, add --half or "
                    "render a smaller --size or --region",
                    output, plan.grid.width, plan.grid.height,
                    plan.exr.mipmap ? " and mip levels" : "", static_cast<double>(bytes) / 1e9,
                    static_cast<double>(space.available) / 1e9, folder.string()));
}

// Renders grids (the whole image, or one strip after another of a tiled file) with the settings'
// backend, one progress bar across all of them: `total_pixels` is the pixels of every grid.
class GridRenderer {
 public:
  GridRenderer(const Model& model, const RenderSettings& settings, int threads,
               std::uint64_t total_pixels)
      : model_(model), seed_(settings.seed), total_(static_cast<double>(total_pixels)) {
    options_.threads = threads;
    options_.tile_size = settings.tile;
    options_.supersample = settings.supersample;
    options_.filter = !settings.no_filter;
    if (settings.backend != "gl") return;
#ifdef STOCHTEX_WITH_GL
    gpu_options_.filter = options_.filter;
    gpu_options_.texture_filter =
        settings.gl_filter == "hardware" ? GlFilter::hardware : GlFilter::exact;
    if (options_.supersample != 1)
      throw std::invalid_argument("--supersample is a CPU reference: use it with --backend cpu");
    gl_ = std::make_unique<GlRenderer>(model);
#else
    throw Error(ErrorCode::io,
                "this stochtex was built without the OpenGL backend "
                "(STOCHTEX_BUILD_GL=OFF); use --backend cpu");
#endif
  }

  void operator()(const Grid& grid, ImageView<float> out) {
    const double pixels = static_cast<double>(grid.width) * grid.height;
#ifdef STOCHTEX_WITH_GL
    if (gl_) {
      gl_->render(grid, seed_, out, gpu_options_);
      done_ += pixels;
      progress_(done_ / total_);
      return;
    }
#endif
    options_.progress = [&](double fraction) { progress_((done_ + fraction * pixels) / total_); };
    render(model_, grid, seed_, out, options_);
    done_ += pixels;
  }

 private:
  const Model& model_;
  std::uint32_t seed_;
  double total_;
  double done_ = 0.0;
  RenderOptions options_;
  Progress progress_{"render "};
#ifdef STOCHTEX_WITH_GL
  GpuRenderOptions gpu_options_;
  std::unique_ptr<GlRenderer> gl_;
#endif
};

// A material's maps, each written to the output named with {map} replaced by the map's name,
// after all are rendered (docs/materials.md).
constexpr std::string_view kMapField = "{map}";

std::string map_output(std::string output, std::string_view name) {
  for (auto at = output.find(kMapField); at != std::string::npos;
       at = output.find(kMapField, at + name.size()))
    output.replace(at, kMapField.size(), name);
  return output;
}

// The channels of each map's image as split_maps writes it.
int written_channels(const MapInfo& map) {
  return map.kind == MapKind::normal ? 3 : map.channels;
}

// Checks a material's outputs before the render: {map} in the name exactly when the model has
// maps, every map's file writable, in memory and within the memory budget (the render, the maps
// cut from it and one map's encoded copy).
void check_map_outputs(const Model& model, const RenderPlan& plan, const std::string& output,
                       const std::string& input) {
  const bool per_map = output.find(kMapField) != std::string::npos;
  if (model.maps().empty()) {
    if (per_map)
      throw std::invalid_argument("'" + output + "' names a file per map with {map}, but '" +
                                  input + "' is a model of one image; remove {map}");
    return;
  }
  std::string names;
  for (const MapInfo& map : model.maps()) names += (names.empty() ? "" : ", ") + map.name;
  if (!per_map)
    throw std::invalid_argument("'" + input + "' is a material of maps " + names +
                                ": name the output with {map}, one file per map, e.g. -o "
                                "out_{map}.png");
  std::uint64_t bytes_per_pixel = 4 * static_cast<std::uint64_t>(model.channels());
  for (const MapInfo& map : model.maps()) {
    const std::string path = map_output(output, map.name);
    check_output_path(path, true, input);
    check_output_channels(path, written_channels(map));
    // The map cut from the render and its encoded copy, or the strip of every map's file.
    bytes_per_pixel += (plan.streamed ? 8 : 6) * static_cast<std::uint64_t>(written_channels(map));
  }
  // In memory: the whole grid; streamed: one strip and its margin (render_maps).
  const std::uint64_t rows = plan.streamed ? kExrTileSide + 2 : plan.grid.height;
  check_memory_budget(
      bytes_per_pixel * static_cast<std::uint64_t>(plan.grid.width + 2) * rows,
      fmt::format("rendering the {} maps of a {}x{} material{}", model.maps().size(),
                  plan.grid.width, plan.streamed ? static_cast<int>(rows) : plan.grid.height,
                  plan.streamed ? " strip" : ""),
      "render a smaller --size, or --region pieces");
}

// The pixels render_maps renders for `grid`: with a derived normal map, a one-pixel margin.
std::uint64_t material_pixels(const Model& model, const Grid& grid) {
  const bool margin = std::any_of(model.maps().begin(), model.maps().end(),
                                  [](const MapInfo& map) { return !map.derived_from.empty(); });
  return static_cast<std::uint64_t>(grid.width + (margin ? 2 : 0)) *
         static_cast<std::uint64_t>(grid.height + (margin ? 2 : 0));
}

// A material's maps to one tiled .exr file each, strip by strip: each strip is one render_maps
// call for every map (docs/materials.md).
void stream_maps(const Model& model, const RenderPlan& plan, int threads,
                 const RenderSettings& settings, const std::string& output) {
  std::vector<TiledExrFile> files;
  for (const MapInfo& map : model.maps())
    files.push_back({map_output(output, map.name), written_channels(map)});
  std::uint64_t pixels = 0;
  for (const Grid& level : tiled_exr_levels(plan.grid, plan.exr.mipmap))
    for (int row = 0; row < level.height; row += kExrTileSide) {
      Grid strip = level;
      strip.height = std::min(kExrTileSide, level.height - row);
      pixels += material_pixels(model, strip);
    }
  GridRenderer renderer(model, settings, threads, pixels);
  TiledExrOptions options = plan.exr;
  options.threads = threads;
  write_tiled_exrs(files, plan.grid, options, [&](const Grid& strip, ImageView<float> out) {
    const std::vector<NamedImage> maps = render_maps(
        model, strip, [&](const Grid& part, ImageView<float> into) { renderer(part, into); });
    int first = 0;
    for (const auto& [name, map] : maps) {
      for (int y = 0; y < strip.height; ++y)
        for (int x = 0; x < strip.width; ++x)
          for (int c = 0; c < map.channels(); ++c) out.at(x, y, first + c) = map.at(x, y, c);
      first += map.channels();
    }
  });
}

void render_model(const Model& model, const RenderPlan& plan, int threads,
                  const RenderSettings& settings, const std::string& output) {
  const Grid& grid = plan.grid;
  if (!model.maps().empty() && plan.streamed) {
    stream_maps(model, plan, threads, settings, output);
    return;
  }
  if (!model.maps().empty()) {
    GridRenderer renderer(model, settings, threads, material_pixels(model, grid));
    const std::vector<NamedImage> maps = render_maps(
        model, grid, [&](const Grid& part, ImageView<float> out) { renderer(part, out); });
    for (const auto& [name, map] : maps)
      write_image(map_output(output, name), map.view(), settings.bit_depth);
    return;
  }
  if (!plan.streamed) {
    ImageF image(grid.width, grid.height, model.channels());
    GridRenderer(model, settings, threads, static_cast<std::uint64_t>(grid.width) * grid.height)(
        grid, image.view());
    write_image(output, image.view(), settings.bit_depth);
    return;
  }
  GridRenderer renderer(model, settings, threads, tiled_exr_pixels(grid, plan.exr.mipmap));
  TiledExrOptions options = plan.exr;
  options.threads = threads;
  write_tiled_exr(output, grid, model.channels(), options,
                  [&](const Grid& strip, ImageView<float> out) { renderer(strip, out); });
}

}  // namespace

void render_to_file(const std::function<Model()>& make_model, const RenderSettings& settings,
                    const std::string& output, const std::string& input) {
  check_output_path(map_output(output, "map"), true, input);
  const RenderPlan plan = render_plan(settings, output);
  const int threads = render_threads(settings, plan);
  use_cpu_target(settings.cpu_target);
  const Model model = make_model();
  check_map_outputs(model, plan, output, input);
  if (model.maps().empty()) check_output_channels(output, model.channels());
  if (plan.streamed) {
    int channels = model.channels();  // a material's: every map's file
    if (!model.maps().empty()) {
      channels = 0;
      for (const MapInfo& map : model.maps()) channels += written_channels(map);
    }
    check_disk_space(plan, channels,
                     map_output(output, model.maps().empty() ? "" : model.maps().front().name));
  }
  render_model(model, plan, threads, settings, output);
  if (model.maps().empty()) {
    fmt::print(stderr, "wrote {}\n", output);
    return;
  }
  for (const MapInfo& map : model.maps())
    fmt::print(stderr, "wrote {}\n", map_output(output, map.name));
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
