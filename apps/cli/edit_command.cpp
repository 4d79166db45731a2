// `stochtex edit`: group editing of a Gabor noise model (Gabor noise by example, section 8). The
// Gaussians of the model's spectrum are grouped automatically after the Wold decomposition
// (periodic peaks, strongly anisotropic lines, the stochastic rest); an edit rotates, scales and
// translates a group in frequency and changes its magnitude and bandwidth.

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <variant>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/image_io.hpp"
#include "methods/gabor/edit_analysis.hpp"
#include "model/model_data.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

struct EditOptions {
  std::string model;
  std::string output;
  std::string group = "all";
  double rotate_degrees = 0.0;
  double scale = 1.0;
  std::string translate = "0,0";
  double magnitude = 1.0;
  double bandwidth = 1.0;
  bool list_groups = false;
  bool json = false;
};

constexpr std::array<gabor::WoldComponent, 3> kComponents = {gabor::WoldComponent::periodic,
                                                             gabor::WoldComponent::anisotropic,
                                                             gabor::WoldComponent::stochastic};

// Frequencies are in cycles per exemplar pixel; a translation beyond Nyquist moves every
// Gaussian out of the pixel grid's reach.
struct Translation {
  double x = 0.0;
  double y = 0.0;
};

Translation parse_translation(const std::string& text) {
  if (const std::optional<Vec2d> t = parse_number_pair(text);
      t && std::abs(t->x) <= 1.0 && std::abs(t->y) <= 1.0)
    return {t->x, t->y};
  throw std::invalid_argument(
      "--translate must be FX,FY in cycles per pixel, each within [-1, 1], "
      "e.g. 0.05,-0.1, not '" +
      text + "'");
}

// The bandwidths are quantised to a_b = 2^-b a_0 (section 4.3): a factor of 2^k shifts the band
// index by -k.
int bandwidth_shift(double factor) {
  const double exponent = std::log2(factor);
  if (!(factor > 0.0) || exponent != std::round(exponent) || std::abs(exponent) >= gabor::kMaxBands)
    throw std::invalid_argument(fmt::format(
        "--bandwidth must be a power of two such as 0.5 or 2 (the bandwidths are quantised to "
        "powers of two, section 4.3 of the paper), not {}",
        factor));
  return -static_cast<int>(exponent);
}

const gabor::GaborModel& gabor_model(const Model& model, const std::string& path) {
  const auto* gabor = std::get_if<gabor::GaborModel>(&model.data().model);
  if (gabor == nullptr)
    throw std::invalid_argument(
        fmt::format("'{}' is a {} model; `stochtex edit` edits gabor "
                    "models only (stochtex analyze INPUT --method gabor)",
                    path, model.method()));
  return *gabor;
}

void list_groups(const gabor::GaborModel& model, const std::vector<gabor::WoldComponent>& labels,
                 bool json) {
  std::array<std::size_t, 3> counts{};
  std::array<double, 3> variances{};
  double total = 0.0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const auto slot = static_cast<std::size_t>(labels[i]);
    ++counts[slot];
    variances[slot] += model.gaussians()[i].variance;
    total += model.gaussians()[i].variance;
  }
  const auto share = [&](std::size_t slot) { return total > 0.0 ? variances[slot] / total : 0.0; };
  if (json) {
    nlohmann::ordered_json doc{{"gaussians", labels.size()}};
    for (const gabor::WoldComponent component : kComponents) {
      const auto slot = static_cast<std::size_t>(component);
      doc["groups"][std::string(gabor::component_name(component))] = {
          {"gaussians", counts[slot]}, {"variance_share", share(slot)}};
    }
    fmt::print("{}\n", doc.dump(2));
    return;
  }
  fmt::print("{:<14}{:>10}{:>16}\n", "group", "gaussians", "variance share");
  for (const gabor::WoldComponent component : kComponents) {
    const auto slot = static_cast<std::size_t>(component);
    fmt::print("{:<14}{:>10}{:>15.1f}%\n", gabor::component_name(component), counts[slot],
               100.0 * share(slot));
  }
}

void add_edit_options(CLI::App* command, EditOptions& options) {
  command->add_option("MODEL", options.model, "gabor model file (.stx)")->required();
  command->add_option("-o,--output", options.output, "edited model file to write (.stx)");
  command->add_option("--group", options.group, "which Gaussians the edit changes")
      ->capture_default_str()
      ->check(CLI::IsMember({"all", "periodic", "anisotropic", "stochastic"}));
  command
      ->add_option("--rotate", options.rotate_degrees,
                   "rotate the group's frequencies by DEG degrees, counter-clockwise")
      ->capture_default_str();
  command
      ->add_option("--scale", options.scale,
                   "multiply the group's frequencies by S (> 1: finer detail)")
      ->capture_default_str();
  command
      ->add_option("--translate", options.translate,
                   "add FX,FY cycles per pixel to the group's frequencies")
      ->capture_default_str();
  command
      ->add_option("--magnitude", options.magnitude,
                   "multiply the group's kernel magnitude K by this (the variance by its square)")
      ->capture_default_str();
  command
      ->add_option("--bandwidth", options.bandwidth,
                   "multiply the group's bandwidth a by this power of two (< 1: sharper spectral "
                   "Gaussians, longer-range kernels); each Gaussian keeps its variance")
      ->capture_default_str();
  command->add_flag("--list-groups", options.list_groups,
                    "print how many Gaussians and how much variance each group holds, and write "
                    "nothing");
  command->add_flag("--json", options.json, "with --list-groups: print one JSON document");
}

// Lists the groups (and writes nothing), or writes the edited model (save_model writes
// atomically: a failure never leaves a partial file).
void run_edit(const EditOptions& options) {
  // Usage errors first, before any file is read.
  if (options.output.empty() && !options.list_groups)
    throw std::invalid_argument("edit needs -o OUT.stx for the edited model (or --list-groups)");
  if (options.json && !options.list_groups)
    throw std::invalid_argument("--json goes with --list-groups");
  if (!std::isfinite(options.rotate_degrees) || !std::isfinite(options.scale) ||
      !(options.scale > 0.0))
    throw std::invalid_argument(
        fmt::format("--rotate must be finite and --scale a positive number, not {} and {}",
                    options.rotate_degrees, options.scale));
  // The variance grows by the square: up to 1e3, variances (about 10 after analysis) stay far
  // within the model value range (model/value_range.hpp).
  constexpr double kMaxMagnitude = 1e3;
  if (!(options.magnitude >= 0.0 && options.magnitude <= kMaxMagnitude))
    throw std::invalid_argument(fmt::format("--magnitude must be a number from 0 to {}, not {}",
                                            kMaxMagnitude, options.magnitude));
  const Translation translation = parse_translation(options.translate);
  gabor::SpectrumEdit edit;
  edit.rotation = options.rotate_degrees * std::numbers::pi / 180.0;
  edit.scale = options.scale;
  edit.translation_x = translation.x;
  edit.translation_y = translation.y;
  edit.magnitude = options.magnitude;
  edit.bandwidth_shift = bandwidth_shift(options.bandwidth);
  if (!options.list_groups) check_output_path(options.output, false, options.model);

  const Model model = load_model(options.model);
  const gabor::GaborModel& gabor = gabor_model(model, options.model);
  const std::vector<gabor::WoldComponent> labels = gabor::wold_components(gabor);
  if (options.list_groups) {
    list_groups(gabor, labels, options.json);
    return;
  }

  std::vector<bool> selected(labels.size(), true);
  if (options.group != "all")
    for (std::size_t i = 0; i < labels.size(); ++i)
      selected[i] = gabor::component_name(labels[i]) == options.group;
  gabor::GaborModel edited = gabor::edit_gaussians(gabor, selected, edit);
  const std::size_t dropped = gabor.gaussians().size() - edited.gaussians().size();
  save_model(Model(std::make_shared<const ModelData>(
                 ModelData{model.params(), std::move(edited), model.data().maps})),
             options.output);
  fmt::print(
      stderr, "wrote {} ({} group: {} Gaussians edited{})\n", options.output, options.group,
      static_cast<std::size_t>(std::count(selected.begin(), selected.end(), true)),
      dropped > 0 ? fmt::format(", {} moved beyond Nyquist or to zero and dropped", dropped) : "");
}

}  // namespace

Command add_edit_command(CLI::App& app) {
  auto options = std::make_shared<EditOptions>();
  CLI::App* command = app.add_subcommand(
      "edit",
      "edit a gabor model's spectrum by groups of Gaussians: periodic peaks, anisotropic lines, "
      "the stochastic rest (section 8 of the Gabor noise paper)");
  add_edit_options(command, *options);
  return {command, [options] {
            run_edit(*options);
            return 0;
          }};
}

}  // namespace stochtex::cli
