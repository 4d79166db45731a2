#pragma once
// A render as the front ends ask for it (docs/design.md §3, "the renderer"): the settings of
// `stochtex render` as typed values, and the plan made of them before any work: the grid, whether
// the output is held in memory or streamed strip by strip into a tiled OpenEXR file, and the
// threads the memory budget allows. Every refusal is one sentence that names the settings by
// stochtex render's options (--size, --region, --tiled...), as its users meet them; thrown as
// std::invalid_argument, a usage error.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "io/tiled_exr.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/render.hpp"

namespace stochtex::renderer {

// An image held in memory (render, synth, gaussian, render-mesh) has each side at most 32768 and
// at most 64 Mpixel (an 8192 x 8192 image, 1 GiB of RGBA floats), so that larger requests are
// refused up front rather than attempted as multi-gigabyte allocations. A render streamed to a
// tiled OpenEXR file has sides up to kMaxStreamedSide and any number of pixels.
inline constexpr int kMaxInMemorySide = 32768;
inline constexpr std::int64_t kMaxInMemoryPixels = std::int64_t{1} << 26;
inline constexpr int kMaxStreamedSide = 1 << 20;
bool fits_in_memory(std::int64_t width, std::int64_t height);

// The scales a render takes, in exemplar pixels per output pixel: `stochtex render --scale`
// (CLI::Range(kMinScale, kMaxScale)) and the studio's render.png refuse any other.
inline constexpr double kMinScale = 1e-6;
inline constexpr double kMaxScale = 1e6;

// What evaluates the grids: the CPU reference, or the GL backend (renderer/backends.hpp).
enum class Backend { cpu, gl };

// Pixels [x, x + width) x [y, y + height) of the whole image.
struct PixelRegion {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};

// How refusals quote the size, region and origin: as the caller was given them (stochtex
// render's --size, --region and --origin text, which a user recognises); an empty one is written
// from the request's numbers.
struct RequestText {
  std::string size;
  std::string region;
  std::string origin;
};

// The settings of a render. The ranges that stochtex render's options check (threads 0 to
// kMaxThreads, supersample 1 to 64, tile 1 to 4096, bit depth 8 or 16, a scale of kMinScale to
// kMaxScale) are the caller's to keep; plan_render checks the rest.
struct RenderRequest {
  // The whole image, each side 1 to kMaxStreamedSide, and the pixels of it that are rendered
  // and written (none: all of them), equal to the same pixels of the whole render.
  int width = 512;
  int height = 512;
  std::optional<PixelRegion> region;
  Vec2d origin;  // the model-space position of the image's top-left corner
  double scale = 1.0;
  std::uint32_t seed = 0;
  int threads = 0;  // 0: as many cores as the memory budget allows
  int supersample = 1;
  int tile = 64;
  bool filter = true;
  std::optional<CpuTarget> cpu_target;  // none: the best this machine runs
  Backend backend = Backend::cpu;
  GlFilter gl_filter = GlFilter::exact;
  // The output file: a tiled OpenEXR file (streamed strip by strip, with mip levels, with half
  // floats), and a PNG's bits per channel.
  bool tiled = false;
  bool mipmap = false;
  bool half = false;
  int bit_depth = 8;
  // A tileable bake (docs/render.md): the field repeats with the whole image, request_period.
  bool periodic = false;
  RequestText text;
};

// The model-space period of a periodic request: the whole image, (width, height) * scale; a
// region and every mip level sample the same field.
inline Vec2d request_period(const RenderRequest& request) {
  return {request.width * request.scale, request.height * request.scale};
}

// What a render does: the grid of its region of the image, whether it is streamed into a tiled
// OpenEXR file (with the file's options) rather than held in memory, and its CPU threads.
struct RenderPlan {
  Grid grid;
  bool streamed = false;
  TiledExrOptions exr;
  int threads = 1;
};

// The plan of `request` written to `output` (an image path; .exr is the tiled OpenEXR format):
// streamed for .exr beyond the in-memory limit or with tiled, mipmap or half, in memory
// otherwise. Refuses, before any work, a size or region out of range, tiled OpenEXR options for
// another format, mip levels of a region, --periodic on the GL backend (check_periodic_backend),
// an in-memory output beyond its limit, a GL render beyond it, a grid (of any mip level) beyond
// the precise range of positions (check_grid), and a CPU render beyond the memory budget
// (budgeted_threads).
RenderPlan plan_render(const RenderRequest& request, const std::string& output);

// Refuses --periodic (render's, render-mesh's) on a backend without periodic evaluation: only the
// CPU's scalar evaluators have it (docs/render.md), the GL backend's GLSL does not.
void check_periodic_backend(Backend backend);

// The threads of a CPU render that holds width x rows pixels of `channels` channels at once (the
// image, or the strip a streamed render holds) with `tile` and `supersample` (docs/design.md §9):
// `requested`, or for 0 as many of the machine's cores as fit in the memory budget, at least one.
// Refuses a render whose peak with them is beyond the budget (check_memory_budget):
// `request(threads)` names the render in the sentence and `remedy` says what to change.
int budgeted_threads(int width, int rows, int tile, int supersample, int requested,
                     const std::function<std::string(int threads)>& request,
                     const std::string& remedy, int channels = 4);

}  // namespace stochtex::renderer
