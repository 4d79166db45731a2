// `stochtex gaussian INPUT -o IMAGE --size WxH`: the exemplar's Gaussian version (asymptotic
// discrete spot noise, ADSN), the texture that texton, lrp and gabor noise approximate. The ADSN
// is of the file's values as --colour-space says they are (auto: what the file says), and the
// output holds them as a render of a model of that colour space would: a photo's sRGB values go
// into a PNG as they are, with an sRGB chunk, and into OpenEXR decoded to linear light.

#include <fmt/core.h>

#include <cstdint>
#include <memory>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/memory_budget.hpp"
#include "io/image_io.hpp"

namespace stochtex::cli {

Command add_gaussian_command(CLI::App& app) {
  struct Options {
    std::string input;
    std::string output;
    std::string size;
    std::uint32_t seed = 0;
    int bit_depth = 8;
    std::string colour_space = "auto";
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("gaussian", "the exemplar's Gaussian version (ADSN)");
  command->add_option("INPUT", options->input, "exemplar image")->required();
  command->add_option("-o,--output", options->output, "image to write")->required();
  command->add_option("--size", options->size, "output size WIDTHxHEIGHT")->required();
  command->add_option("--seed", options->seed, "32-bit seed")->capture_default_str();
  command->add_option("--bit-depth", options->bit_depth, "PNG output bits per channel")
      ->capture_default_str()
      ->check(CLI::IsMember({8, 16}));
  command
      ->add_option("--colour-space", options->colour_space,
                   "what the exemplar's values are: auto (what the file says, as analyze reads "
                   "it), srgb, linear or data (written as they are)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "srgb", "linear", "data"}));
  return {command, [options] {
            const Size size = output_size(options->size);
            check_memory_budget(gaussian_peak_bytes(size.width, size.height),
                                fmt::format("the Gaussian version at --size {}", options->size),
                                "use a smaller --size");
            check_output_path(options->output, true, {options->input});
            ImageReadLimits limits;
            limits.check_declared = [&](int width, int height, int channels) {
              check_memory_budget(
                  gaussian_peak_bytes(size.width, size.height, width, height, channels),
                  fmt::format("the Gaussian version at --size {} of the {}x{} exemplar '{}'",
                              options->size, width, height, options->input),
                  "use a smaller --size or exemplar");
            };
            const ReadExemplar exemplar =
                read_exemplar(options->input, option_space(options->colour_space), limits);
            validate_exemplar(exemplar.image.view(), options->input);
            check_output_channels(options->output, exemplar.image.channels());
            const ImageF result =
                gaussian_version(exemplar.image.view(), size.width, size.height, options->seed);
            write_image(options->output, result.view(), options->bit_depth, exemplar.space);
            if (!exemplar.note.empty()) fmt::print(stderr, "{}\n", exemplar.note);
            fmt::print(stderr, "wrote {}\n", options->output);
            return 0;
          }};
}

}  // namespace stochtex::cli
