// `stochtex mix A B -o MODEL.stx`: texton noise mixing (texton paper section 7), a model going
// from A's texton noise to B's along a ramp or as a grey mask says.

#include <fmt/core.h>

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analyze_command.hpp"
#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "io/image_io.hpp"
#include "progress.hpp"

namespace stochtex::cli {

Command add_mix_command(CLI::App& app) {
  struct Options {
    std::string a;
    std::string b;
    std::string output;
    std::vector<std::string> params;
    std::string steps;
    std::string ramp;
    std::string direction;
    std::string mask;
    std::string mask_scale;
    std::uint32_t seed = 0;
    std::string colour_space = "auto";
    std::string crop_a;
    std::string crop_b;
    double scale_input = 0.0;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "mix", "two exemplars -> a texton noise mixing model (.stx), A where rho = 0, B where 1");
  command->add_option("A", options->a, "first exemplar (rho = 0)")->required();
  command->add_option("B", options->b, "second exemplar (rho = 1), same channel count as A")
      ->required();
  command->add_option("-o,--output", options->output, "model file to write (.stx)")->required();
  command->add_option("--steps", options->steps, "number R of textons (default 21)");
  auto* ramp =
      command->add_option("--ramp", options->ramp,
                          "X0,X1: rho goes from 0 to 1 between these positions (default 0,1024)");
  auto* direction = command->add_option("--direction", options->direction,
                                        "DX,DY: the ramp's direction in model space (default 1,0)");
  auto* mask = command->add_option("--mask", options->mask,
                                   "grey image giving rho (black = A, white = B) over model space");
  command
      ->add_option("--mask-scale", options->mask_scale,
                   "model-space pixels per mask pixel (default 1)")
      ->needs(mask);
  mask->excludes(ramp)->excludes(direction);
  command->add_option("-p,--param", options->params,
                      "texton parameter key=value: support, order, iterations, mni (repeatable)");
  command
      ->add_option("--colour-space", options->colour_space,
                   "what both exemplars' values are, as analyze's --colour-space: auto, srgb, "
                   "linear (the mix then renders linear light) or data")
      ->check(CLI::IsMember({"auto", "srgb", "linear", "data"}))
      ->capture_default_str();
  command->add_option("--analysis-seed", options->seed, "seed of Algorithm 1's white-noise start")
      ->capture_default_str();
  command->add_option("--crop-a", options->crop_a,
                      "analyse this part of A: WIDTHxHEIGHT+X+Y in pixels, as 1024x1024+1500+800");
  command->add_option("--crop-b", options->crop_b, "analyse this part of B, as --crop-a");
  command
      ->add_option("--scale-input", options->scale_input,
                   "analyse A and B (after their crops) downscaled by this factor, in (0, 1], "
                   "averaging linear light; by default an exemplar longer than texton analyses "
                   "(`stochtex methods`) is downscaled to it, and a note says so")
      ->check(scale_input_validator());
  return {command, [options] {
            std::map<std::string, std::string, std::less<>> given = parse_params(options->params);
            const auto pair = [](const std::string& text, const char* option, const char* first,
                                 const char* second,
                                 std::map<std::string, std::string, std::less<>>& into) {
              if (text.empty()) return;
              const std::optional<Vec2d> value = parse_number_pair(text);
              if (!value)
                throw std::invalid_argument(fmt::format(
                    "{} must be two finite numbers separated by a comma, not '{}'", option, text));
              into[first] = fmt::format("{}", value->x);
              into[second] = fmt::format("{}", value->y);
            };
            pair(options->ramp, "--ramp", "ramp_start", "ramp_end", given);
            pair(options->direction, "--direction", "direction_x", "direction_y", given);
            if (!options->steps.empty()) given["steps"] = options->steps;
            if (!options->mask_scale.empty()) given["mask_scale"] = options->mask_scale;
            const ParamValues params = resolve_params("texton_mix", given);
            check_output_path(options->output, false, {options->a, options->b, options->mask});
            const std::optional<ColourSpace> space = option_space(options->colour_space);
            // Each exemplar is analysed by texton's Algorithm 1 (texton paper section 7), so
            // each is read down to the region texton analyses; what was scaled is said once both
            // are read, so that a refused B is the only line.
            std::vector<std::string> scale_notes;
            const auto read = [&](const std::string& path, const std::string& crop,
                                  const char* crop_option) {
              ExemplarRegion region;
              if (!crop.empty()) region.crop = parse_crop(crop, crop_option);
              region.scale = options->scale_input;
              ReadExemplar exemplar =
                  read_exemplar_region(path, space, "texton", region, scale_notes.emplace_back());
              validate_exemplar(exemplar.image.view(), path);
              return exemplar;
            };
            const ReadExemplar a = read(options->a, options->crop_a, "--crop-a");
            const ReadExemplar b = read(options->b, options->crop_b, "--crop-b");
            HeldImages held;
            held.add(a.image.width(), a.image.height(), a.image.channels(), options->a);
            held.add(b.image.width(), b.image.height(), b.image.channels(), options->b);
            if (a.space != b.space)
              throw Error(ErrorCode::invalid_input,
                          fmt::format("'{}' is {} and '{}' is {}; a mix needs both exemplars in "
                                      "one colour space: give --colour-space",
                                      options->a, colour_space_name(a.space), options->b,
                                      colour_space_name(b.space)));
            MixInputs inputs{a.image.view(), b.image.view(), options->a,
                             options->b,     std::nullopt,   "mask"};
            ImageF mask_image;
            if (!options->mask.empty()) {
              ImageReadLimits limits;
              limits.check_declared = held.check(options->mask);
              mask_image = read_image(options->mask, limits);
              inputs.mask = mask_image.view();
              inputs.mask_name = options->mask;
            }
            for (const std::string& note : scale_notes)
              if (!note.empty()) fmt::print(stderr, "{}\n", note);
            Progress progress("mix");
            progress.message(fmt::format("mixing {} and {}...", options->a, options->b));
            const Model model = mix(inputs, params, options->seed);
            save_model(a.space == ColourSpace::data ? model : with_colour_space(model, a.space),
                       options->output);
            fmt::print(stderr, "wrote {}\n", options->output);
            for (const ReadExemplar* exemplar : {&a, &b})
              if (!exemplar->note.empty()) fmt::print(stderr, "{}\n", exemplar->note);
            return 0;
          }};
}

}  // namespace stochtex::cli
