#include "methods/lrp/target_analysis.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "methods/lrp/analysis.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::lrp {
namespace {

constexpr double kDefaultVariance = 0.01;
constexpr double kDefaultMean = 0.5;
constexpr int kDefaultSize = 128;
constexpr int kMaxSize = 1024;

std::invalid_argument bad(const std::string& text, const std::string& why) {
  return std::invalid_argument("the target spectrum '" + text + "': " + why +
                               " (e.g. ring:radius=0.2,width=0.02)");
}

}  // namespace

Model target_model(const std::string& text, const ParamValues& params, std::uint32_t seed) {
  const auto colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  if (kind != "ring" && kind != "gaussian" && kind != "anisotropic")
    throw bad(text, "the kind must be ring, gaussian or anisotropic");
  std::map<std::string, double> values;
  std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const std::string entry = rest.substr(0, comma);
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    const auto equals = entry.find('=');
    if (equals == std::string::npos) throw bad(text, "'" + entry + "' is not key=value");
    const std::string key = entry.substr(0, equals);
    const std::string number = entry.substr(equals + 1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
    if (ec != std::errc() || end != number.data() + number.size() || !std::isfinite(value))
      throw bad(text, "'" + number + "' is not a number");
    if (!values.emplace(key, value).second) throw bad(text, "'" + key + "' is given twice");
  }
  const std::vector<std::string> shape_keys =
      kind == "ring" ? std::vector<std::string>{"radius", "width"}
                     : std::vector<std::string>{"cx", "cy", "along", "across"};
  for (const auto& [key, value] : values) {
    const bool known = key == "variance" || key == "mean" || key == "size" ||
                       std::find(shape_keys.begin(), shape_keys.end(), key) != shape_keys.end();
    if (!known) throw bad(text, "'" + key + "' is not a key of a " + kind + " target");
  }
  for (const std::string& key : shape_keys)
    if (values.find(key) == values.end()) throw bad(text, "a " + kind + " target needs " + key);
  const auto optional = [&](const std::string& key, double fallback) {
    const auto found = values.find(key);
    return found == values.end() ? fallback : found->second;
  };
  const double size = optional("size", kDefaultSize);
  if (size != std::floor(size) || size < 8 || size > kMaxSize || static_cast<int>(size) % 2 != 0)
    throw bad(text, "size must be an even integer from 8 to 1024");
  const auto spectrum = [&] {
    try {
      return kind == "ring" ? ring_spectrum(static_cast<int>(size), values["radius"],
                                            values["width"], optional("variance", kDefaultVariance))
                            : gaussian_spectrum(static_cast<int>(size), values["cx"], values["cy"],
                                                values["along"], values["across"],
                                                optional("variance", kDefaultVariance));
    } catch (const std::invalid_argument& e) {
      throw bad(text, e.what());
    }
  };
  // The mean and the standard deviation stay within the exemplar value range (stochtex.hpp).
  const double mean = optional("mean", kDefaultMean);
  const double variance = optional("variance", kDefaultVariance);
  const double largest = kMaxExemplarValue;
  if (std::abs(mean) > largest || variance > largest * largest)
    throw bad(text, "the mean must be within +-1e6 and the variance at most 1e12");
  SpectrumTarget target = spectrum();
  target.mean = mean;
  return spectrum_model(target, params, seed);
}

}  // namespace stochtex::lrp
