#include "model/model_record.hpp"

#include <cmath>

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

}  // namespace stochtex
