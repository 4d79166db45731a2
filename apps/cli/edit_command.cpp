// `stochtex edit`: group editing of a Gabor noise model (Gabor noise by example, section 8). The
// Gaussians of the model's spectrum are grouped automatically after the Wold decomposition
// (periodic peaks, strongly anisotropic lines, the stochastic rest); an edit rotates, scales and
// translates a group in frequency and changes its magnitude and bandwidth.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
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
  gabor::EditRequest edit;
  std::string translate = "0,0";
  bool list_groups = false;
  bool json = false;
};

// --translate FX,FY within gabor::kMaxTranslation (the message quotes the text as typed).
void parse_translation(const std::string& text, gabor::EditRequest& edit) {
  const std::optional<Vec2d> t = parse_number_pair(text);
  if (!t || !(std::abs(t->x) <= gabor::kMaxTranslation) ||
      !(std::abs(t->y) <= gabor::kMaxTranslation))
    throw std::invalid_argument(
        "--translate must be FX,FY in cycles per pixel, each within [-1, 1], "
        "e.g. 0.05,-0.1, not '" +
        text + "'");
  edit.translate_x = t->x;
  edit.translate_y = t->y;
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
  if (json) {
    fmt::print("{}\n", gabor::groups_json(model, labels).dump(2));
    return;
  }
  fmt::print("{:<14}{:>10}{:>16}\n", "group", "gaussians", "variance share");
  for (const gabor::GroupShare& share : gabor::group_shares(model, labels))
    fmt::print("{:<14}{:>10}{:>15.1f}%\n", gabor::component_name(share.component), share.gaussians,
               100.0 * share.variance_share);
}

void add_edit_options(CLI::App* command, EditOptions& options) {
  command->add_option("MODEL", options.model, "gabor model file (.stx)")->required();
  command->add_option("-o,--output", options.output, "edited model file to write (.stx)");
  command->add_option("--group", options.edit.group, "which Gaussians the edit changes")
      ->capture_default_str()
      ->check(CLI::IsMember({"all", "periodic", "anisotropic", "stochastic"}));
  command
      ->add_option("--rotate", options.edit.rotate_degrees,
                   "rotate the group's frequencies by DEG degrees, counter-clockwise")
      ->capture_default_str();
  command
      ->add_option("--scale", options.edit.scale,
                   "multiply the group's frequencies by S (> 1: finer detail)")
      ->capture_default_str();
  command
      ->add_option("--translate", options.translate,
                   "add FX,FY cycles per pixel to the group's frequencies")
      ->capture_default_str();
  command
      ->add_option("--magnitude", options.edit.magnitude,
                   "multiply the group's kernel magnitude K by this (the variance by its square)")
      ->capture_default_str();
  command
      ->add_option("--bandwidth", options.edit.bandwidth,
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
  gabor::EditRequest request = options.edit;
  parse_translation(options.translate, request);
  const gabor::SpectrumEdit edit = gabor::spectrum_edit(request, "--");
  if (!options.list_groups) check_output_path(options.output, false, options.model);

  const Model model = load_model(options.model);
  const gabor::GaborModel& gabor = gabor_model(model, options.model);
  const std::vector<gabor::WoldComponent> labels = gabor::wold_components(gabor);
  if (options.list_groups) {
    list_groups(gabor, labels, options.json);
    return;
  }

  const std::vector<bool> selected = gabor::select_group(labels, request.group, "--");
  gabor::GaborModel edited = gabor::edit_gaussians(gabor, selected, edit);
  const std::size_t dropped = gabor.gaussians().size() - edited.gaussians().size();
  save_model(Model(std::make_shared<const ModelData>(
                 ModelData{model.params(), std::move(edited), model.data().maps})),
             options.output);
  fmt::print(
      stderr, "wrote {} ({} group: {} Gaussians edited{})\n", options.output, options.edit.group,
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
