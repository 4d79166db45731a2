#include "stochtex/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/parallel.hpp"
#include "model/map_layout.hpp"
#include "model/model_data.hpp"
#include "model/model_file.hpp"
#include "model/value_range.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

// Finds the variant alternative whose kMethodName matches the record and builds it.
template <std::size_t I = 0>
MethodModel model_from_record(const ModelRecord& record, const std::string& source) {
  if constexpr (I == std::variant_size_v<MethodModel>) {
    throw Error(ErrorCode::format, "'" + source + "' uses the unknown method '" + record.method +
                                       "'; it was written by another version of stochtex");
  } else {
    using Alternative = std::variant_alternative_t<I, MethodModel>;
    if (record.method == Alternative::kMethodName) return Alternative::from_record(record, source);
    return model_from_record<I + 1>(record, source);
  }
}

// The model file's generic array of ModelColour::removed_deviation.
constexpr std::string_view kRemovedDeviationArray = "colour_removed_deviation";

ModelRecord record_of(const Model& model) {
  ModelRecord record =
      std::visit([&](const auto& m) { return m.to_record(model.params()); }, model.data().model);
  record.maps = model.data().maps;
  const ModelColour& colour = model.data().colour;
  if (record.maps.empty()) record.colour_space = image_colour_space(colour);
  record.exemplar_wrap = model.data().exemplar_wrap;
  if (!colour.removed_deviation.empty())
    record.arrays.push_back({std::string(kRemovedDeviationArray),
                             {kRemovedSteps, model.channels()},
                             colour.removed_deviation});
  return record;
}

// Whether the method's evaluator returns channel `channel` as linear light already.
bool decodes_in_tables(const MethodModel& model, int channel) {
  return std::visit(
      [&](const auto& m) {
        if constexpr (requires { m.decodes_in_tables(channel); })
          return m.decodes_in_tables(channel);
        else
          return false;
      },
      model);
}

}  // namespace

std::vector<float> measure_removed_deviation(const MethodModel& model) {
  const int channels = std::visit([](const auto& m) { return m.channels(); }, model);
  const auto n = static_cast<std::size_t>(kMeasuredSamples);
  const std::vector<Vec2d> positions = spread_positions(n, 0x243f6a8885a308d3ull);
  std::vector<float> values(n * static_cast<std::size_t>(channels));
  const ImageView<float> view{values.data(), kMeasuredSamples, 1, channels,
                              static_cast<std::ptrdiff_t>(values.size())};
  // Each channel's variance of the evaluator's values at the first `count` positions (a multiple
  // of kChunk) with footprints of width `width` (0: point samples).
  constexpr std::size_t kChunk = 1024;
  const auto variances = [&](double width, std::size_t count) {
    std::vector<Footprint> footprints;
    if (width > 0.0) footprints.assign(count, Footprint{{width, 0.0}, {0.0, width}});
    // In chunks on every core: evaluate() is a pure function of each position.
    parallel_for(count / kChunk, 0, [&](std::size_t chunk) {
      const std::size_t first = chunk * kChunk;
      std::visit(
          [&](const auto& m) {
            m.evaluate(std::span(positions).subspan(first, kChunk),
                       footprints.empty()
                           ? std::span<const Footprint>()
                           : std::span<const Footprint>(footprints).subspan(first, kChunk),
                       0, view.sub(static_cast<int>(first), 0, static_cast<int>(kChunk), 1));
          },
          model);
    });
    std::vector<double> result(static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c) {
      double sum = 0.0;
      double squares = 0.0;
      for (std::size_t i = 0; i < count; ++i) {
        const double v = values[i * static_cast<std::size_t>(channels) + c];
        sum += v;
        squares += v * v;
      }
      const double mean = sum / static_cast<double>(count);
      result[static_cast<std::size_t>(c)] =
          std::max(0.0, squares / static_cast<double>(count) - mean * mean);
    }
    return result;
  };
  // The positions for the next width, from the variances `last` measured at the previous one: a
  // variance V from m independent values is off by about V (2 / m)^(1/2), and V(w) <= last. With
  // m >= 16 n (last / V(1))^2 that error stays within a quarter of V(1) (2 / n)^(1/2), the error of
  // the first widths, measured at all n; at least kChunk. The narrow widths, where V(w) is close
  // to V(1), take every position, the wide ones, whose variance is small, few. Measured on the
  // default models of grass_lawn_128 against all n at every width: the tables moved by at most
  // 0.15% of r's last value, and srgb analysis took 1.2 s instead of 3.5 s for lrp (whose V(w)
  // stays at 3e-3 V(1) to the table's end), 0.6 s instead of 1.3 s for texton, 1.6 s instead of
  // 2.3 s for gabor.
  const auto samples_after = [&](const std::vector<double>& last,
                                 const std::vector<double>& point) {
    double ratio = 0.0;
    for (std::size_t c = 0; c < last.size(); ++c)
      if (point[c] > 0.0) ratio = std::max(ratio, last[c] / point[c]);
    const double wanted = std::ceil(16.0 * static_cast<double>(n) * ratio * ratio / kChunk);
    return std::clamp(static_cast<std::size_t>(wanted), std::size_t{1}, n / kChunk) * kChunk;
  };
  const std::vector<double> point = variances(0.0, n);
  // removed[k][c] = r^2 at step k, measured at even steps until every channel's V(w) is below a
  // thousandth of V(1), then V(1); or until the evaluator has returned the same values at the
  // same positions for three widths an octave apart (its filter has nothing left to remove: lrp's
  // zero frequency, whose random offset per node no clamping fades), then that.
  std::vector<std::vector<double>> removed(kRemovedSteps, point);
  int measured = 0;
  std::vector<double> filtered = point;
  std::vector<float> previous;
  int unchanged = 0;
  for (int k = 0; k < kRemovedSteps; k += 2) {
    std::size_t count = n;
    if (k > 0) {
      count = samples_after(filtered, point);
      filtered = variances(std::exp2(static_cast<double>(k) / kRemovedStepsPerOctave), count);
    }
    bool faded = true;
    for (int c = 0; c < channels; ++c) {
      const auto cc = static_cast<std::size_t>(c);
      removed[static_cast<std::size_t>(k)][cc] = std::max(0.0, point[cc] - filtered[cc]);
      faded = faded && filtered[cc] <= 1e-3 * point[cc];
    }
    measured = k;
    const std::span<const float> now(values.data(), count * static_cast<std::size_t>(channels));
    unchanged =
        std::equal(now.begin(), now.end(), previous.begin(), previous.end()) ? unchanged + 1 : 0;
    previous.assign(now.begin(), now.end());
    if (unchanged == 2) {
      for (std::size_t rest = static_cast<std::size_t>(k) + 1; rest < removed.size(); ++rest)
        removed[rest] = removed[static_cast<std::size_t>(k)];
      break;
    }
    if (faded) break;
  }
  for (int k = 1; k < measured; k += 2)
    for (int c = 0; c < channels; ++c) {
      const auto cc = static_cast<std::size_t>(c);
      removed[static_cast<std::size_t>(k)][cc] =
          0.5 * (removed[static_cast<std::size_t>(k - 1)][cc] +
                 removed[static_cast<std::size_t>(k + 1)][cc]);
    }
  std::vector<float> table(static_cast<std::size_t>(kRemovedSteps) * channels);
  for (int k = 0; k < kRemovedSteps; ++k)
    for (int c = 0; c < channels; ++c)
      table[static_cast<std::size_t>(k) * channels + c] = static_cast<float>(
          std::sqrt(removed[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)]));
  return table;
}

Model assemble_model(ParamValues params, MethodModel model, std::vector<MapInfo> maps,
                     std::vector<ColourSpace> spaces,
                     std::optional<std::vector<float>> removed_deviation,
                     std::optional<WrapSteps> exemplar_wrap) {
  const int channels = std::visit([](const auto& m) { return m.channels(); }, model);
  if (std::all_of(spaces.begin(), spaces.end(),
                  [](ColourSpace space) { return space == ColourSpace::data; }))
    spaces.clear();
  if (!spaces.empty() && spaces.size() != static_cast<std::size_t>(channels))
    throw std::invalid_argument("the colour spaces do not match the model's channels");
  if (auto* tiling = std::get_if<tiling::TilingModel>(&model);
      tiling && tiling->data().colour != spaces)
    model = tiling->with_colour(spaces);
  ModelColour colour;
  colour.spaces = std::move(spaces);
  for (std::size_t c = 0; c < colour.spaces.size(); ++c)
    colour.in_tables.push_back(decodes_in_tables(model, static_cast<int>(c)));
  if (colour.expects_any()) {
    if (!removed_deviation) removed_deviation = measure_removed_deviation(model);
    if (removed_deviation->size() != static_cast<std::size_t>(kRemovedSteps) * channels)
      throw std::invalid_argument("the removed deviations of the srgb channels are missing");
    colour.removed_deviation = std::move(*removed_deviation);
    if (auto* tiling = std::get_if<tiling::TilingModel>(&model))
      tiling->calibrate_decoded([&](int c, double width) {
        return stochtex::removed_deviation(colour, channels, c, width);
      });
  }
  return Model(std::make_shared<const ModelData>(ModelData{
      std::move(params), std::move(model), std::move(maps), std::move(colour), exemplar_wrap}));
}

Model with_method_model(const Model& model, MethodModel edited) {
  const ModelData& data = model.data();
  return assemble_model(data.params, std::move(edited), data.maps, data.colour.spaces, std::nullopt,
                        data.exemplar_wrap);
}

std::string_view Model::method() const {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kMethodName; },
                    data_->model);
}

int Model::channels() const {
  return std::visit([](const auto& m) { return m.channels(); }, data_->model);
}

ColourSpace Model::colour_space() const {
  return image_colour_space(data_->colour);
}

std::optional<WrapSteps> Model::exemplar_wrap() const {
  return data_->exemplar_wrap;
}

const ParamValues& Model::params() const {
  return data_->params;
}

std::span<const MapInfo> Model::maps() const {
  return data_->maps;
}

Model with_colour_space(const Model& model, ColourSpace space) {
  if (model.empty()) throw std::invalid_argument("with_colour_space: the model is empty");
  if (!model.maps().empty())
    throw std::invalid_argument(
        "with_colour_space: a material's maps each have their colour space (MapInfo)");
  const ModelData& data = model.data();
  return assemble_model(data.params, data.model, data.maps,
                        image_channel_spaces(space, model.channels()), std::nullopt,
                        data.exemplar_wrap);
}

std::vector<std::uint8_t> serialize_model(const Model& model) {
  return write_model_record(record_of(model));
}

Model deserialize_model(std::span<const std::uint8_t> bytes, const std::string& source_name) {
  ModelRecord record = read_model_record(bytes, source_name);
  std::vector<float> removed;
  const auto table = std::find_if(record.arrays.begin(), record.arrays.end(),
                                  [](const auto& a) { return a.name == kRemovedDeviationArray; });
  std::vector<std::int64_t> table_shape;
  if (table != record.arrays.end()) {
    removed = std::move(table->values);
    table_shape = table->shape;
    record.arrays.erase(table);
  }
  MethodModel method_model = model_from_record(record, source_name);
  const int channels = std::visit([](const auto& m) { return m.channels(); }, method_model);
  const auto corrupt = [&](const std::string& problem) {
    return Error(ErrorCode::format, "'" + source_name + "' " + problem + "; the file is corrupt");
  };
  if (!record.maps.empty() && map_channels(record.maps) != channels)
    throw corrupt("declares maps of " + std::to_string(map_channels(record.maps)) +
                  " channels for a model of " + std::to_string(channels));
  if (!removed.empty() && (table_shape != std::vector<std::int64_t>{kRemovedSteps, channels} ||
                           !std::all_of(removed.begin(), removed.end(),
                                        [](float v) { return v >= 0.0f && v <= kMaxModelValue; })))
    throw corrupt("has a table of removed deviations of the wrong shape or values");
  try {
    return assemble_model(std::move(record.params), std::move(method_model), std::move(record.maps),
                          record.channel_spaces(channels), std::move(removed),
                          record.exemplar_wrap);
  } catch (const std::invalid_argument& e) {
    throw corrupt(std::string("has a colour that does not fit its model (") + e.what() + ")");
  }
}

void save_model(const Model& model, const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = serialize_model(model);
  write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Model load_model(const std::filesystem::path& path) {
  InputFile file(path, "a model file");
  const std::uint64_t max_size = 64 + kMaxModelHeaderBytes + 4 * kMaxModelArrayValues;
  if (file.size() > max_size)
    throw Error(ErrorCode::format,
                "'" + path.string() + "' is too large to be a stochtex model file");
  const std::string bytes = file.read_all(max_size, "check the path");
  return deserialize_model({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()},
                           path.string());
}

std::string describe_model(const Model& model) {
  const ModelRecord record = record_of(model);
  nlohmann::ordered_json json;
  json["method"] = record.method;
  json["channels"] = model.channels();
  json["params"] = record.params;
  if (!record.maps.empty()) json["maps"] = maps_json(record.maps);
  if (record.maps.empty()) json["colour_space"] = colour_space_name(record.colour_space);
  if (record.exemplar_wrap)
    json["exemplar_wrap_step"] = {record.exemplar_wrap->x, record.exemplar_wrap->y};
  json["scalars"] = record.scalars;
  auto arrays = nlohmann::ordered_json::array();
  std::size_t bytes = 0;
  for (const auto& array : record.arrays) {
    arrays.push_back({{"name", array.name}, {"shape", array.shape}});
    bytes += array.values.size() * sizeof(float);
  }
  json["arrays"] = arrays;
  json["array_bytes"] = bytes;
  return json.dump(2);
}

std::vector<NamedImage> model_images(const Model& model) {
  std::vector<NamedImage> images;
  for (const auto& array : record_of(model).arrays) {
    if (array.shape.size() != 3 || array.shape[2] < 1 || array.shape[2] > 4) continue;
    ImageF image(static_cast<int>(array.shape[1]), static_cast<int>(array.shape[0]),
                 static_cast<int>(array.shape[2]));
    std::copy(array.values.begin(), array.values.end(), image.pixels().begin());
    images.push_back({array.name, std::move(image)});
  }
  return images;
}

}  // namespace stochtex
