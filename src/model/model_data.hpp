#pragma once
// The closed set of method models. Adding a method = its folder + one alternative here + one row in
// src/registry.cpp. Dispatch happens once per batch with std::visit, never per sample.

#include <string>
#include <variant>

#include "methods/gabor/model.hpp"
#include "methods/lrp/model.hpp"
#include "methods/texton/model.hpp"
#include "methods/tiling/model.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

using MethodModel =
    std::variant<texton::TextonModel, tiling::TilingModel, lrp::LrpModel, gabor::GaborModel>;

struct ModelData {
  ParamValues params;
  MethodModel model;
};

}  // namespace stochtex
