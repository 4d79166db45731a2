#pragma once
// The one list of methods: the closed set of method models. Adding a method = its folder, one
// include and one alternative here, and its docs page (docs/design.md §11): the registry
// (src/registry.cpp), the GPU backend and the exporter are made from this variant. Dispatch happens
// once per batch with std::visit, never per sample.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "methods/gabor/model.hpp"
#include "methods/lrp/model.hpp"
#include "methods/texton/model.hpp"
#include "methods/texton_mix/model.hpp"
#include "methods/tiling/model.hpp"
#include "model/model_colour.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

using MethodModel = std::variant<texton::TextonModel, tiling::TilingModel, lrp::LrpModel,
                                 gabor::GaborModel, texton_mix::TextonMixModel>;

struct ModelData {
  ParamValues params;
  MethodModel model;
  std::vector<MapInfo> maps;  // a material's maps in channel order; empty for one image
  ModelColour colour;         // each channel's colour space (model/model_colour.hpp)
  std::optional<WrapSteps> exemplar_wrap;  // Model::exemplar_wrap
};

// ModelColour::removed_deviation of a method model (the model's srgb channels decoded after
// evaluation): r(w)^2 = V(1) - V(w), where V(w) is the variance of each channel's values that the
// method's own evaluator returns with footprints of width w, measured at kMeasuredSamples
// positions far apart (independent values) on every core: every position for the narrow widths,
// and as the variance falls, the first of them, fewer, as many as keep its error within a quarter
// of the narrow widths' (measure_removed_deviation). A footprint
// filters each method in its own way (texton's pyramid and probes, gabor's and lrp's analytic
// filters); measured, r(w) is the method's. Widths are measured every two steps of the table,
// until V(w) falls below a thousandth of V(1) (beyond, r = V(1)^(1/2)), or until three widths
// an octave apart gave the same values at the same positions (beyond, r keeps its last value: the
// filter has nothing left to remove); the others are interpolated in r^2.
inline constexpr int kMeasuredSamples = 8192;
std::vector<float> measure_removed_deviation(const MethodModel& model);

// The model of a method's model with each channel's colour space (every channel data when
// `spaces` is empty or all data): the spaces given to the method (tiling decodes in its tables)
// and to ModelColour, with `removed_deviation` (kRemovedSteps x channels), which a model needs
// when ModelColour::expects_any() (it is dropped otherwise): a model file's, or, when none is
// given, measure_removed_deviation's. Throws std::invalid_argument for spaces of the wrong size
// or a table of the wrong size.
Model assemble_model(ParamValues params, MethodModel model, std::vector<MapInfo> maps,
                     std::vector<ColourSpace> spaces,
                     std::optional<std::vector<float>> removed_deviation = std::nullopt,
                     std::optional<WrapSteps> exemplar_wrap = std::nullopt);
// The same model with another method model (an edit), keeping its parameters, maps, colour
// spaces and exemplar's wrap steps; the removed deviations are measured again.
Model with_method_model(const Model& model, MethodModel edited);

}  // namespace stochtex
