#pragma once
// Models: what analysis builds and evaluation reads. A `Model` is immutable plain data behind a
// shared pointer (cheap to copy, safe to share between threads); its method-specific content is a
// closed variant dispatched once per batch, never per sample.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stochtex/colour.hpp"
#include "stochtex/image.hpp"

namespace stochtex {

// The most channels of an exemplar: one image has 1 to 4, a material (several aligned maps side
// by side, MapInfo) up to kMaxChannels. A method's registry row says how many it analyses
// (MethodInfo::max_channels).
inline constexpr int kMaxImageChannels = 4;
inline constexpr int kMaxChannels = 16;

struct Vec2d {
  double x = 0.0;
  double y = 0.0;
};

// The area a sample covers in model space (unit = one exemplar pixel): the derivatives of the
// sample position along the output's x and y axes. Zero means a point sample (no filtering).
struct Footprint {
  Vec2d dpdx;
  Vec2d dpdy;
};

// One value of an enumerated parameter (or a switch): the name a user writes and the number the
// model file stores.
struct ParamChoice {
  std::string_view name;
  double value;
};

// One parameter of a method, described once: this record feeds the CLI, the model file and docs.
struct ParamInfo {
  std::string_view name;
  double default_value;
  double min_value;
  double max_value;
  bool integer;
  std::string_view help;
  std::span<const ParamChoice> choices = {};  // when not empty, the only accepted values
  bool zero_chooses = false;  // 0 is accepted too: the analysis chooses the value from the exemplar
};

using ParamValues = std::map<std::string, double, std::less<>>;

struct MethodInfo {
  std::string_view name;
  std::string_view summary;
  std::span<const ParamInfo> params;
  // The most channels its analysis takes (stochtex.hpp: kMaxImageChannels for one image, up to
  // kMaxChannels for a material set).
  int max_channels = 4;
  // Whether a material's normal map is derived from its synthesised height (the Gaussian-model
  // methods: their slopes would otherwise not follow their height) rather than synthesised.
  bool derives_normals = true;
};

// A material model (stochtex/material.hpp) is analysed from several aligned maps whose channels
// sit side by side; each map's kind says how its channels are read and written.
enum class MapKind {
  colour,  // 1 or 3 channels of plain values (albedo, emission)
  normal,  // a tangent-space normal map, stored as 2 channels: the height's gradient
           // (-n_x / n_z, -n_y / n_z), x right, y up (OpenGL's convention)
  height,  // 1 channel, higher is brighter (displacement, bump)
  scalar,  // 1 channel of plain values (roughness, metallic, ambient occlusion)
};
struct MapInfo {
  std::string name;  // 1 to 32 of a-z, 0-9 and _, unique in a model
  MapKind kind = MapKind::colour;
  int channels = 1;  // the channels this map holds in the model (2 for a normal map, 0 derived)
  // A normal map derived from the height map `derived_from` (channels 0): its slopes are
  // slope_scale times the rendered height's gradient (stochtex/material.hpp, render_maps).
  std::string derived_from;
  double slope_scale = 0.0;
  // What its values are (stochtex/colour.hpp): by default srgb for a colour map analysed from a
  // PNG, data for every other kind.
  ColourSpace colour_space = ColourSpace::data;
};
std::string_view map_kind_name(MapKind kind);

// How tileable an exemplar is: the mean absolute difference between its last and first columns
// (x) or rows (y), the step a repeat of it shows at its wrap, divided by the mean absolute
// difference between neighbouring columns (rows) inside it; all channels together (wrap_steps,
// metrics/metrics.hpp, measures it). A tileable image gives about 1, a photo cut from a larger
// scene more (docs/inputs.md).
struct WrapSteps {
  double x = 1.0;
  double y = 1.0;
  double largest() const { return x > y ? x : y; }
};
// Beyond this wrap step an exemplar is not tileable: above the tileable exemplars' spread (1.25)
// with a margin for smaller ones' noisier wrap.
inline constexpr double kTileableWrapStep = 1.5;

struct ModelData;  // the closed variant of method models (src/model_data.hpp)

class Model {
 public:
  Model() = default;
  explicit Model(std::shared_ptr<const ModelData> data) : data_(std::move(data)) {}

  bool empty() const { return data_ == nullptr; }
  std::string_view method() const;
  int channels() const;
  const ParamValues& params() const;
  // The maps of a material model in channel order; empty for a model of one image.
  std::span<const MapInfo> maps() const;
  // What the colour channels of a model of one image are (its alpha is data), and what a
  // render's values are: linear light for srgb and linear, as they are for data (a model
  // written before colour spaces). A material's maps each have theirs (MapInfo::colour_space).
  ColourSpace colour_space() const;
  // The wrap steps of the exemplar it was analysed from, as given (before any change the method
  // made to it, such as tiling's make_tileable); none for a model made without one exemplar (a
  // target spectrum, a mix) or written before they were kept.
  std::optional<WrapSteps> exemplar_wrap() const;
  const ModelData& data() const { return *data_; }

 private:
  std::shared_ptr<const ModelData> data_;
};

// Model files (.stx, docs/design.md §7). Loading validates everything before allocating and
// throws stochtex::Error with a message naming the file and the problem.
void save_model(const Model& model, const std::filesystem::path& path);
Model load_model(const std::filesystem::path& path);
std::vector<std::uint8_t> serialize_model(const Model& model);
Model deserialize_model(std::span<const std::uint8_t> bytes, const std::string& source_name);

// The same model with its exemplar's values in `space` (stochtex/colour.hpp; the alpha of a
// grey + alpha or RGBA model stays data). Analysis does not depend on the colour space, so a
// model analysed as data, as every model written before colour spaces was, becomes a srgb one
// without analysing again. Throws std::invalid_argument for an empty model or a material (its
// maps each have theirs).
Model with_colour_space(const Model& model, ColourSpace space);

// A JSON description of a model: method, parameters, maps, array sizes (`stochtex info`).
std::string describe_model(const Model& model);

// The model's image-shaped arrays (height x width x 1 to 4 channels), by name: e.g. the texton of
// a texton model. Other arrays of three dimensions (tiling's level_tables: levels x tables x
// entries) are not images. For inspection and documentation (`stochtex info --export`).
struct NamedImage {
  std::string name;
  ImageF image;
};
std::vector<NamedImage> model_images(const Model& model);

}  // namespace stochtex
