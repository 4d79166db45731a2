// `stochtex edit`: group editing of a model, for the methods whose registry row has an edit
// capability (methods/capabilities.hpp; gabor: section 8 of the Gabor noise paper). The options
// come from the capabilities' records: a group, then one option per field.

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/image_io.hpp"
#include "registry.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

// One field's option: its record, its text as typed (a pair is "X,Y"; CLI11 writes into it) and
// the option, which says whether it was given.
struct FieldOption {
  const EditField* field = nullptr;
  std::string typed;
  CLI::Option* option = nullptr;
};

struct EditOptions {
  std::string model;
  std::string output;
  std::string group;
  // The fields of every editing method, by name (a map: each text keeps its address).
  std::map<std::string, FieldOption, std::less<>> fields;
  bool list_groups = false;
  bool json = false;
};

// Every editing method's capability, in registry order.
std::vector<const EditCapability*> edit_capabilities() {
  std::vector<const EditCapability*> list;
  for (const MethodInfo& method : methods())
    if (const EditCapability* edit = edit_capability(method.name)) list.push_back(edit);
  return list;
}

// The numbers of the options given, read as their records say: a pair within its bound, quoted as
// typed when it is not.
EditValues edit_values(const EditOptions& options) {
  EditValues values{options.group, {}};
  for (const auto& [name, given] : options.fields) {
    if (given.option->count() == 0) continue;
    const EditField& field = *given.field;
    const std::string& text = given.typed;
    if (field.components == 1) {
      double number = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
      if (ec != std::errc() || end != text.data() + text.size())
        throw std::invalid_argument(fmt::format("--{} must be a number, not '{}'", name, text));
      values.numbers[name] = {number};
      continue;
    }
    const std::optional<Vec2d> pair = parse_number_pair(text);
    if (!pair || !(std::abs(pair->x) <= field.max_abs) || !(std::abs(pair->y) <= field.max_abs))
      throw std::invalid_argument(
          fmt::format("--{} must be two numbers X,Y, each within [-{}, {}] ({}), not '{}'", name,
                      field.max_abs, field.max_abs, field.help, text));
    values.numbers[name] = {pair->x, pair->y};
  }
  return values;
}

void add_edit_options(CLI::App* command, EditOptions& options) {
  const std::vector<const EditCapability*> capabilities = edit_capabilities();
  command->add_option("MODEL", options.model, "model file (.stx)")->required();
  command->add_option("-o,--output", options.output, "edited model file to write (.stx)");
  std::vector<std::string> groups;
  for (const EditCapability* edit : capabilities)
    for (std::string_view group : edit->groups)
      if (std::find(groups.begin(), groups.end(), group) == groups.end())
        groups.emplace_back(group);
  if (!groups.empty()) options.group = groups.front();
  command->add_option("--group", options.group, "which parts the edit changes")
      ->capture_default_str()
      ->check(CLI::IsMember(groups));
  for (const EditCapability* edit : capabilities)
    for (const EditField& field : edit->fields) {
      const std::string name(field.name);
      if (options.fields.contains(name)) continue;
      FieldOption& given = options.fields[name];
      given.field = &field;
      given.typed = field.components == 1 ? fmt::format("{}", field.default_value)
                                          : fmt::format("{0},{0}", field.default_value);
      given.option = command->add_option("--" + name, given.typed, std::string(field.help))
                         ->capture_default_str()
                         ->type_name(field.components == 1 ? "NUMBER" : "X,Y");
    }
  command->add_flag("--list-groups", options.list_groups,
                    "print what each group holds, and write nothing");
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
  const EditValues values = edit_values(options);
  if (!options.list_groups) check_output_path(options.output, false, {options.model});

  const Model model = load_model(options.model);
  const EditCapability* edit = edit_capability(model.method());
  if (edit == nullptr)
    throw std::invalid_argument(
        fmt::format("'{}' is a {} model; `stochtex edit` edits {} models only (stochtex analyze "
                    "INPUT --method {})",
                    options.model, model.method(), methods_with(CapabilityKind::edit),
                    methods_with(CapabilityKind::edit)));
  const std::shared_ptr<const void> groups = edit->find_groups(model);
  if (options.list_groups) {
    if (options.json)
      fmt::print("{}\n", edit->groups_json(model, groups.get()).dump(2));
    else
      fmt::print("{}", edit->groups_table(model, groups.get()));
    return;
  }
  const EditResult edited = edit->edit(model, groups.get(), values, "--");
  save_model(edited.model, options.output);
  fmt::print(stderr, "wrote {} ({})\n", options.output, edited.summary);
}

}  // namespace

Command add_edit_command(CLI::App& app) {
  auto options = std::make_shared<EditOptions>();
  // The editing methods' own descriptions (one today: gabor's).
  std::string summary;
  for (const EditCapability* edit : edit_capabilities())
    summary += (summary.empty() ? "" : "; ") + std::string(edit->summary);
  CLI::App* command = app.add_subcommand("edit", summary);
  add_edit_options(command, *options);
  return {command, [options] {
            run_edit(*options);
            return 0;
          }};
}

}  // namespace stochtex::cli
