#pragma once
// Histogram-preserving tiling and blending model (Heitz & Neyret 2018): the Gaussianised exemplar
// G = T(X) (sections 4.1-4.2), the inverse T^-1 as look-up tables (section 4.3), and, derived at
// construction, the mip pyramid of G and T^-1 prefiltered for each pyramid level (section 5.4 and
// the follow-up of Deliot & Heitz 2019), plus the triplanar operator of figure 16.
//
// Channels: 1 (grey), 2 (grey + alpha), 3 (colour), 4 (colour + alpha). Alpha is carried as its
// own channel with its own 1-D transport and table: it is tiled and blended like the colour (so its
// histogram is preserved too) but never enters the colour transport or the colour look-up table.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "methods/tiling/evaluate.hpp"
#include "model/model_record.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"
#include "stochtex/surface.hpp"

namespace stochtex::tiling {

struct SimdTiling;

enum class Transport { sliced = 0, per_channel = 1 };
// The blending operator (section 3): histogram-preserving (eq. 18), variance-preserving (eq. 8,
// exact for Gaussian inputs: the fast path of section 6.1) or linear (eq. 3, a baseline).
enum class Blend { histogram = 0, variance = 1, linear = 2 };

// How one group of channels goes through T and T^-1: the 3-D table of section 4.3 (3 channels,
// sliced transport; at most one group), 1-D tables on the group's principal axes (Deliot & Heitz
// 2019), one 1-D table (one channel), or the radial transform of a normal map's two slopes that
// commutes with rotation (one table of |s|: radial_lookup in evaluate.hpp; materials whose
// patches turn or scale).
enum class GroupTransform { lut = 0, decorrelated = 1, direct = 2, radial = 3 };
struct GroupSpec {
  GroupTransform transform = GroupTransform::direct;
  int channels = 1;
  bool operator==(const GroupSpec&) const = default;
};

// The exemplar sides a model takes: 2 to kMaxExemplarSide pixels.
inline constexpr int kMaxExemplarSide = 1 << 16;

// The plain data of a model, as analysis builds it and the model file stores it.
struct TilingData {
  int channels = 0;
  int width = 0;  // exemplar size in pixels
  int height = 0;
  double tile_radius = 0.5;  // lattice edge / min(width, height)
  Transport transport = Transport::sliced;
  int lut_size = 32;
  int table_size = 1024;
  Blend blend = Blend::histogram;  // variance and linear: no T, no T^-1 (section 6.1)
  // The artist controls (params.hpp): each patch's random rotation (degrees) and scale jitter,
  // and the blend weights' exponent (Burley 2019). The defaults are the paper's operator.
  double rotation = 0.0;
  double scale_jitter = 0.0;
  double sharpness = 1.0;
  // The height-aware blend (height_blend_weights): the transition's width in Gaussian values,
  // 0 when off; the channel of the material's height map when on, -1 when off.
  double height_blend = 0.0;
  int height_channel = -1;
  // Whether the analysis made the exemplar tileable (params.hpp's make_tileable, resolved): the
  // evaluator does not need it; the record's parameters keep it.
  bool made_tileable = false;
  std::vector<float> gaussian;      // height x width x channels: T(X), or X itself without T
  std::vector<float> blend_mean;    // channels: E[G] in eq. (8)
  std::vector<float> lut;           // lut_size^3 x 3, T^-1 of the colour (3-D transport), or empty
  std::vector<float> tables;        // table_count x table_size, 1-D T^-1 tables, or empty
  std::vector<float> colour_basis;  // each decorrelated group's channels^2, row-major, or empty
  std::vector<float> colour_mean;   // each decorrelated group's channels, or empty
  // T^-1 by groups of channels, a material's maps (issue 18); empty: an image's colour and alpha
  // (tiling_layout).
  std::vector<GroupSpec> groups;
  // Derived, optional: the 1-D tables of T^-1 prefiltered for every pyramid level and calibrated
  // (TilingModel::level_tables), as the model file stores them so that a load need not rebuild
  // them; empty: built at construction. Never with the 3-D table, whose 32³ per level would make
  // the file several times larger.
  std::vector<float> level_tables;
  // Each channel's colour space (model/model_colour.hpp), or empty: every channel data. Not in
  // the tiling record: the model file's header holds it. The 3-D table's and the direct 1-D
  // tables' srgb channels are decoded before they are prefiltered, so that each level's T^-1
  // returns the expectation of the decoded colour (decodes_in_tables).
  std::vector<ColourSpace> colour;
};

// One group of channels of T^-1 and where its tables are.
struct TableGroup {
  GroupTransform transform = GroupTransform::direct;
  int first = 0;  // its first channel
  int channels = 1;
  int first_table = 0;  // its 1-D tables: one per channel (decorrelated) or one (direct, radial)
  int first_basis = 0;  // decorrelated: its channels^2 values in colour_basis
  int first_mean = 0;   // decorrelated: its channels values in colour_mean
};

// How the arrays of TilingData are laid out for a channel count, transport and blend. The fields
// before `groups` describe an image (colour, then alpha when it has 2 or 4 channels), as the GLSL
// twin reads them; a material's groups have no such description (image_layout false).
struct TilingLayout {
  int colour_channels = 0;    // 1 or 3
  bool has_alpha = false;     // the last channel is alpha
  bool colour_lut = false;    // colour through the 3-D table (else 1-D tables + basis)
  int table_count = 0;        // 1-D tables: decorrelated colour channels (if no 3-D table), alpha
  int first_alpha_table = 0;  // index of the alpha table when has_alpha
  bool image_layout = true;
  std::vector<TableGroup> groups;  // empty for the variance and linear blends
  int basis_size = 0;
  int mean_size = 0;
};
// `groups` empty: an image's colour (3-D table with sliced transport and 3 colour channels, else
// decorrelated) and alpha (direct). Throws std::invalid_argument for groups that do not cover
// the channels, a 3-D table that is not the one group of 3 channels with sliced transport, or a
// direct group of more than one channel.
TilingLayout tiling_layout(int channels, Transport transport, Blend blend,
                           std::span<const GroupSpec> groups = {});

// Which pyramid levels a footprint reads: level `level` blended with level + 1 by `blend`.
struct LevelOfDetail {
  int level = 0;
  float blend = 0.0f;
};

class TilingModel {
 public:
  static constexpr std::string_view kMethodName = "tiling";

  // Validates sizes and ranges (throws std::invalid_argument) and derives the pyramid and the
  // prefiltered tables.
  explicit TilingModel(TilingData data);

  static TilingModel from_record(const ModelRecord& record, const std::string& source);
  ModelRecord to_record(const ParamValues& params) const;
  // The choices the analysis made in place of its parameters' automatic values: the tile radius
  // used (tile_radius 0) and whether the exemplar was made tileable (make_tileable auto), as the
  // model file's parameters hold them (analyze_exemplar applies it to a new model's).
  void resolve_params(ParamValues& params) const;

  int channels() const { return data_.channels; }
  const TilingData& data() const { return data_; }
  const TilingLayout& layout() const { return layout_; }
  double lattice_edge() const { return edge_; }
  int level_count() const { return static_cast<int>(levels_.size()); }
  MipLevel level(int index) const;
  // T^-1 prefiltered for pyramid level `index`: the 3-D table and the 1-D tables, each empty when
  // the model has none (no T^-1 at all for the variance and linear blends). For the GLSL twin of
  // the evaluator (gl_data.cpp).
  std::span<const float> level_lut(int index) const {
    return std::span<const float>(level_luts_)
        .subspan(static_cast<std::size_t>(index) * lut_floats_, lut_floats_);
  }
  std::span<const float> level_tables(int index) const {
    return std::span<const float>(level_tables_)
        .subspan(static_cast<std::size_t>(index) * table_floats_, table_floats_);
  }

  // Algorithm 1 at each position, filtered by the footprint when it is wider than a pixel.
  // noexcept, no allocation.
  void evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                std::uint32_t seed, ImageView<float> out) const noexcept;
  // evaluate() for a field of model-space period `period` (PeriodicLattice). The scalar loop, for
  // periodic renders (docs/render.md). noexcept, no allocation.
  void evaluate_periodic(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                         std::uint32_t seed, ImageView<float> out, Vec2d period) const noexcept;

  // The pyramid levels a footprint reads (footprint == nullptr: a point sample, level 0), from
  // its width: the longer axis (footprint_width; 0 for nullptr).
  LevelOfDetail level_of_detail(const Footprint* footprint) const noexcept {
    return level_of_detail(footprint_width(footprint));
  }
  LevelOfDetail level_of_detail(double width) const noexcept;
  static double footprint_width(const Footprint* footprint) noexcept;
  // Level int(lod) blended with the next by the fraction, clamped to the top level.
  LevelOfDetail split_level(double lod) const noexcept;
  // Steps 1-2 of Algorithm 1: three patches of G, variance-preserving blend (eq. 13), for a
  // footprint of width `footprint_width` (exemplar pixels; 0: a point sample). `g` gets
  // `channels()` values. Returns the level of detail of T^-1 (step 3): the footprint's, or, with
  // scale jitter (each patch at its own level), the w^2-weighted mean of the patches' levels, as
  // evaluate_triplanar does for its planes. With height_blend on, the weights are the
  // height-aware ones (height_blend_weights) of the patches' heights.
  // `periodic` (not null): the periodic lattice's vertices and patch translations
  // (PeriodicLattice), `position` reduced into its period.
  LevelOfDetail blended_gaussian(Vec2d position, double footprint_width, std::uint32_t seed,
                                 float* g,
                                 const PeriodicLattice* periodic = nullptr) const noexcept;
  // Whether the T^-1 tables return channel `channel` as linear light (the 3-D table's and the
  // direct tables' srgb channels); the others (decorrelated groups, the variance and linear
  // blends) are decoded after evaluation (model/model_colour.hpp).
  bool decodes_in_tables(int channel) const noexcept;
  // The same model with each channel's colour space (TilingData::colour).
  TilingModel with_colour(std::vector<ColourSpace> colour) const;
  // The level tables of the srgb channels decoded after evaluation (a decorrelated group of
  // several channels, which mixes its tables linearly: model/model_colour.hpp), shifted per level
  // so that the level's decoded renders average what decoded point samples average, as
  // calibrate_colour does for the channels decoded in the tables: by D(v, r(w)) (model_colour.hpp,
  // expected_decoded), `removed(channel, width)` giving r(w) for a footprint of width `width`.
  // Runs once: nothing to do for tables a model file stored (calibrated when it was written) or
  // already calibrated.
  void calibrate_decoded(const std::function<float(int, double)>& removed);
  // The rotation or the scale jitter is on.
  bool transformed() const noexcept { return data_.rotation > 0.0 || data_.scale_jitter > 0.0; }
  // Step 3: T^-1 by the look-up tables prefiltered for `lod` (eq. 22, section 4.3); the identity
  // for the variance and linear blends.
  void inverse_transform(const float* g, LevelOfDetail lod, float* out) const noexcept;

  // Triplanar histogram-preserving blending (figure 16; evaluate_surface with
  // SurfaceMapping::triplanar, src/render/surface.cpp): the tiling noise projected on the three
  // axis planes (y,z), (z,x), (x,y) (core/triplanar.hpp), each plane's steps 1-2 at the level of
  // detail of the 3-D footprint projected on it, blended with the normal's weights |n_k|^sharpness
  // / sum by the variance-preserving operator of eq. (13) in Gaussian space, then one T^-1
  // look-up (step 3) per point. Plane k draws its patches from the seed triplanar_seed(k, seed).
  // height_blend applies within each plane (its lattice's patches); the planes keep the normal's
  // weights, which say where the surface faces, not which patch is higher.
  // `out` holds points.size() pixels in row-major order. noexcept, no allocation. The GLSL twin
  // is stochtex_tiling_triplanar (triplanar.glsl).
  void evaluate_triplanar(std::span<const SurfacePoint> points, double sharpness,
                          std::uint32_t seed, ImageView<float> out) const noexcept;
  // The seed of plane k's patches: cell_key(k, 0, seed, Stream::offsets), a hash, so the three
  // planes' streams differ from each other and are unrelated to the planar seeds seed, seed + 1,
  // ... (the linear baseline's planes use seed + k: plane 1 of seed s is plane 0 of seed s + 1).
  static std::uint32_t triplanar_seed(int plane, std::uint32_t seed) noexcept {
    return cell_key(plane, 0, seed, Stream::offsets);
  }

 private:
  void inverse_at_level(const float* g, int level, float* out) const noexcept;
  // The level tables of the channels decoded in them, corrected so that each level's renders
  // average what point samples average (docs/design.md §14).
  void calibrate_colour();
  // What the calibrations measure: the model's values (channels interleaved) at 32 768 positions
  // far apart (independent patches), seed 0, as point samples, at_level(0, 0, values), then with
  // the footprint of each level l >= 1, at_level(l, its width, values), in that order (a
  // calibration may shift level l's tables before level l + 1 is measured).
  void measure_levels(
      const std::function<void(int, double, std::span<const float>)>& at_level) const;
  // evaluate's vectorised path (simd.hpp), when simd_ready_.
  SimdTiling simd_tiling() const noexcept;
  void evaluate_simd(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                     std::uint32_t seed, ImageView<float> out) const noexcept;

  TilingData data_;
  TilingLayout layout_;
  double edge_ = 0.0;
  // Derived at construction. Every level's texels in one array, and every level's tables in one
  // array, so that the vectorised evaluator reads any level of a lane by one index.
  struct PyramidLevel {
    int width = 0;
    int height = 0;
    std::size_t first = 0;  // its texels in pyramid_
  };
  std::vector<PyramidLevel> levels_;
  std::vector<float> pyramid_;
  bool has_radial_group_ = false;  // a normal map's slopes, turned with their patches
  // Level l's 3-D table (lut_size^3 x 3) at l * lut_floats_ and 1-D tables (table_count x
  // table_size) at l * table_floats_; no level has any without T^-1 (variance and linear blends).
  std::vector<float> level_luts_;
  std::vector<float> level_tables_;
  std::size_t lut_floats_ = 0;
  std::size_t table_floats_ = 0;
  // The level tables are calibrated for decoding after evaluation (calibrate_decoded ran, or the
  // model file stored them), so that a model assembled again is not shifted twice.
  bool decoded_calibrated_ = false;
  // The vectorised evaluator takes this model: the paper's operator (no artist control, no
  // radial group) and every index within int32.
  bool simd_ready_ = false;
};

}  // namespace stochtex::tiling
