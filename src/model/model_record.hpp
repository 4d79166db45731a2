#pragma once
// The method-neutral content of a model file: a method name, its parameters, a few scalars and
// named float32 arrays. Each method converts its model to and from a record; the .stx format
// (model_file.hpp) reads and writes records and knows nothing about methods.

#include <cstdint>
#include <string>
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

  // Throws Error(format) naming `source` when the array is missing or its shape differs.
  const NamedArray& array(const std::string& name, const std::vector<std::int64_t>& shape,
                          const std::string& source) const;
  // Throws Error(format) naming `source` when the scalar is missing or not finite.
  double scalar(const std::string& name, const std::string& source) const;
};

}  // namespace stochtex
