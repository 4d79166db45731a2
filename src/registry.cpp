// The one table of methods: name, described parameters, analysis. Evaluation and model files
// dispatch through the closed variant in model/model_data.hpp.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "methods/gabor/analysis.hpp"
#include "methods/gabor/params.hpp"
#include "methods/lrp/analysis.hpp"
#include "methods/lrp/params.hpp"
#include "methods/texton/analysis.hpp"
#include "methods/texton/params.hpp"
#include "methods/tiling/analysis.hpp"
#include "methods/tiling/params.hpp"
#include "model/model_data.hpp"
#include "spectral/adsn.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

using AnalyzeFunction = MethodModel (*)(ImageView<const float>, const ParamValues&, std::uint32_t);

struct MethodEntry {
  MethodInfo info;
  AnalyzeFunction analyze;
};

const std::array kMethods = {
    MethodEntry{{texton::TextonModel::kMethodName,
                 "texton noise (Galerne, Leclaire, Moisan 2017): a small texton summarising the "
                 "spectrum, ~30 fetches per sample",
                 texton::kParams},
                [](ImageView<const float> exemplar, const ParamValues& params, std::uint32_t seed) {
                  return MethodModel(texton::analyze(exemplar, params, seed));
                }},
    MethodEntry{{tiling::TilingModel::kMethodName,
                 "histogram-preserving tiling and blending (Heitz, Neyret 2018): 3 patches of the "
                 "Gaussianised exemplar and one look-up per sample",
                 tiling::kParams},
                [](ImageView<const float> exemplar, const ParamValues& params, std::uint32_t seed) {
                  return MethodModel(tiling::analyze(exemplar, params, seed));
                }},
    MethodEntry{{lrp::LrpModel::kMethodName,
                 "local random-phase noise (Gilet et al. 2014): windowed cosines with random "
                 "phases on a lattice, 9 (J + L) cosines and windows per channel and sample",
                 lrp::kParams},
                [](ImageView<const float> exemplar, const ParamValues& params, std::uint32_t seed) {
                  return MethodModel(lrp::analyze(exemplar, params, seed));
                }},
    MethodEntry{{gabor::GaborModel::kMethodName,
                 "Gabor noise by example (Galerne, Lagae, Lefebvre, Drettakis 2012): a sparse sum "
                 "of bandwidth-quantised Gaussians fitted to the spectrum, ~2N kernels per sample",
                 gabor::kParams},
                [](ImageView<const float> exemplar, const ParamValues& params, std::uint32_t seed) {
                  return MethodModel(gabor::analyze(exemplar, params, seed));
                }},
};

const MethodEntry& find_entry(std::string_view name) {
  for (const auto& entry : kMethods)
    if (entry.info.name == name) return entry;
  std::string known;
  for (const auto& entry : kMethods)
    known += (known.empty() ? "" : ", ") + std::string(entry.info.name);
  throw std::invalid_argument("unknown method '" + std::string(name) +
                              "'; known methods: " + known);
}

std::string format_number(double value) {
  std::array<char, 32> buffer{};
  auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return ec == std::errc() ? std::string(buffer.data(), end) : std::to_string(value);
}

}  // namespace

std::span<const MethodInfo> methods() {
  static const auto infos = [] {
    std::array<MethodInfo, kMethods.size()> result;
    std::transform(kMethods.begin(), kMethods.end(), result.begin(),
                   [](const auto& e) { return e.info; });
    return result;
  }();
  return infos;
}

const MethodInfo& method_info(std::string_view name) {
  return find_entry(name).info;
}

ParamValues resolve_params(std::string_view method, const ParamValues& given) {
  const MethodInfo& info = method_info(method);
  ParamValues resolved;
  for (const auto& param : info.params) resolved[std::string(param.name)] = param.default_value;
  for (const auto& [name, value] : given) {
    const auto param = std::find_if(info.params.begin(), info.params.end(),
                                    [&](const ParamInfo& p) { return p.name == name; });
    if (param == info.params.end()) {
      std::string known;
      for (const auto& p : info.params) known += (known.empty() ? "" : ", ") + std::string(p.name);
      throw std::invalid_argument("unknown parameter '" + name + "' for method " +
                                  std::string(method) + "; its parameters are: " + known);
    }
    const std::string where = "parameter " + name + " of method " + std::string(method);
    if (!std::isfinite(value) || value < param->min_value || value > param->max_value)
      throw std::invalid_argument(where + " must be between " + format_number(param->min_value) +
                                  " and " + format_number(param->max_value) + ", not " +
                                  format_number(value));
    if (param->integer && value != std::floor(value))
      throw std::invalid_argument(where + " must be an integer, not " + format_number(value));
    if (!param->allowed.empty() &&
        std::find(param->allowed.begin(), param->allowed.end(), value) == param->allowed.end()) {
      std::string allowed;
      for (double a : param->allowed) allowed += (allowed.empty() ? "" : ", ") + format_number(a);
      throw std::invalid_argument(where + " must be one of " + allowed + ", not " +
                                  format_number(value));
    }
    resolved[name] = value;
  }
  return resolved;
}

ParamValues resolve_params(std::string_view method,
                           const std::map<std::string, std::string, std::less<>>& given) {
  ParamValues numbers;
  for (const auto& [name, text] : given) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      throw std::invalid_argument("parameter " + name + " of method " + std::string(method) +
                                  " must be a number, not '" + text + "'");
    numbers[name] = value;
  }
  return resolve_params(method, numbers);
}

Model analyze(std::string_view method, ImageView<const float> exemplar, const ParamValues& params,
              std::uint32_t seed, const std::string& source_name) {
  const MethodEntry& entry = find_entry(method);
  ParamValues resolved = resolve_params(method, params);
  validate_exemplar(exemplar, source_name);
  MethodModel model = entry.analyze(exemplar, resolved, seed);
  return Model(std::make_shared<const ModelData>(ModelData{std::move(resolved), std::move(model)}));
}

ImageF gaussian_version(ImageView<const float> exemplar, int width, int height,
                        std::uint32_t seed) {
  return adsn(exemplar, width, height, seed);
}

}  // namespace stochtex
