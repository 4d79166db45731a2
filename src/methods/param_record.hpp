#pragma once
// A method's parameters as one typed struct whose fields are bound once to their descriptions.
// Each method's params.hpp declares `Params` (the defaults are its member initialisers) and
// `kFields`, one ParamField per member; from that single record come the ParamInfo table
// (`kParams`: the CLI's parsing and help, `methods --json`, the docs' tables, resolve_params'
// checks) and the conversions between the struct and the ParamValues numbers the model file
// stores, so that analysis reads `params.mni`, never a name.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

#include "methods/capabilities.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

template <class P>
struct ParamField {
  ParamInfo info;
  double (*get)(const P&);
  void (*set)(P&, double);
};

namespace param_detail {

template <auto Member>
struct MemberOf;
template <class P, class T, T P::*Member>
struct MemberOf<Member> {
  using Struct = P;
  using Type = T;
};

template <class T>
constexpr double to_number(T value) {
  if constexpr (std::is_enum_v<T>)
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(value));
  else
    return static_cast<double>(value);
}

// `value` has passed resolve_params: an integer field receives an integer, a switch 0 or 1.
template <class T>
constexpr T from_number(double value) {
  if constexpr (std::is_enum_v<T>)
    return static_cast<T>(static_cast<std::underlying_type_t<T>>(value));
  else if constexpr (std::is_same_v<T, bool>)
    return value != 0.0;
  else
    return static_cast<T>(value);
}

template <auto Member>
constexpr auto field(ParamInfo info) {
  using P = typename MemberOf<Member>::Struct;
  using T = typename MemberOf<Member>::Type;
  info.default_value = to_number(P{}.*Member);
  info.integer = !std::is_floating_point_v<T>;
  return ParamField<P>{info, [](const P& params) { return to_number(params.*Member); },
                       [](P& params, double value) { params.*Member = from_number<T>(value); }};
}

}  // namespace param_detail

// A numeric field (int or double) accepting [min_value, max_value].
template <auto Member>
constexpr auto number_field(std::string_view name, double min_value, double max_value,
                            std::string_view help) {
  using T = typename param_detail::MemberOf<Member>::Type;
  static_assert(std::is_same_v<T, int> || std::is_same_v<T, double>, "a number is int or double");
  return param_detail::field<Member>({name, 0.0, min_value, max_value, false, help});
}

// A numeric field accepting [min_value, max_value], or 0 (its default), which asks the analysis
// to choose the value from the exemplar.
template <auto Member>
constexpr auto chosen_number_field(std::string_view name, double min_value, double max_value,
                                   std::string_view help) {
  using T = typename param_detail::MemberOf<Member>::Type;
  static_assert(std::is_same_v<T, int> || std::is_same_v<T, double>, "a number is int or double");
  return param_detail::field<Member>({name, 0.0, min_value, max_value, false, help, {}, true});
}

// An enumeration, switch or other field accepting only `choices`, by name or by number.
template <auto Member>
constexpr auto choice_field(std::string_view name, std::span<const ParamChoice> choices,
                            std::string_view help) {
  const auto [low, high] =
      std::minmax_element(choices.begin(), choices.end(),
                          [](const auto& a, const auto& b) { return a.value < b.value; });
  return param_detail::field<Member>({name, 0.0, low->value, high->value, true, help, choices});
}

// The switches' names (bool fields), the same for every method.
inline constexpr std::array<ParamChoice, 2> kSwitch = {{{"off", 0}, {"on", 1}}};

// The ParamInfo table of a record, in its order.
template <class P, std::size_t N>
constexpr std::array<ParamInfo, N> param_infos(const std::array<ParamField<P>, N>& fields) {
  std::array<ParamInfo, N> infos{};
  for (std::size_t i = 0; i < N; ++i) infos[i] = fields[i].info;
  return infos;
}

// The struct of checked values (resolve_params); a name `values` lacks keeps its default.
template <class P, std::size_t N>
P params_from_values(const std::array<ParamField<P>, N>& fields, const ParamValues& values) {
  P params;
  for (const auto& field : fields)
    if (const auto value = values.find(field.info.name); value != values.end())
      field.set(params, value->second);
  return params;
}

// The numbers of every field, as the model file stores them.
template <class P, std::size_t N>
ParamValues param_values(const std::array<ParamField<P>, N>& fields, const P& params) {
  ParamValues values;
  for (const auto& field : fields) values[std::string(field.info.name)] = field.get(params);
  return values;
}

// The peak memory of a method's analysis of a width x height exemplar with c channels, about
// (per_pixel + per_channel * c) bytes a pixel above kFixedPeakBytes (core/memory_budget.hpp,
// docs/design.md §9): the method's peak resident size, measured at 512² and 1024² (128² to 512²
// for gabor) in grey and colour over its parameters, plus a margin; AnalysisMemoryTest checks the
// row against a measurement.
struct AnalysisMemory {
  std::uint64_t per_pixel = 0;
  std::uint64_t per_channel = 0;
};

// A method's row of the registry (src/registry.cpp): its one-line summary, its parameter record,
// its analysis's memory, the most channels it analyses, whether it derives a material's normal
// map from the height (MethodInfo), the relative cost and default size of its analysis and its
// optional capabilities (methods/capabilities.hpp). Each method's analysis.hpp returns it from
// `registry_row(std::type_identity<Model>)`, which the registry finds by argument-dependent lookup
// for every alternative of MethodModel.
template <class P, std::size_t N>
struct RegistryRow {
  std::string_view summary;
  const std::array<ParamField<P>, N>& fields;
  AnalysisMemory analysis_memory;
  int max_channels = 4;
  bool derives_normals = true;  // MethodInfo::derives_normals
  // The analysis's time per pixel and channel against the other methods' (about 1), by which
  // `stochtex report` starts the longest analyses first.
  double analysis_cost = 1.0;
  // The longer side of the largest exemplar analysed by default: a larger photo is downscaled to
  // it (io/exemplar_region.hpp), unless the user chooses a scale, so that a phone's photo takes
  // seconds, not minutes (docs/inputs.md).
  int analysis_side = 1024;
  const TargetCapability* target = nullptr;  // `stochtex analyze --target`
  const EditCapability* edit = nullptr;      // `stochtex edit`, the studio's editor
};

}  // namespace stochtex
