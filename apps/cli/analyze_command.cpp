// `stochtex analyze INPUT -m METHOD -o MODEL.stx`: exemplar (or, for the methods whose registry
// row has a target capability, a target spectrum) -> model file.

#include "analyze_command.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/file_message.hpp"
#include "core/memory_budget.hpp"
#include "io/exemplar_region.hpp"
#include "io/image_io.hpp"
#include "metrics/metrics.hpp"
#include "progress.hpp"
#include "registry.hpp"
#include "stochtex/material.hpp"

namespace stochtex::cli {
void add_analyze_options(CLI::App* command, AnalyzeOptions& options) {
  auto* input = command->add_option("INPUT", options.input,
                                    "exemplar image (PNG, JPEG, TIFF, WebP, TGA, OpenEXR or PFM)");
  std::string target_help = "continuous target spectrum instead of INPUT (" +
                            methods_with(CapabilityKind::target) + " only):";
  for (const MethodInfo& method : methods())
    if (const TargetCapability* capability = target_capability(method.name))
      target_help += " " + std::string(capability->help);
  auto* target = command->add_option("--target", options.target, target_help)->excludes(input);
  command
      ->add_option("--map", options.maps,
                   "a material's map NAME[:KIND]=FILE instead of INPUT, repeatable: the maps of "
                   "one surface, aligned, analysed together (docs/materials.md). KIND is colour, "
                   "normal, height or scalar; by default normal for normal, height for height, "
                   "displacement or bump, scalar for roughness, metallic, ao, opacity and the "
                   "like, else colour")
      ->excludes(input)
      ->excludes(target);
  command
      ->add_option("--normal-y", options.normal_y,
                   "which way the green channel of a --map normal map points: up (OpenGL) or "
                   "down (DirectX)")
      ->check(CLI::IsMember({"up", "down"}))
      ->capture_default_str();
  command->add_flag("--synthesise-normals", options.synthesise_normals,
                    "synthesise a --map normal map as two channels of its own; by default texton, "
                    "lrp and gabor derive it from the synthesised height map when the material "
                    "has one and the normal map follows its gradient (docs/materials.md)");
  command
      ->add_option("--method,-m", options.method,
                   "texture method (see `stochtex methods`), or auto: chosen from the exemplar's "
                   "measured structure, saying why (docs/comparison.md)")
      ->required();
  command->add_option("-p,--param", options.params,
                      "method parameter key=value (repeatable; listed below)");
  command->footer("\nmethods and parameters (-p name=default):\n" + methods_text());
  command
      ->add_option("--analysis-seed", options.seed, "seed of the analysis' random initialisation")
      ->capture_default_str();
  command
      ->add_option("--colour-space", options.colour_space,
                   "what the exemplar's values are: auto (what the file says: a PNG is sRGB "
                   "unless its sRGB, gAMA, cICP or ICC profile chunks say otherwise, OpenEXR and "
                   "PFM are linear), srgb (an ordinary photo: the model renders linear light, "
                   "each filtered value the mean of the decoded colour), linear (linear light) or "
                   "data (numbers that are not colour, filtered and rendered as they are); for "
                   "--map, the colour maps' (a map's own :COLOUR_SPACE overrides it; every other "
                   "kind is data)")
      ->check(CLI::IsMember({"auto", "srgb", "linear", "data"}))
      ->capture_default_str();
  command->add_option("--crop", options.crop,
                      "analyse this part of the exemplar (and of each --map): WIDTHxHEIGHT+X+Y "
                      "in pixels, as 1024x1024+1500+800");
  command
      ->add_option("--scale-input", options.scale_input,
                   "analyse the exemplar (after --crop) downscaled by this factor, in (0, 1], "
                   "averaging linear light; by default an exemplar longer than the method "
                   "analyses (`stochtex methods`) is downscaled to it, and a note says so")
      ->check(scale_input_validator());
}

CLI::Validator scale_input_validator() {
  return CLI::Validator(
      [](const std::string& text) {
        double value = 0.0;
        return CLI::detail::lexical_cast(text, value) && value > 0.0 && value <= 1.0
                   ? std::string()
                   : "--scale-input " + text + " is not a factor above 0 and at most 1";
      },
      "FACTOR in (0, 1]");
}

namespace {

// The side `method` analyses by default; for --method auto, the largest of any method's, so that
// the exemplar is measured at least as finely as the chosen method analyses it.
int region_side(const std::string& method) {
  if (method != kAutoMethod) return analysis_side(method);
  int side = 0;
  for (const MethodInfo& info : methods()) side = std::max(side, analysis_side(info.name));
  return side;
}

// Refuses, before decoding, an image whose region `method` cannot analyse within the memory
// budget, or whose --crop is not inside it.
// (For --method auto, the method is not known before the exemplar is measured: its analysis is
// checked by analyze(), before any work.)
ImageReadLimits analysis_limits(const std::string& method, const std::string& path,
                                const ExemplarRegion& region) {
  ImageReadLimits limits;
  limits.check_declared = [method, path, region](int width, int height, int channels) {
    // The decoded image and its region live together while the region is made.
    check_memory_budget(std::uint64_t(width) * height * channels * sizeof(float) * 2,
                        "reading the " + std::to_string(width) + "x" + std::to_string(height) +
                            " exemplar '" + path + "'",
                        "crop or downscale the exemplar");
    const RegionSize size = region_size(width, height, region, region_side(method),
                                        stochtex::quoted(std::filesystem::path(path)));
    if (method != kAutoMethod)
      check_analysis_request(method, size.width, size.height, channels, path);
  };
  return limits;
}

ReadExemplar read_region(const std::string& path, std::optional<ColourSpace> space,
                         const AnalyzeOptions& options) {
  ExemplarRegion region;
  if (!options.crop.empty()) region.crop = parse_crop(options.crop, "--crop");
  region.scale = options.scale_input;
  std::string note;
  ReadExemplar exemplar = read_exemplar_region(path, space, options.method, region, note);
  if (!note.empty()) fmt::print(stderr, "{}\n", note);
  return exemplar;
}

}  // namespace

ReadExemplar read_exemplar_region(const std::string& path, std::optional<ColourSpace> space,
                                  const std::string& method, const ExemplarRegion& region,
                                  std::string& scale_note) {
  ReadExemplar exemplar = read_exemplar(path, space, analysis_limits(method, path, region));
  std::string note;
  exemplar.image =
      exemplar_region(std::move(exemplar.image), exemplar.space, region, region_side(method),
                      stochtex::quoted(std::filesystem::path(path)), method, &note);
  scale_note = note.empty() ? std::string()
                            : note +
                                  "; give --scale-input 1 to analyse every pixel, or --crop "
                                  "to choose a part";
  return exemplar;
}

namespace {

Model analyze_maps(const AnalyzeOptions& options, const ParamValues& params,
                   std::vector<std::string>* notes) {
  std::vector<MapArgument> arguments;
  for (const auto& text : options.maps) arguments.push_back(parse_map_argument(text));
  std::vector<ImageF> images;
  std::vector<MaterialMap> maps;
  for (const auto& argument : arguments) {
    const MapKind kind = argument.kind.value_or(default_map_kind(argument.name));
    // A colour map in the option's space or its own; every other kind is data unless it says
    // otherwise (which analyze_material refuses).
    const std::optional<ColourSpace> space = argument.colour_space ? argument.colour_space
                                             : kind == MapKind::colour
                                                 ? option_space(options.colour_space)
                                                 : ColourSpace::data;
    ReadExemplar map = read_region(argument.file, space, options);
    if (notes && !map.note.empty()) notes->push_back(map.note);
    images.push_back(std::move(map.image));
    maps.push_back({argument.name, kind, {}, argument.file, map.space});
  }
  for (std::size_t i = 0; i < maps.size(); ++i) maps[i].image = images[i].view();
  Progress progress("analyse");
  progress.message(
      fmt::format("analysing a material of {} maps with {}...", maps.size(), options.method));
  return analyze_material(
      options.method, maps, params, options.seed,
      {.normal_y_down = options.normal_y == "down", .derive_normals = !options.synthesise_normals},
      [&](double fraction) { progress(fraction); });
}

// The model of `--target TEXT`, through the method's target capability.
Model target_model(const AnalyzeOptions& options, const ParamValues& params) {
  const TargetCapability* target = target_capability(options.method);
  if (target == nullptr)
    throw std::invalid_argument("--target is a continuous spectrum for --method " +
                                methods_with(CapabilityKind::target) + " only, not " +
                                options.method);
  return target->model(options.target, params, options.seed);
}

// --method auto measures one exemplar: refused, in one sentence, with what it cannot measure.
void check_auto_request(const AnalyzeOptions& options) {
  if (!options.target.empty())
    throw std::invalid_argument(
        "--method auto chooses by measuring an exemplar, and --target is a "
        "spectrum: give --method " +
        methods_with(CapabilityKind::target) + " with --target");
  if (!options.maps.empty())
    throw std::invalid_argument(
        "--method auto measures one exemplar, not a material's maps: "
        "give the method, or run auto on the colour map to choose it");
  if (!options.params.empty())
    throw std::invalid_argument(
        "-p sets a named method's parameter, and --method auto chooses "
        "the method from the exemplar: give the method with -p");
}

}  // namespace

Model run_analyze(const AnalyzeOptions& options, std::vector<std::string>* notes) {
  const bool automatic = options.method == kAutoMethod;
  if (automatic) check_auto_request(options);
  const ParamValues params =
      automatic ? ParamValues{} : resolve_params(options.method, parse_params(options.params));
  if (!options.target.empty()) return target_model(options, params);
  if (!options.maps.empty()) return analyze_maps(options, params, notes);
  if (options.input.empty())
    throw std::invalid_argument("give an exemplar INPUT, a material's --map NAME=FILE or, for " +
                                methods_with(CapabilityKind::target) + ", a --target spectrum");
  ReadExemplar exemplar = read_region(options.input, option_space(options.colour_space), options);
  validate_exemplar(exemplar.image.view(), options.input);
  std::string method = options.method;
  if (automatic) {
    const MethodChoice choice = choose_method(exemplar.image.view());
    method = choice.method;
    if (notes) notes->push_back(options.input + ": --method auto chose " + choice.reason);
    // Measured at the largest side any method analyses; the chosen one's may be smaller.
    if (options.scale_input == 0.0) {
      std::string note;
      exemplar.image =
          exemplar_region(std::move(exemplar.image), exemplar.space, {}, analysis_side(method),
                          stochtex::quoted(std::filesystem::path(options.input)), method, &note);
      if (!note.empty())
        fmt::print(stderr, "{}; give --scale-input 1 to analyse every pixel\n", note);
    }
  }
  if (notes && !exemplar.note.empty()) notes->push_back(exemplar.note);
  Progress progress("analyse");
  progress.message(fmt::format("analysing {} with {}{}...", options.input, method,
                               automatic ? " (chosen by --method auto)" : ""));
  Model model = analyze(
      method, exemplar.image.view(), params, options.seed, options.input,
      [&](double fraction) { progress(fraction); }, exemplar.space);
  const std::optional<WrapSteps> wrap = model.exemplar_wrap();
  if (notes && wrap && wrap->largest() > kTileableWrapStep) {
    // Tiling's patches read across the border unless it makes the exemplar tileable; the
    // Gaussian methods estimate the spectrum without the border (docs/inputs.md).
    const auto made = model.params().find("make_tileable");
    const bool seams = made != model.params().end() && made->second == 0.0;
    notes->push_back(fmt::format(
        "{}: not tileable: a repeat of it steps {:.1f} times as much at its wrap as between "
        "neighbouring pixels (x {:.1f}, y {:.1f}); {}",
        options.input, wrap->largest(), wrap->x, wrap->y,
        seams ? "tiling's patches show that seam (make_tileable is off: a repeated pattern is "
                "left as is unless asked, docs/inputs.md)"
              : "the analysis keeps that seam out of the renders (docs/inputs.md)"));
  }
  return model;
}

Command add_analyze_command(CLI::App& app) {
  struct Options {
    AnalyzeOptions analyze;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("analyze", "exemplar -> model file (.stx)");
  add_analyze_options(command, options->analyze);
  command->add_option("-o,--output", options->output, "model file to write (.stx)")->required();
  return {command, [options] {
            std::vector<std::filesystem::path> inputs{options->analyze.input};
            for (const auto& text : options->analyze.maps)
              inputs.emplace_back(parse_map_argument(text).file);
            check_output_path(options->output, false, inputs);
            std::vector<std::string> notes;
            save_model(run_analyze(options->analyze, &notes), options->output);
            fmt::print(stderr, "wrote {}\n", options->output);
            for (const std::string& note : notes) fmt::print(stderr, "{}\n", note);
            return 0;
          }};
}

}  // namespace stochtex::cli
