#include "model/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

// xxHash's functions inlined here (header only): nothing to link, for stochtex nor its users.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include "model/map_layout.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

constexpr char kMagic[8] = {'S', 'T', 'O', 'C', 'H', 'T', 'E', 'X'};
constexpr std::size_t kPreambleBytes = sizeof(kMagic) + 4 + 4;
constexpr std::size_t kChecksumBytes = 8;
// The header is a flat document; deeper nesting is hostile and refused before parsing.
constexpr int kMaxJsonDepth = 4;
constexpr std::size_t kMaxArrays = 64;
constexpr std::size_t kMaxArrayRank = 4;
constexpr std::size_t kMaxNameLength = 64;
const std::string kArrayLimitText =
    "the " + std::to_string(kMaxModelArrayValues) + " values a model file may hold";

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

void put_u64(std::vector<std::uint8_t>& out, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint32_t get_u32(const std::uint8_t* p) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return value;
}

std::uint64_t get_u64(const std::uint8_t* p) {
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return value;
}

int json_depth(std::string_view text) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, const std::string& source)
      : bytes_(bytes), source_(source) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(ErrorCode::format, "'" + source_ + "' " + problem);
  }

  ModelRecord read() const {
    if (bytes_.size() < kPreambleBytes + kChecksumBytes ||
        std::memcmp(bytes_.data(), kMagic, sizeof(kMagic)) != 0)
      fail(
          "is not a stochtex model file (no STOCHTEX signature); create one with `stochtex "
          "analyze`");
    const std::uint32_t version = get_u32(bytes_.data() + 8);
    if (version > kModelFormatVersion)
      fail("uses model format version " + std::to_string(version) + ", newer than this stochtex (" +
           std::to_string(kModelFormatVersion) + "); upgrade stochtex to read it");
    if (version < kSingleImageModelFormatVersion)
      fail("uses the old model format version " + std::to_string(version) +
           "; re-run `stochtex analyze` to write version " + std::to_string(kModelFormatVersion));
    const std::uint32_t header_length = get_u32(bytes_.data() + 12);
    if (header_length > kMaxModelHeaderBytes)
      fail("declares a header of " + std::to_string(header_length) +
           " bytes, more than the limit; the file is corrupt or hostile");
    if (header_length > bytes_.size() - kPreambleBytes - kChecksumBytes)
      fail("is truncated (its header runs past the end of the file); re-run `stochtex analyze`");
    const std::size_t payload_end = bytes_.size() - kChecksumBytes;
    if (model_checksum(bytes_.first(payload_end)) != get_u64(bytes_.data() + payload_end))
      fail("fails its checksum: the file is truncated or corrupt; re-run `stochtex analyze`");

    const std::string_view header(reinterpret_cast<const char*>(bytes_.data() + kPreambleBytes),
                                  header_length);
    if (json_depth(header) > kMaxJsonDepth) fail("has a malformed header (nested too deeply)");
    const nlohmann::json json = nlohmann::json::parse(header, nullptr, false);
    if (json.is_discarded() || !json.is_object()) fail("has a malformed header (not JSON)");

    ModelRecord record;
    const auto method = json.find("method");
    if (method == json.end() || !method->is_string() || method->get<std::string>().empty() ||
        method->get<std::string>().size() > kMaxNameLength)
      fail("has no method name in its header; the file is corrupt");
    record.method = method->get<std::string>();
    record.params = numbers(json, "params");
    record.scalars = numbers(json, "scalars");
    const auto maps = json.find("maps");
    if (version == kMaterialModelFormatVersion && maps == json.end())
      fail("is a version-2 model file without its list of maps; the file is corrupt");
    if (version == kSingleImageModelFormatVersion && maps != json.end())
      fail("has a list of maps in a version-1 model file; the file is corrupt");
    if (maps != json.end()) record.maps = read_maps(*maps, version);
    const auto space = json.find("colour_space");
    if (space != json.end()) {
      if (version < kColourModelFormatVersion || maps != json.end())
        fail("has a colour space where its format version holds none; the file is corrupt");
      record.colour_space = read_colour_space(*space);
    }
    if (version == kColourModelFormatVersion && !has_colour(record))
      fail("is a version-3 model file without a colour space; the file is corrupt");
    if (const auto wrap = json.find("exemplar_wrap_step"); wrap != json.end()) {
      const auto step = [&](std::size_t i) {
        const double value = wrap->is_array() && wrap->size() == 2 && (*wrap)[i].is_number()
                                 ? (*wrap)[i].get<double>()
                                 : -1.0;
        if (!(value >= 0.0 && std::isfinite(value)))
          fail(
              "has an exemplar wrap step that is not two finite numbers >= 0; the file is "
              "corrupt");
        return value;
      };
      record.exemplar_wrap = WrapSteps{step(0), step(1)};
    }

    const auto arrays = json.find("arrays");
    if (arrays == json.end() || !arrays->is_array() || arrays->size() > kMaxArrays)
      fail("has a malformed array list in its header; the file is corrupt");
    std::uint64_t total_values = 0;
    std::set<std::string> names;
    std::vector<std::pair<std::string, std::vector<std::int64_t>>> declared;
    for (const auto& entry : *arrays) {
      const auto name = entry.find("name");
      const auto shape = entry.find("shape");
      if (!entry.is_object() || name == entry.end() || !name->is_string() || shape == entry.end() ||
          !shape->is_array() || shape->empty() || shape->size() > kMaxArrayRank)
        fail("has a malformed array declaration in its header; the file is corrupt");
      const std::string array_name = name->get<std::string>();
      if (array_name.empty() || array_name.size() > kMaxNameLength ||
          !names.insert(array_name).second)
        fail("declares an empty, overlong or repeated array name; the file is corrupt");
      std::vector<std::int64_t> dims;
      std::uint64_t values = 1;
      for (const auto& dim : *shape) {
        if (!dim.is_number_integer() || dim.get<std::int64_t>() < 1 ||
            static_cast<std::uint64_t>(dim.get<std::int64_t>()) > kMaxModelArrayValues)
          fail("declares array '" + array_name + "' with an invalid size; the file is corrupt");
        dims.push_back(dim.get<std::int64_t>());
        values *= static_cast<std::uint64_t>(dims.back());  // each factor <= 2^28, rank <= 4
        if (values > kMaxModelArrayValues)
          fail("declares array '" + array_name + "' of more than " + kArrayLimitText +
               "; the file is corrupt or hostile");
      }
      total_values += values;
      if (total_values > kMaxModelArrayValues)
        fail("declares arrays of more than " + kArrayLimitText +
             "; the file is corrupt or hostile");
      declared.emplace_back(array_name, std::move(dims));
    }
    const std::size_t data_begin = kPreambleBytes + header_length;
    if (total_values * 4 != payload_end - data_begin)
      fail("holds " + std::to_string(payload_end - data_begin) + " bytes of array data where its " +
           "header declares " + std::to_string(total_values * 4) +
           "; the file is truncated or corrupt");

    const std::uint8_t* cursor = bytes_.data() + data_begin;
    for (auto& [name, dims] : declared) {
      NamedArray array{std::move(name), std::move(dims), {}};
      std::size_t count = 1;
      for (const auto dim : array.shape) count *= static_cast<std::size_t>(dim);
      array.values.resize(count);
      for (float& value : array.values) {
        const std::uint32_t bits = get_u32(cursor);
        std::memcpy(&value, &bits, sizeof(value));
        cursor += 4;
      }
      record.arrays.push_back(std::move(array));
    }
    return record;
  }

 private:
  ParamValues numbers(const nlohmann::json& json, const char* key) const {
    const auto object = json.find(key);
    if (object == json.end() || !object->is_object())
      fail(std::string("has no '") + key + "' object in its header; the file is corrupt");
    ParamValues values;
    for (const auto& [name, value] : object->items()) {
      if (!value.is_number() || !std::isfinite(value.get<double>()) || name.empty() ||
          name.size() > kMaxNameLength)
        fail(std::string("has an invalid entry '") + name.substr(0, kMaxNameLength) + "' in '" +
             key + "'; the file is corrupt");
      values[name] = value.get<double>();
    }
    return values;
  }

  ColourSpace read_colour_space(const nlohmann::json& value) const {
    const auto space =
        value.is_string() ? colour_space_from_name(value.get<std::string>()) : std::nullopt;
    if (!space.has_value())
      fail(
          "has an unknown colour space in its header; the file is corrupt or newer than this "
          "stochtex");
    return *space;
  }

  std::vector<MapInfo> read_maps(const nlohmann::json& list, std::uint32_t version) const {
    if (!list.is_array() || list.size() > static_cast<std::size_t>(kMaxChannels))
      fail("has a malformed list of maps in its header; the file is corrupt");
    std::vector<MapInfo> maps;
    for (const auto& entry : list) {
      const auto name = entry.is_object() ? entry.find("name") : entry.end();
      const auto kind = entry.is_object() ? entry.find("kind") : entry.end();
      const auto channels = entry.is_object() ? entry.find("channels") : entry.end();
      if (!entry.is_object() || name == entry.end() || !name->is_string() || kind == entry.end() ||
          !kind->is_string() || channels == entry.end() || !channels->is_number_integer() ||
          !map_kind_from_name(kind->get<std::string>()).has_value())
        fail("has a malformed map declaration in its header; the file is corrupt");
      const auto count = channels->get<std::int64_t>();
      if (count < 0 || count > kMaxChannels)
        fail("declares a map of " + std::to_string(count) + " channels; the file is corrupt");
      MapInfo map{name->get<std::string>(),
                  *map_kind_from_name(kind->get<std::string>()),
                  static_cast<int>(count),
                  {},
                  0.0};
      const auto from = entry.find("from");
      const auto scale = entry.find("scale");
      if ((from == entry.end()) != (scale == entry.end()) ||
          (from != entry.end() && (!from->is_string() || !scale->is_number())))
        fail("has a malformed map declaration in its header; the file is corrupt");
      if (from != entry.end()) {
        map.derived_from = from->get<std::string>();
        map.slope_scale = scale->get<double>();
      }
      const auto space = entry.find("colour_space");
      if (space != entry.end()) {
        if (version < kColourModelFormatVersion)
          fail("has a colour space where its format version holds none; the file is corrupt");
        map.colour_space = read_colour_space(*space);
      }
      maps.push_back(std::move(map));
    }
    if (const auto problem = map_layout_problem(maps)) fail(*problem + "; the file is corrupt");
    return maps;
  }

  std::span<const std::uint8_t> bytes_;
  const std::string& source_;
};

}  // namespace

bool has_colour(const ModelRecord& record) {
  return record.colour_space != ColourSpace::data ||
         std::any_of(record.maps.begin(), record.maps.end(),
                     [](const MapInfo& map) { return map.colour_space != ColourSpace::data; });
}

std::vector<std::uint8_t> write_model_record(const ModelRecord& record) {
  std::uint64_t values = 0;
  for (const auto& array : record.arrays) values += array.values.size();
  if (values > kMaxModelArrayValues)
    throw Error(ErrorCode::invalid_input,
                "the " + record.method + " model holds " + std::to_string(values) +
                    " values, more than " + kArrayLimitText +
                    " within the memory budget; analyse a smaller exemplar");
  nlohmann::ordered_json header;
  header["method"] = record.method;
  header["params"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : record.params) header["params"][name] = value;
  header["scalars"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : record.scalars) header["scalars"][name] = value;
  header["arrays"] = nlohmann::ordered_json::array();
  for (const auto& array : record.arrays)
    header["arrays"].push_back({{"name", array.name}, {"shape", array.shape}});
  if (!record.maps.empty()) header["maps"] = maps_json(record.maps);
  if (record.maps.empty() && record.colour_space != ColourSpace::data)
    header["colour_space"] = colour_space_name(record.colour_space);
  if (record.exemplar_wrap)
    header["exemplar_wrap_step"] = {record.exemplar_wrap->x, record.exemplar_wrap->y};
  const std::string text = header.dump();

  std::vector<std::uint8_t> out(std::begin(kMagic), std::end(kMagic));
  put_u32(out, kModelFormatVersion);
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  out.insert(out.end(), text.begin(), text.end());
  for (const auto& array : record.arrays)
    for (const float value : array.values) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &value, sizeof(bits));
      put_u32(out, bits);
    }
  put_u64(out, model_checksum(out));
  return out;
}

std::uint64_t model_checksum(std::span<const std::uint8_t> bytes_before_checksum) {
  if (bytes_before_checksum.size() >= kPreambleBytes &&
      get_u32(bytes_before_checksum.data() + sizeof(kMagic)) >= kModelFormatVersion)
    return XXH3_64bits(bytes_before_checksum.data(), bytes_before_checksum.size());
  std::uint64_t hash = 14695981039346656037ull;
  for (const std::uint8_t byte : bytes_before_checksum) {
    hash ^= byte;
    hash *= 1099511628211ull;
  }
  return hash;
}

ModelRecord read_model_record(std::span<const std::uint8_t> bytes, const std::string& source_name) {
  return Reader(bytes, source_name).read();
}

}  // namespace stochtex
