#pragma once
// The optional capabilities of a method's registry row (param_record.hpp's RegistryRow), described
// by records as its parameters are. The front ends (the CLI, the studio, the report) ask the
// registry (src/registry.hpp) what a method can do and drive it through these records; none of
// them names a method. A new capability is a record here, a field of RegistryRow and its lookup
// in the registry.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/model.hpp"

namespace stochtex {

// A continuous target spectrum in place of an exemplar (`stochtex analyze --target TEXT`).
struct TargetCapability {
  // The syntax of TEXT, for a help line.
  std::string_view help;
  // The model of the target `text` with the method's checked parameters; a std::invalid_argument
  // of one sentence that quotes the text otherwise.
  Model (*model)(const std::string& text, const ParamValues& params, std::uint32_t seed);
};

// How the studio's editor moves a field: a slider (one per component) of positions low to high in
// steps of `step`, a position p standing for the value p or, for a factor moved in octaves, 2^p.
// The value is shown as `prefix`, its 3 significant digits, `suffix`.
struct EditSlider {
  double low = 0.0;
  double high = 0.0;
  double step = 0.0;
  bool octaves = false;
  std::string_view prefix = {};
  std::string_view suffix = {};
};

// One value an edit takes: `stochtex edit --NAME`, the key NAME of the studio's JSON edit.
struct EditField {
  std::string_view name;
  std::string_view help;
  double default_value = 0.0;
  // 2: a pair, "X,Y" on the command line and [x, y] in JSON, each number within
  // [-max_abs, max_abs] (checked where it is typed, so that the message can quote the text).
  int components = 1;
  double max_abs = 0.0;
  EditSlider slider;
};

// An edit as asked for: a group name and the numbers of the fields given (a field not given keeps
// its default).
struct EditValues {
  std::string group;
  std::map<std::string, std::vector<double>, std::less<>> numbers;
};

// The edited model and a clause saying what the edit did ("12 Gaussians edited").
struct EditResult {
  Model model;
  std::string summary;
};

// Editing a model by groups of its parts (gabor: section 8 of the Gabor noise paper).
struct EditCapability {
  // What `stochtex edit` does, for its help.
  std::string_view summary;
  // The group names; the first selects every part.
  std::span<const std::string_view> groups;
  std::span<const EditField> fields;
  // The model's grouping, found once (it can take a while) and handed to the calls below.
  std::shared_ptr<const void> (*find_groups)(const Model& model);
  // What each group holds, as one JSON document (`stochtex edit --list-groups --json`, the
  // studio's /api/models/<id>/groups) and as a table of lines for a terminal.
  nlohmann::ordered_json (*groups_json)(const Model& model, const void* groups);
  std::string (*groups_table)(const Model& model, const void* groups);
  // The model edited; a std::invalid_argument of one sentence for a value it refuses, naming the
  // value as `prefix` + its field name ("--rotate" on the command line).
  EditResult (*edit)(const Model& model, const void* groups, const EditValues& values,
                     std::string_view prefix);
};

}  // namespace stochtex
