#pragma once
// The one list of methods: the closed set of method models. Adding a method = its folder, one
// include and one alternative here, and its docs page (docs/design.md §11): the registry
// (src/registry.cpp), the GPU backend and the exporter are made from this variant. Dispatch happens
// once per batch with std::visit, never per sample.

#include <string>
#include <variant>
#include <vector>

#include "methods/gabor/model.hpp"
#include "methods/lrp/model.hpp"
#include "methods/texton/model.hpp"
#include "methods/texton_mix/model.hpp"
#include "methods/tiling/model.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

using MethodModel = std::variant<texton::TextonModel, tiling::TilingModel, lrp::LrpModel,
                                 gabor::GaborModel, texton_mix::TextonMixModel>;

struct ModelData {
  ParamValues params;
  MethodModel model;
  std::vector<MapInfo> maps;  // a material's maps in channel order; empty for one image
};

}  // namespace stochtex
