// The table of methods (name, summary, described parameters, analysis), made from the closed
// variant of models in model/model_data.hpp, the one list of methods: evaluation, model files and
// the GPU backend dispatch through the same variant.

#include "registry.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "core/memory_budget.hpp"
#include "metrics/metrics.hpp"
#include "model/model_data.hpp"
#include "spectral/adsn.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex_method_analyses.hpp"

namespace stochtex {
namespace {

using AnalyzeFunction = MethodModel (*)(ImageView<const float>, const ParamValues&, std::uint32_t,
                                        const std::function<void(double)>&,
                                        std::span<const MapInfo>);

struct MethodEntry {
  MethodInfo info;
  AnalyzeFunction analyze;
  AnalysisMemory analysis_memory;
  double analysis_cost = 1.0;
  int analysis_side = 1024;
  const TargetCapability* target = nullptr;
  const EditCapability* edit = nullptr;
};

// The entry of one alternative of MethodModel: its name, the summary and parameter record of its
// registry row (`registry_row`, in the method's analysis.hpp), and its analysis from checked values
// through the typed record (`analyze`, found by argument-dependent lookup on the method's Params),
// given the progress hook where the method's analysis reports progress and a material's maps
// where it groups channels by map.
template <class Params>
concept ReportsProgress = requires(ImageView<const float> exemplar, const Params& params,
                                   const std::function<void(double)>& progress) {
  analyze(exemplar, params, std::uint32_t{0}, progress);
};
template <class Params>
concept GroupsMaps = requires(ImageView<const float> exemplar, const Params& params,
                              std::span<const MapInfo> maps) {
  analyze(exemplar, params, std::uint32_t{0}, maps);
};

template <class Model>
MethodEntry entry_of() {
  static constexpr auto row = registry_row(std::type_identity<Model>{});
  static constexpr auto infos = param_infos(row.fields);
  return {{Model::kMethodName, row.summary, infos, row.max_channels, row.derives_normals},
          [](ImageView<const float> exemplar, const ParamValues& values, std::uint32_t seed,
             const std::function<void(double)>& progress, std::span<const MapInfo> maps) {
            const auto params = params_from_values(row.fields, values);
            if constexpr (ReportsProgress<decltype(params)>)
              return MethodModel(analyze(exemplar, params, seed, progress));
            else if constexpr (GroupsMaps<decltype(params)>)
              return MethodModel(analyze(exemplar, params, seed, maps));
            else
              return MethodModel(analyze(exemplar, params, seed));
          },
          row.analysis_memory,
          row.analysis_cost,
          row.analysis_side,
          row.target,
          row.edit};
}

// The models analysed from one exemplar (`stochtex analyze -m`) have a registry row; the others
// are made by their own command (texton_mix: `stochtex mix A B`) and give their parameter
// record as the ParamInfo table `kParams` of their namespace, found through their params_of().
template <class Model>
concept AnalysedFromOneExemplar = requires {
  registry_row(std::type_identity<Model>{});
};

template <class... Models>
std::vector<MethodEntry> entries(std::type_identity<std::variant<Models...>>) {
  std::vector<MethodEntry> list;
  (
      [&] {
        if constexpr (AnalysedFromOneExemplar<Models>) list.push_back(entry_of<Models>());
      }(),
      ...);
  return list;
}

// Every method analysed from one exemplar, in the order of the closed variant of models
// (model/model_data.hpp); made on first use, so that no other static initialiser can see it
// unmade.
const std::vector<MethodEntry>& method_entries() {
  static const auto entries_of_every_method = entries(std::type_identity<MethodModel>{});
  return entries_of_every_method;
}

// The name and parameter record of `name`, whether or not it is analysed from one exemplar.
MethodInfo any_method_info(std::string_view name) {
  std::optional<MethodInfo> found;
  [&]<typename... Models>(std::type_identity<std::variant<Models...>>) {
    (
        [&] {
          if constexpr (!AnalysedFromOneExemplar<Models>)
            if (name == Models::kMethodName)
              found = MethodInfo{Models::kMethodName, "", params_of(std::type_identity<Models>{})};
        }(),
        ...);
  }(std::type_identity<MethodModel>{});
  return found ? *found : method_info(name);
}

const MethodEntry& find_entry(std::string_view name) {
  for (const auto& entry : method_entries())
    if (entry.info.name == name) return entry;
  std::string known;
  for (const auto& entry : method_entries())
    known += (known.empty() ? "" : ", ") + std::string(entry.info.name);
  throw std::invalid_argument("unknown method '" + std::string(name) +
                              "'; known methods: " + known);
}

std::string format_number(double value) {
  std::array<char, 32> buffer{};
  auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return ec == std::errc() ? std::string(buffer.data(), end) : std::to_string(value);
}

const ParamInfo& find_param(const MethodInfo& info, const std::string& name) {
  const auto param = std::find_if(info.params.begin(), info.params.end(),
                                  [&](const ParamInfo& p) { return p.name == name; });
  if (param != info.params.end()) return *param;
  std::string known;
  for (const auto& p : info.params) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw std::invalid_argument("unknown parameter '" + name + "' for method " +
                              std::string(info.name) + "; its parameters are: " + known);
}

template <class Predicate>
const ParamChoice* find_choice(const ParamInfo& param, Predicate matches) {
  const auto choice = std::find_if(param.choices.begin(), param.choices.end(), matches);
  return choice == param.choices.end() ? nullptr : &*choice;
}

// "one of histogram, variance, linear (or 0, 1, 2)": the names a user writes, then the numbers
// that model files and older scripts use.
std::string choices_sentence(const ParamInfo& param) {
  std::string names;
  std::string numbers;
  for (const auto& choice : param.choices) {
    names += (names.empty() ? "" : ", ") + std::string(choice.name);
    numbers += (numbers.empty() ? "" : ", ") + format_number(choice.value);
  }
  return "one of " + names + " (or " + numbers + ")";
}

// A value as a user writes it: the choice's name for an enumeration or switch, else the number.
std::string format_value(const ParamInfo& param, double value) {
  const ParamChoice* named =
      find_choice(param, [&](const ParamChoice& c) { return c.value == value; });
  return named ? std::string(named->name) : format_number(value);
}

}  // namespace

std::span<const MethodInfo> methods() {
  static const auto infos = [] {
    const auto& entries = method_entries();
    std::vector<MethodInfo> result(entries.size());
    std::transform(entries.begin(), entries.end(), result.begin(),
                   [](const auto& e) { return e.info; });
    return result;
  }();
  return infos;
}

const MethodInfo& method_info(std::string_view name) {
  return find_entry(name).info;
}

ParamValues resolve_params(std::string_view method, const ParamValues& given) {
  const MethodInfo info = any_method_info(method);
  ParamValues resolved;
  for (const auto& param : info.params) resolved[std::string(param.name)] = param.default_value;
  for (const auto& [name, value] : given) {
    const ParamInfo& param = find_param(info, name);
    const std::string where = "parameter " + name + " of method " + std::string(method);
    if (!param.choices.empty()) {
      // (The lambda captures a copy: clang 14, the sanitizer build's, cannot capture a binding.)
      if (!find_choice(param, [number = value](const ParamChoice& c) { return c.value == number; }))
        throw std::invalid_argument(where + " must be " + choices_sentence(param) + ", not " +
                                    format_number(value));
    } else if (param.zero_chooses && value == 0.0) {
      // 0: the analysis chooses the value from the exemplar.
    } else if (!std::isfinite(value) || value < param.min_value || value > param.max_value) {
      throw std::invalid_argument(where + " must be " +
                                  (param.zero_chooses ? "0 (chosen from the exemplar) or " : "") +
                                  "between " + format_number(param.min_value) + " and " +
                                  format_number(param.max_value) + ", not " + format_number(value));
    } else if (param.integer && value != std::floor(value)) {
      throw std::invalid_argument(where + " must be an integer, not " + format_number(value));
    }
    resolved[name] = value;
  }
  return resolved;
}

ParamValues resolve_params(std::string_view method,
                           const std::map<std::string, std::string, std::less<>>& given) {
  const MethodInfo info = any_method_info(method);
  ParamValues numbers;
  for (const auto& [name, text] : given) {
    const ParamInfo& param = find_param(info, name);
    if (const ParamChoice* named = find_choice(
            param, [&wanted = text](const ParamChoice& c) { return c.name == wanted; })) {
      numbers[name] = named->value;
      continue;
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      throw std::invalid_argument(
          "parameter " + name + " of method " + std::string(method) + " must be " +
          (param.choices.empty() ? "a number" : choices_sentence(param)) + ", not '" + text + "'");
    numbers[name] = value;
  }
  return resolve_params(method, numbers);
}

std::string format_param(std::string_view method, std::string_view name, double value) {
  const MethodInfo info = any_method_info(method);
  const auto& params = info.params;
  const auto param = std::find_if(params.begin(), params.end(),
                                  [&](const ParamInfo& p) { return p.name == name; });
  return param == params.end() ? format_number(value) : format_value(*param, value);
}

std::string methods_text() {
  std::string text;
  for (const auto& method : methods()) {
    text += std::string(method.name) + ": " + std::string(method.summary) + "\n";
    text += "  analyses exemplars up to " + std::to_string(analysis_side(method.name)) +
            " pixels on the longer side by default (larger ones downscaled: --scale-input)\n";
    for (const auto& p : method.params) {
      std::string option = std::string(p.name) + "=" + format_value(p, p.default_value);
      option.resize(std::max<std::size_t>(option.size(), 20), ' ');
      text += "  -p " + option + " " + std::string(p.help) + "\n";
    }
  }
  text += std::string(kAutoMethod) +
          ": not a method but a choice of one (analyze, synth, the studio): tiling where the "
          "exemplar measures far from Gaussian or periodic, else texton, saying why in one line "
          "(docs/comparison.md \"Which method?\"); takes no -p\n";
  return text;
}

std::string methods_json() {
  auto list = nlohmann::ordered_json::array();
  for (const auto& method : methods()) {
    auto params = nlohmann::ordered_json::array();
    for (const auto& p : method.params) {
      nlohmann::ordered_json param{{"name", p.name},       {"default", p.default_value},
                                   {"min", p.min_value},   {"max", p.max_value},
                                   {"integer", p.integer}, {"help", p.help}};
      if (p.zero_chooses) param["zero_chooses"] = true;
      if (!p.choices.empty()) {
        auto allowed = nlohmann::ordered_json::array();
        auto choices = nlohmann::ordered_json::array();
        for (const auto& choice : p.choices) {
          allowed.push_back(choice.value);
          choices.push_back({{"name", choice.name}, {"value", choice.value}});
        }
        param["allowed"] = allowed;
        param["choices"] = choices;
      }
      params.push_back(param);
    }
    nlohmann::ordered_json entry{{"name", method.name},
                                 {"summary", method.summary},
                                 {"max_channels", method.max_channels},
                                 {"analysis_side", analysis_side(method.name)},
                                 {"derives_normals", method.derives_normals},
                                 {"params", params}};
    // The optional capabilities (methods/capabilities.hpp), present only where the method has one.
    if (const TargetCapability* target = target_capability(method.name))
      entry["target"] = {{"help", target->help}};
    if (const EditCapability* edit = edit_capability(method.name)) {
      auto fields = nlohmann::ordered_json::array();
      for (const EditField& field : edit->fields)
        fields.push_back({{"name", field.name},
                          {"default", field.default_value},
                          {"components", field.components},
                          {"help", field.help},
                          {"slider",
                           {{"min", field.slider.low},
                            {"max", field.slider.high},
                            {"step", field.slider.step},
                            {"octaves", field.slider.octaves},
                            {"prefix", field.slider.prefix},
                            {"suffix", field.slider.suffix}}}});
      entry["edit"] = {{"summary", edit->summary}, {"groups", edit->groups}, {"fields", fields}};
    }
    list.push_back(entry);
  }
  return list.dump(2);
}

const TargetCapability* target_capability(std::string_view method) {
  return find_entry(method).target;
}

const EditCapability* edit_capability(std::string_view method) {
  for (const auto& entry : method_entries())
    if (entry.info.name == method) return entry.edit;
  return nullptr;
}

std::string methods_with(CapabilityKind kind) {
  std::string names;
  for (const auto& entry : method_entries())
    if (kind == CapabilityKind::target ? entry.target != nullptr : entry.edit != nullptr)
      names += (names.empty() ? "" : ", ") + std::string(entry.info.name);
  return names;
}

double analysis_cost(std::string_view method) {
  return find_entry(method).analysis_cost;
}

int analysis_side(std::string_view method) {
  return find_entry(method).analysis_side;
}

EditValues edit_values_from_json(const EditCapability& edit, const nlohmann::ordered_json& body) {
  std::string keys = "group";
  for (std::size_t i = 0; i < edit.fields.size(); ++i)
    keys += (i + 1 == edit.fields.size() ? " and " : ", ") + std::string(edit.fields[i].name);
  if (!body.is_object()) throw std::invalid_argument("an edit is a JSON object of " + keys);
  EditValues values{std::string(edit.groups.front()), {}};
  for (const auto& [key, value] : body.items()) {
    const auto field = std::find_if(edit.fields.begin(), edit.fields.end(),
                                    [&name = key](const EditField& f) { return f.name == name; });
    if (key == "group") {
      if (!value.is_string()) {
        std::string names;
        for (std::size_t i = 0; i < edit.groups.size(); ++i)
          names += (i == 0                        ? ""
                    : i + 1 == edit.groups.size() ? " or "
                                                  : ", ") +
                   std::string(edit.groups[i]);
        throw std::invalid_argument("\"group\" must be " + names);
      }
      values.group = value.get<std::string>();
    } else if (field == edit.fields.end()) {
      throw std::invalid_argument("an edit has no \"" + key + "\"; it takes " + keys);
    } else if (field->components == 1) {
      if (!value.is_number())
        throw std::invalid_argument("\"" + key + "\" must be a number, not " + value.dump());
      values.numbers[key] = {value.get<double>()};
    } else {
      if (!value.is_array() || value.size() != static_cast<std::size_t>(field->components) ||
          !std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); }))
        throw std::invalid_argument("\"" + key + "\" must be an array of " +
                                    std::to_string(field->components) + " numbers, not " +
                                    value.dump());
      auto& numbers = values.numbers[key];
      for (const auto& number : value) numbers.push_back(number.get<double>());
    }
  }
  return values;
}

std::uint64_t analysis_peak_bytes(std::string_view method, int width, int height, int channels) {
  const AnalysisMemory& memory = find_entry(method).analysis_memory;
  // (Negative sides, refused by validate_exemplar, count as none here.)
  const auto pixels = static_cast<std::uint64_t>(std::max(width, 0)) *
                      static_cast<std::uint64_t>(std::max(height, 0));
  return kFixedPeakBytes +
         pixels * (memory.per_pixel +
                   memory.per_channel * static_cast<std::uint64_t>(std::max(channels, 0)));
}

void check_analysis_request(std::string_view method, int width, int height, int channels,
                            const std::string& source_name) {
  const MethodEntry& entry = find_entry(method);
  if (channels > entry.info.max_channels)
    throw Error(ErrorCode::invalid_input, "method " + std::string(method) + " analyses 1 to " +
                                              std::to_string(entry.info.max_channels) +
                                              " channels, but '" + source_name + "' has " +
                                              std::to_string(channels) + "; choose another method");
  check_memory_budget(analysis_peak_bytes(method, width, height, channels),
                      "analysing the " + std::to_string(width) + "x" + std::to_string(height) +
                          " exemplar '" + source_name + "' with method " + std::string(method),
                      "crop or downscale the exemplar");
}

Model analyze_exemplar(std::string_view method, ImageView<const float> exemplar,
                       const ParamValues& params, std::uint32_t seed,
                       const std::string& source_name, const std::function<void(double)>& progress,
                       std::vector<MapInfo> maps, ColourSpace colour_space) {
  const MethodEntry& entry = find_entry(method);
  ParamValues resolved = resolve_params(method, params);
  check_analysis_request(method, exemplar.width, exemplar.height, exemplar.channels, source_name);
  validate_exemplar(exemplar, source_name, entry.info.max_channels);
  // The methods' analyses do not know the file: their data errors are named here (§9).
  MethodModel model = [&] {
    try {
      return entry.analyze(exemplar, resolved, seed, progress, maps);
    } catch (const Error& e) {
      throw Error(e.code(), "cannot analyse '" + source_name + "': " + e.what());
    }
  }();
  if (progress) progress(1.0);
  // The choices the analysis made for automatic parameters, as its model file will hold them.
  std::visit(
      [&](const auto& m) {
        if constexpr (requires { m.resolve_params(resolved); }) m.resolve_params(resolved);
      },
      model);
  std::vector<ColourSpace> spaces = maps.empty()
                                        ? image_channel_spaces(colour_space, exemplar.channels)
                                        : map_channel_spaces(maps);
  return assemble_model(std::move(resolved), std::move(model), std::move(maps), std::move(spaces),
                        std::nullopt, wrap_steps(exemplar));
}

Model analyze(std::string_view method, ImageView<const float> exemplar, const ParamValues& params,
              std::uint32_t seed, const std::string& source_name,
              const std::function<void(double)>& progress, ColourSpace colour_space) {
  return analyze_exemplar(method, exemplar, params, seed, source_name, progress, {}, colour_space);
}

ImageF gaussian_version(ImageView<const float> exemplar, int width, int height,
                        std::uint32_t seed) {
  return adsn(exemplar, width, height, seed);
}

}  // namespace stochtex
