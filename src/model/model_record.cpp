#include "model/model_record.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/model_colour.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i)
    text += (i == 0 ? "" : ", ") + std::to_string(shape[i]);
  return text + "]";
}

}  // namespace

const NamedArray& ModelRecord::array(const std::string& name,
                                     const std::vector<std::int64_t>& shape,
                                     const std::string& source) const {
  for (const auto& candidate : arrays) {
    if (candidate.name != name) continue;
    if (candidate.shape != shape)
      throw Error(ErrorCode::format, "'" + source + "' declares array '" + name + "' with shape " +
                                         shape_text(candidate.shape) + " where " +
                                         shape_text(shape) +
                                         " is expected; the file is corrupt, re-run `stochtex "
                                         "analyze`");
    return candidate;
  }
  throw Error(ErrorCode::format, "'" + source + "' has no array '" + name +
                                     "'; the file is corrupt, re-run `stochtex analyze`");
}

double ModelRecord::scalar(const std::string& name, const std::string& source) const {
  const auto found = scalars.find(name);
  if (found == scalars.end() || !std::isfinite(found->second))
    throw Error(ErrorCode::format, "'" + source + "' has no valid value for '" + name +
                                       "'; the file is corrupt, re-run `stochtex analyze`");
  return found->second;
}

double ModelRecord::scalar_in(const std::string& name, double low, double high, bool integer,
                              const std::string& source) const {
  const double value = scalar(name, source);
  if ((integer && value != std::floor(value)) || value < low || value > high)
    throw Error(ErrorCode::format, "'" + source + "' has an invalid " + method + " " + name +
                                       " value; re-run `stochtex analyze`");
  return value;
}

double ModelRecord::param_scalar(std::string_view name, std::span<const ParamInfo> method_params,
                                 const std::string& source) const {
  const auto param = std::find_if(method_params.begin(), method_params.end(),
                                  [&](const ParamInfo& p) { return p.name == name; });
  if (param == method_params.end())
    throw std::logic_error("param_scalar: '" + std::string(name) + "' is not a parameter");
  return scalar_in(std::string(name), param->min_value, param->max_value, param->integer, source);
}

std::vector<ColourSpace> ModelRecord::channel_spaces(int channels) const {
  return maps.empty() ? image_channel_spaces(colour_space, channels) : map_channel_spaces(maps);
}

}  // namespace stochtex
