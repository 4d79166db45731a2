#pragma once
// The method-neutral content of a model file: a method name, its parameters, a few scalars and
// named float32 arrays. Each method converts its model to and from a record; the .stx format
// (model_file.hpp) reads and writes records and knows nothing about methods.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/model.hpp"

namespace stochtex {

struct NamedArray {
  std::string name;
  std::vector<std::int64_t> shape;  // e.g. {height, width, channels}; product == values.size()
  std::vector<float> values;
};

struct ModelRecord {
  std::string method;
  ParamValues params;   // the analysis parameters, as described by the method's ParamInfo table
  ParamValues scalars;  // derived scalar values the evaluator needs (e.g. channel count)
  std::vector<NamedArray> arrays;
  std::vector<MapInfo> maps;  // a material's maps (file format version 2); empty for one image
  // A model of one image: its colour channels' colour space (file format version 3 when not data).
  ColourSpace colour_space = ColourSpace::data;
  // The analysed exemplar's wrap steps (Model::exemplar_wrap), when known: an optional entry of
  // the header, which an older stochtex ignores.
  std::optional<WrapSteps> exemplar_wrap;

  // Throws Error(format) naming `source` when the array is missing or its shape differs.
  const NamedArray& array(const std::string& name, const std::vector<std::int64_t>& shape,
                          const std::string& source) const;
  // Throws Error(format) naming `source` when the scalar is missing or not finite.
  double scalar(const std::string& name, const std::string& source) const;
  // The same, also refusing a value outside [low, high] or, when `integer`, not an integer: a
  // file must not ask the evaluator for more work or memory than `stochtex analyze` could.
  double scalar_in(const std::string& name, double low, double high, bool integer,
                   const std::string& source) const;
  // A scalar named like one of the method's parameters, checked against that parameter's range.
  double param_scalar(std::string_view name, std::span<const ParamInfo> method_params,
                      const std::string& source) const;
  // Each channel's colour space, for a model of `channels` channels: the maps' or the image's.
  std::vector<ColourSpace> channel_spaces(int channels) const;
};

}  // namespace stochtex
