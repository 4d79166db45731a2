// `stochtex info MODEL`: what a model file holds (method, parameters, a material's maps, arrays),
// and with --export its image arrays as pictures.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "io/image_io.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

void export_model_images(const Model& model, const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder))
    throw Error(ErrorCode::io, fmt::format("cannot export into '{}': the folder does not exist; "
                                           "create it first",
                                           folder.string()));
  AtomicFileSet written;  // every picture or none
  for (auto& [name, image] : model_images(model)) {
    write_image(written, folder / (name + ".exr"), image.view());
    float peak = 0.0f;
    for (const float value : image.pixels()) peak = std::max(peak, std::abs(value));
    for (float& value : image.pixels()) value = 0.5f + 0.5f * value / std::max(peak, 1e-30f);
    write_image(written, folder / (name + ".png"), image.view());
  }
  written.commit();
}

void print_text(const Model& model, const std::string& path, const std::string& description) {
  const auto doc = nlohmann::json::parse(description);
  fmt::print("model     {}\nmethod    {}\nchannels  {}\n", path, model.method(), model.channels());
  if (model.maps().empty()) fmt::print("colour    {}\n", colour_space_name(model.colour_space()));
  if (const auto wrap = model.exemplar_wrap())
    fmt::print("wrap step x {:.2f}, y {:.2f}: the exemplar {}\n", wrap->x, wrap->y,
               wrap->largest() > kTileableWrapStep ? "is not tileable" : "tiles");
  for (const auto& [name, value] : doc["params"].items())
    fmt::print("  {} = {}\n", name, format_param(model.method(), name, value.get<double>()));
  for (const MapInfo& map : model.maps())
    if (map.derived_from.empty())
      fmt::print("map       {} ({}, {} channel{}, {})\n", map.name, map_kind_name(map.kind),
                 map.channels, map.channels == 1 ? "" : "s", colour_space_name(map.colour_space));
    else
      fmt::print("map       {} ({}, derived: {:.4g} times the gradient of {})\n", map.name,
                 map_kind_name(map.kind), map.slope_scale, map.derived_from);
  for (const auto& array : doc["arrays"])
    fmt::print("array     {} {}\n", array["name"].get<std::string>(), array["shape"].dump());
  fmt::print("data      {} bytes\n", doc["array_bytes"].get<std::size_t>());
}

}  // namespace

Command add_info_command(CLI::App& app) {
  struct Options {
    std::string model;
    bool json = false;
    std::string export_folder;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("info", "describe a model file");
  command->add_option("MODEL", options->model, "model file (.stx)")->required();
  command->add_flag("--json", options->json, "print one JSON document");
  command->add_option("--export", options->export_folder,
                      "write the model's image arrays (e.g. the texton) into this folder as "
                      "NAME.exr (values) and NAME.png (preview: 0.5 + 0.5 v / max|v|)");
  return {command, [options] {
            const Model model = load_model(options->model);
            if (!options->export_folder.empty()) export_model_images(model, options->export_folder);
            const std::string description = describe_model(model);
            if (options->json)
              fmt::print("{}\n", description);
            else
              print_text(model, options->model, description);
            return 0;
          }};
}

}  // namespace stochtex::cli
