#include "renderer/render_file.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "core/memory_budget.hpp"
#include "io/image_io.hpp"
#include "io/tiled_exr.hpp"
#include "model/model_colour.hpp"
#include "stochtex/error.hpp"
#include "stochtex/material.hpp"

namespace stochtex::renderer {

std::string map_output(std::string output, std::string_view name) {
  constexpr std::string_view field = "{map}";
  for (auto at = output.find(field); at != std::string::npos;
       at = output.find(field, at + name.size()))
    output.replace(at, field.size(), name);
  return output;
}

namespace {

// Renders grids on a backend (the whole image, or one strip after another of a tiled file), with
// one progress across all of them: `total_pixels` is the pixels of every grid.
class TrackedBackend {
 public:
  TrackedBackend(GridBackend& backend, std::uint64_t total_pixels,
                 const std::function<void(double)>& progress)
      : backend_(backend), total_(static_cast<double>(total_pixels)), progress_(progress) {}

  void operator()(const Grid& grid, ImageView<float> out) {
    const double pixels = static_cast<double>(grid.width) * grid.height;
    backend_.render(grid, out, [&](double fraction) {
      if (progress_) progress_((done_ + fraction * pixels) / total_);
    });
    done_ += pixels;
  }

 private:
  GridBackend& backend_;
  double total_;
  double done_ = 0.0;
  const std::function<void(double)>& progress_;
};

// The channels of each map's image as split_maps writes it.
int written_channels(const MapInfo& map) {
  return map.kind == MapKind::normal ? 3 : map.channels;
}

// Checks a material's outputs before the render: {map} in the name exactly when the model has
// maps, every map's file writable, in memory and within the memory budget (the render, the maps
// cut from it and one map's encoded copy).
void check_map_outputs(const Model& model, const RenderPlan& plan, const std::string& output,
                       const std::string& input) {
  const bool per_map = output.find("{map}") != std::string::npos;
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
  for (const MapInfo& map : model.maps()) {
    const std::string path = map_output(output, map.name);
    check_output_path(path, true, {input});
    check_output_channels(path, written_channels(map));
  }
  // In memory: the whole grid; streamed: one strip and its margin (stream_maps).
  const int rows = plan.streamed ? kExrTileSide + 2 : plan.grid.height;
  check_memory_budget(
      maps_peak_bytes(model, plan.grid.width, rows, plan.streamed),
      fmt::format("rendering the {} maps of a {}x{} material{}", model.maps().size(),
                  plan.grid.width, plan.streamed ? rows : plan.grid.height,
                  plan.streamed ? " strip" : ""),
      "render a smaller --size, or --region pieces");
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

// The pixels render_maps renders for `grid`: with a derived normal map, a one-pixel margin.
std::uint64_t material_pixels(const Model& model, const Grid& grid) {
  const bool margin = std::any_of(model.maps().begin(), model.maps().end(),
                                  [](const MapInfo& map) { return !map.derived_from.empty(); });
  return static_cast<std::uint64_t>(grid.width + (margin ? 2 : 0)) *
         static_cast<std::uint64_t>(grid.height + (margin ? 2 : 0));
}

// A material's maps to one tiled .exr file each, strip by strip: each strip is one render_maps
// call for every map (docs/materials.md).
void stream_maps(const Model& model, const RenderPlan& plan, GridBackend& backend,
                 const std::function<void(double)>& progress, const std::string& output) {
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
  TrackedBackend renderer(backend, pixels, progress);
  TiledExrOptions options = plan.exr;
  options.threads = plan.threads;
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

void render_model(const Model& model, const RenderPlan& plan, const RenderRequest& request,
                  GridBackend& backend, const std::function<void(double)>& progress,
                  const std::string& output) {
  const Grid& grid = plan.grid;
  if (!model.maps().empty() && plan.streamed) {
    stream_maps(model, plan, backend, progress, output);
    return;
  }
  if (!model.maps().empty()) {
    TrackedBackend renderer(backend, material_pixels(model, grid), progress);
    const std::vector<NamedImage> maps = render_maps(
        model, grid, [&](const Grid& part, ImageView<float> out) { renderer(part, out); });
    AtomicFileSet files;  // all the maps or none
    for (std::size_t m = 0; m < maps.size(); ++m)
      write_image(files, map_output(output, maps[m].name), maps[m].image.view(), request.bit_depth,
                  rendered_space(model.maps()[m].colour_space));
    files.commit();
    return;
  }
  if (!plan.streamed && output_image_format(output) == ImageFormat::png) {
    // Each strip is encoded while the next renders (write_png_strips).
    TrackedBackend renderer(backend, static_cast<std::uint64_t>(grid.width) * grid.height,
                            progress);
    write_png_strips(output, grid.width, grid.height, model.channels(), request.bit_depth,
                     rendered_space(model.colour_space()),
                     [&](int first_row, ImageView<float> out) {
                       Grid strip = grid;
                       strip.height = out.height;
                       strip.first_pixel_y += first_row;
                       renderer(strip, out);
                     });
    return;
  }
  if (!plan.streamed) {
    write_image(output, render_image(model, grid, backend, progress).view(), request.bit_depth,
                rendered_space(model.colour_space()));
    return;
  }
  TrackedBackend renderer(backend, tiled_exr_pixels(grid, plan.exr.mipmap), progress);
  TiledExrOptions options = plan.exr;
  options.threads = plan.threads;
  write_tiled_exr(output, grid, model.channels(), options,
                  [&](const Grid& strip, ImageView<float> out) { renderer(strip, out); });
}

}  // namespace

std::uint64_t maps_peak_bytes(const Model& model, int width, int rows, bool streamed) {
  std::uint64_t bytes_per_pixel = 4 * static_cast<std::uint64_t>(model.channels());
  const auto add = [&](int written) {
    bytes_per_pixel += (streamed ? 8 : 6) * static_cast<std::uint64_t>(written);
  };
  if (model.maps().empty()) add(model.channels());
  for (const MapInfo& map : model.maps()) add(written_channels(map));
  return bytes_per_pixel * static_cast<std::uint64_t>(std::max(width, 0) + 2) *
         static_cast<std::uint64_t>(std::max(rows, 0));
}

ImageF render_image(const Model& model, const Grid& grid, GridBackend& backend,
                    const std::function<void(double)>& progress) {
  ImageF image(grid.width, grid.height, model.channels());
  TrackedBackend(backend, static_cast<std::uint64_t>(grid.width) * grid.height, progress)(
      grid, image.view());
  return image;
}

std::vector<std::string> render_to_file(const std::function<Model()>& make_model,
                                        const RenderRequest& request, const std::string& output,
                                        const std::string& input,
                                        const BackendFactory& make_backend,
                                        const std::function<void(double)>& progress) {
  check_output_path(map_output(output, "map"), true, {input});
  const RenderPlan plan = plan_render(request, output);
  set_cpu_target(request.cpu_target.value_or(available_cpu_targets().back()));
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
  const std::unique_ptr<GridBackend> backend = make_backend(model, request, plan.threads);
  render_model(model, plan, request, *backend, progress, output);
  if (model.maps().empty()) return {output};
  std::vector<std::string> written;
  for (const MapInfo& map : model.maps()) written.push_back(map_output(output, map.name));
  return written;
}

}  // namespace stochtex::renderer
