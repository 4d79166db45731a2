#pragma once
// Histogram-preserving tiling and blending parameters (Heitz & Neyret, "High-Performance
// By-Example Noise using a Histogram-Preserving Blending Operator", HPG 2018), described once
// (methods/param_record.hpp). The record feeds the CLI (`-p name=value`), the model file and
// docs/methods/tiling.md.

#include <array>
#include <cstddef>

#include "methods/param_record.hpp"
#include "methods/tiling/model.hpp"

namespace stochtex::tiling {

// Whether the analysis makes the exemplar tileable first (make_tileable below); automatic: when its
// wrap step says it is not tileable.
enum class MakeTileable { off = 0, on = 1, automatic = 2 };

struct Params {
  double tile_radius = 0.0;
  Transport transport = Transport::per_channel;
  int iterations = 64;
  int lut_size = 32;
  int table_size = 1024;
  Blend blend = Blend::histogram;
  bool stationarity = false;
  MakeTileable make_tileable = MakeTileable::automatic;
  double rotation = 0.0;
  double scale_jitter = 0.0;
  double sharpness = 1.0;
  double height_blend = 0.0;

  bool operator==(const Params&) const = default;
};

inline constexpr std::array<ParamChoice, 2> kTransports = {{{"sliced", 0}, {"pca", 1}}};
inline constexpr std::array<ParamChoice, 3> kBlends = {
    {{"histogram", 0}, {"variance", 1}, {"linear", 2}}};

inline constexpr std::array<ParamChoice, 3> kMakeTileable = {{{"off", 0}, {"on", 1}, {"auto", 2}}};

inline constexpr std::array<ParamField<Params>, 12> kFields = {{
    chosen_number_field<&Params::tile_radius>(
        "tile_radius", 0.05, 4.0,
        "radius of the hexagonal tiles (the edge of the triangle lattice) as a fraction of the "
        "exemplar's smaller side; section 5.3 uses about one half. 0: chosen from the "
        "exemplar's spectrum, the smallest radius whose tile diameter spans the periods of all "
        "but 0.5% of its power, at least 1/4 and at most 1/2 (a tile as wide as the exemplar)"),
    choice_field<&Params::transport>(
        "transport", kTransports,
        "Gaussianisation T: pca (the default), PCA-decorrelated per-channel 1-D transport "
        "(section 2's decorrelated channels, Deliot & Heitz 2019); sliced, iterated sliced "
        "optimal transport in colour space (sections 4.1-4.3), which keeps the joint colour "
        "histogram of colours on a thin curved set better, at 5-6 times the analysis time and a "
        "32³ table per level"),
    number_field<&Params::iterations>(
        "iterations", 1, 2000,
        "iterations of the sliced transport, each along 3 orthogonal random directions "
        "(transport sliced)"),
    number_field<&Params::lut_size>(
        "lut_size", 2, 64,
        "cells per axis of the 3-D look-up table of T^-1 for colour exemplars (section 4.3)"),
    number_field<&Params::table_size>(
        "table_size", 16, 65536,
        "entries of each 1-D look-up table of T^-1 (grey and alpha channels, transport pca)"),
    choice_field<&Params::blend>(
        "blend", kBlends,
        "blending operator: histogram, histogram-preserving (eq. 18); variance, "
        "variance-preserving on the exemplar as is (eq. 8), the fast path for Gaussian inputs "
        "such as `stochtex gaussian` output (no T, no T^-1; section 6.1); linear (eq. 3), a "
        "baseline that loses contrast between vertices"),
    choice_field<&Params::stationarity>(
        "stationarity", kSwitch,
        "on: before the analysis, remove from the colour the variations of periods longer than "
        "about a tile (a periodic Gaussian high-pass of deviation tile edge / pi), the "
        "preprocessing of section 5.3 for exemplars with large-scale variations; the histogram "
        "kept is then the filtered exemplar's; off: the exemplar as is"),
    choice_field<&Params::make_tileable>(
        "make_tileable", kMakeTileable,
        "patches read across the exemplar's border (the lattice's offsets wrap around it): on, "
        "analyse the exemplar made tileable, its periodic component (Moisan 2011) with each "
        "channel's histogram put back exactly, so that a photo cut from a larger scene shows no "
        "seam inside the patches; off: the exemplar as is; auto: on when the exemplar is not "
        "tileable (its wrap step, as `analyze` reports it, beyond 1.5) and not a periodic "
        "pattern (more than a quarter of its power in spectral peaks, such as a woven check, "
        "whose misaligned phase the smoothing would blur). The model keeps the choice made"),
    number_field<&Params::rotation>(
        "rotation", 0.0, 180.0,
        "artist control: each tile's patch turns by a random angle uniform in [-rotation, "
        "+rotation] degrees about the tile's centre (0: no rotation, 180: any angle)"),
    number_field<&Params::scale_jitter>(
        "scale_jitter", 0.0, 1.0,
        "artist control: each tile's patch is read at a random scale 2^(u scale_jitter), u "
        "uniform in [-1, 1] (0: the exemplar's scale everywhere)"),
    number_field<&Params::sharpness>(
        "sharpness", 1.0, 32.0,
        "artist control: the blend weights raised to this power and renormalised before the "
        "blend (Burley 2019), narrowing the transitions between tiles (1: the barycentric "
        "weights of section 5.1)"),
    number_field<&Params::height_blend>(
        "height_blend", 0.0, 1.0,
        "artist control for a material with a height map: the patch of the highest height + "
        "weight wins at the transitions between tiles (the height blend of game engines, smooth "
        "form), over a transition of this width in the height's Gaussianised values (mean 1/2, "
        "deviation 1/6) plus the barycentric weight (smaller: sharper; 1: near the plain blend; "
        "0: off, the blend of section 5.1)"),
}};

inline constexpr auto kParams = param_infos(kFields);
// The artist controls are the last fields, from this index on. A model file stores them only when
// they differ from their defaults (TilingModel::to_record): a model with the defaults is
// byte-identical to one made before the controls existed, and such an older file loads with them.
inline constexpr std::size_t kFirstControl = 8;

// Artist control i of kParams (i >= kFirstControl) in the data.
inline double control(const TilingData& data, std::size_t index) {
  const double values[] = {data.rotation, data.scale_jitter, data.sharpness, data.height_blend};
  return values[index - kFirstControl];
}

}  // namespace stochtex::tiling
