#include "stochtex/model.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "model/map_layout.hpp"
#include "model/model_data.hpp"
#include "model/model_file.hpp"
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

ModelRecord record_of(const Model& model) {
  ModelRecord record =
      std::visit([&](const auto& m) { return m.to_record(model.params()); }, model.data().model);
  record.maps = model.data().maps;
  return record;
}

}  // namespace

std::string_view Model::method() const {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kMethodName; },
                    data_->model);
}

int Model::channels() const {
  return std::visit([](const auto& m) { return m.channels(); }, data_->model);
}

const ParamValues& Model::params() const {
  return data_->params;
}

std::span<const MapInfo> Model::maps() const {
  return data_->maps;
}

std::vector<std::uint8_t> serialize_model(const Model& model) {
  return write_model_record(record_of(model));
}

Model deserialize_model(std::span<const std::uint8_t> bytes, const std::string& source_name) {
  ModelRecord record = read_model_record(bytes, source_name);
  MethodModel method_model = model_from_record(record, source_name);
  const int channels = std::visit([](const auto& m) { return m.channels(); }, method_model);
  if (!record.maps.empty() && map_channels(record.maps) != channels)
    throw Error(ErrorCode::format, "'" + source_name + "' declares maps of " +
                                       std::to_string(map_channels(record.maps)) +
                                       " channels for a model of " + std::to_string(channels) +
                                       "; the file is corrupt");
  return Model(std::make_shared<const ModelData>(
      ModelData{std::move(record.params), std::move(method_model), std::move(record.maps)}));
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
    if (array.shape.size() != 3) continue;
    ImageF image(static_cast<int>(array.shape[1]), static_cast<int>(array.shape[0]),
                 static_cast<int>(array.shape[2]));
    std::copy(array.values.begin(), array.values.end(), image.pixels().begin());
    images.push_back({array.name, std::move(image)});
  }
  return images;
}

}  // namespace stochtex
