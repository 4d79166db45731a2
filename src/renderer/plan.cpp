#include "renderer/plan.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "io/image_io.hpp"

namespace stochtex::renderer {

bool fits_in_memory(std::int64_t width, std::int64_t height) {
  return width <= kMaxInMemorySide && height <= kMaxInMemorySide &&
         width * height <= kMaxInMemoryPixels;
}

namespace {

// The caller's text of a setting, or the one written from its numbers.
std::string quoted(const std::string& text, const std::string& written) {
  return text.empty() ? written : text;
}

// The region's pixels of the whole image, checked to be at least one pixel and inside it;
// `text` quotes it.
PixelRegion checked_region(const RenderRequest& request, const std::string& text) {
  if (!request.region) return {0, 0, request.width, request.height};
  const PixelRegion& region = *request.region;
  if (region.x < 0 || region.y < 0 || region.width < 1 || region.height < 1 ||
      std::int64_t{region.x} + region.width > request.width ||
      std::int64_t{region.y} + region.height > request.height)
    throw std::invalid_argument(fmt::format(
        "--region {} is not inside the {}x{} image of --size: it needs a width and height of at "
        "least 1 and X + WIDTH <= {}, Y + HEIGHT <= {}",
        text, request.width, request.height, request.width, request.height));
  return region;
}

}  // namespace

RenderPlan plan_render(const RenderRequest& request, const std::string& output) {
  const std::string size =
      quoted(request.text.size, fmt::format("{}x{}", request.width, request.height));
  if (request.width < 1 || request.height < 1 || request.width > kMaxStreamedSide ||
      request.height > kMaxStreamedSide)
    throw std::invalid_argument(fmt::format("--size {} is out of range: each side must be 1 to {}",
                                            size, kMaxStreamedSide));
  std::string region_text;
  if (request.region) {
    const PixelRegion& given = *request.region;
    region_text = quoted(request.text.region,
                         fmt::format("{},{},{},{}", given.x, given.y, given.width, given.height));
  }
  const PixelRegion region = checked_region(request, region_text);
  RenderPlan plan;
  plan.grid = {request.origin, request.scale, region.width, region.height, region.x, region.y};
  const std::string what =
      request.region ? "--region " + region_text : fmt::format("--size {}", size);
  const bool exr = is_exr_output(output);
  const bool in_memory = fits_in_memory(region.width, region.height);
  const bool tiled_options = request.tiled || request.mipmap || request.half;
  plan.streamed = exr && (tiled_options || !in_memory);
  if (tiled_options && !exr)
    throw std::invalid_argument(
        "--tiled, --mipmap and --half write a tiled OpenEXR file: name the output .exr, not '" +
        output + "'");
  if (request.periodic) check_periodic_backend(request.backend);
  if (request.mipmap && request.region)
    throw std::invalid_argument(
        "--mipmap cannot be combined with --region: a region has no mip levels of its own; render "
        "the whole --size image with --mipmap");
  if (!plan.streamed && !in_memory)
    throw std::invalid_argument(fmt::format(
        "{} is {} pixels; {} output is rendered in memory and holds at most {} pixels and {} a "
        "side: write a .exr file, which is streamed tile by tile",
        what, static_cast<std::int64_t>(region.width) * region.height,
        std::filesystem::path(output).extension().string(), kMaxInMemoryPixels, kMaxInMemorySide));
  if (plan.streamed && request.backend == Backend::gl && !in_memory)
    throw std::invalid_argument(fmt::format(
        "{} is {}x{} pixels, more than --backend gl renders ({} pixels and {} a side); use "
        "--backend cpu, which streams it tile by tile",
        what, region.width, region.height, kMaxInMemoryPixels, kMaxInMemorySide));
  plan.exr.mipmap = request.mipmap;
  plan.exr.half = request.half;
  // A NaN scale passes a range check (every comparison with it is false): the grid check refuses
  // it with the origin and positions beyond the precise range (render.hpp); each mip level's grid
  // too, since its last pixels may reach further than level 0's.
  const std::string grid_request = fmt::format(
      "--origin {} with --scale {} and {}",
      quoted(request.text.origin, fmt::format("{},{}", request.origin.x, request.origin.y)),
      request.scale, what);
  for (const Grid& level : tiled_exr_levels(plan.grid, plan.streamed && request.mipmap))
    check_grid(level, grid_request);
  // Each thread holds one tile's samples (docs/design.md §9); a streamed render holds one strip of
  // kExrTileSide rows, not the image.
  const int held_rows = plan.streamed ? std::min(kExrTileSide, plan.grid.height) : plan.grid.height;
  plan.threads = budgeted_threads(
      plan.grid.width, held_rows, request.tile, request.supersample, request.threads,
      [&](int threads) {
        return fmt::format("rendering {}x{} pixels with --supersample {}, --tile {} and {} threads",
                           plan.grid.width, held_rows, request.supersample, request.tile, threads);
      },
      "use fewer --threads or a smaller --supersample, --tile or --size");
  return plan;
}

void check_periodic_backend(Backend backend) {
  if (backend == Backend::gl)
    throw std::invalid_argument(
        "--periodic renders on the CPU (each method's scalar evaluator, docs/render.md): use "
        "--backend cpu");
}

int budgeted_threads(int width, int rows, int tile, int supersample, int requested,
                     const std::function<std::string(int threads)>& request,
                     const std::string& remedy, int channels) {
  const auto peak = [&](int threads) {
    return render_peak_bytes(width, rows, tile, supersample, threads, channels);
  };
  int threads = resolve_thread_count(requested);
  if (requested == 0)
    while (threads > 1 && peak(threads) > kMemoryBudgetBytes) --threads;
  check_memory_budget(peak(threads), request(threads), remedy);
  return threads;
}

}  // namespace stochtex::renderer
