// The tiling model's CPU evaluator (Algorithm 1 of the paper, its inner loop in evaluate.hpp; the
// vectorised path in simd.cpp) and its triplanar form (figure 16).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>

#include "core/cpu_target.hpp"
#include "core/level_of_detail.hpp"
#include "core/triplanar.hpp"
#include "methods/tiling/model.hpp"
#include "methods/tiling/simd.hpp"

namespace stochtex::tiling {

double TilingModel::footprint_width(const Footprint* footprint) noexcept {
  if (footprint == nullptr) return 0.0;
  // Isotropic: the longer axis decides, as GPU trilinear filtering does without anisotropy.
  return std::max(std::hypot(footprint->dpdx.x, footprint->dpdx.y),
                  std::hypot(footprint->dpdy.x, footprint->dpdy.y));
}

LevelOfDetail TilingModel::level_of_detail(double width) const noexcept {
  // Section 5.4: the footprint is the derivative of the position *before* the random offsets (a
  // translation does not change it), so the three patches read the same level (unless scale
  // jitter scales a patch's footprint; a rotation keeps its width).
  if (!(width > 1.0)) return {};
  const double lod = std::log2(width) - kLodBias;
  const int top = level_count() - 1;
  if (!(lod > 0.0)) return {};
  if (lod >= top) return {top, 0.0f};
  const int level = static_cast<int>(lod);
  return {level, static_cast<float>(lod - level)};
}

LevelOfDetail TilingModel::split_level(double lod) const noexcept {
  // A mean of levels may round past the top one: clamped there with no blend, as
  // level_of_detail does (a blend at the top would read beyond the pyramid).
  const int top = level_count() - 1;
  if (lod >= top) return {top, 0.0f};
  return {static_cast<int>(lod), static_cast<float>(lod - static_cast<int>(lod))};
}

LevelOfDetail TilingModel::blended_gaussian(Vec2d position, double footprint_width,
                                            std::uint32_t seed, float* g,
                                            const PeriodicLattice* periodic) const noexcept {
  const int channels = data_.channels;
  const LatticePoint lattice =
      periodic != nullptr ? periodic->lattice(position) : triangle_lattice(position, edge_);
  const LevelOfDetail lod = level_of_detail(footprint_width);
  const Point2f wrapped = periodic != nullptr ? Point2f{0.0f, 0.0f}
                                              : wrap_position(position, data_.width, data_.height);
  const bool transformed = this->transformed();
  const auto max_angle = static_cast<float>(data_.rotation * (std::numbers::pi / 180.0));
  const auto jitter = static_cast<float>(data_.scale_jitter);
  const auto edge = static_cast<float>(edge_);
  float weight[3] = {lattice.weight[0], lattice.weight[1], lattice.weight[2]};
  sharpen_weights(weight, static_cast<float>(data_.sharpness));
  float acc[kMaxChannels] = {};
  float weight_squares = 0.0f;
  double weighted_lod = 0.0;
  // The height-aware blend and the turn of a normal map's slopes: each patch fetched apart, then
  // turned (turn_slopes) and weighted by its height (below).
  const bool height_aware = data_.height_blend > 0.0;
  const bool turned = transformed && has_radial_group_;
  float patch[3][kMaxChannels];
  double patch_level[3] = {};
  for (int v = 0; v < 3; ++v) {
    const float w = weight[v];
    weight_squares += w * w;
    std::int64_t key_x = lattice.vertex_x[v];
    std::int64_t key_y = lattice.vertex_y[v];
    Point2f base = wrapped;
    Point2f local{0.0f, 0.0f};
    if (periodic != nullptr) {
      const PeriodicLattice::Vertex vertex = periodic->vertex(position, key_x, key_y);
      key_x = vertex.key_x;
      key_y = vertex.key_y;
      base = vertex.translation;
      local = vertex.local;
    }
    const Point2f offset = vertex_offset(key_x, key_y, seed, data_.width, data_.height);
    float x = base.x + offset.x;
    float y = base.y + offset.y;
    LevelOfDetail patch_lod = lod;
    PatchTransform m{1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
    if (transformed) {
      m = patch_transform(key_x, key_y, seed, max_angle, jitter);
      // M (p - vertex) - (p - vertex): in the default lattice from the skewed units, in the
      // periodic one from p - vertex in model space (its lattice is stretched).
      const Point2f shift = periodic != nullptr ? transform_shift(m, local)
                                                : patch_shift(m, lattice.from_vertex_x[v],
                                                              lattice.from_vertex_y[v], edge);
      x += shift.x;
      y += shift.y;
      patch_lod = level_of_detail(footprint_width * m.scale);
      weighted_lod +=
          static_cast<double>(w) * w * (patch_lod.level + static_cast<double>(patch_lod.blend));
    }
    const MipLevel fine = level(patch_lod.level);
    if (height_aware || turned) {
      std::fill_n(patch[v], channels, 0.0f);
      fetch_bilinear(fine, channels, x, y, 1.0f - patch_lod.blend, patch[v]);
      if (patch_lod.blend > 0.0f)
        fetch_bilinear(level(std::min(patch_lod.level + 1, level_count() - 1)), channels, x, y,
                       patch_lod.blend, patch[v]);
      patch_level[v] = patch_lod.level + static_cast<double>(patch_lod.blend);
      if (turned)
        for (const TableGroup& group : layout_.groups)
          if (group.transform == GroupTransform::radial)
            turn_slopes(m,
                        data_.tables.data() +
                            static_cast<std::ptrdiff_t>(group.first_table) * data_.table_size,
                        data_.table_size, patch[v] + group.first);
      continue;
    }
    fetch_bilinear(fine, channels, x, y, w * (1.0f - patch_lod.blend), acc);
    if (patch_lod.blend > 0.0f)
      fetch_bilinear(level(std::min(patch_lod.level + 1, level_count() - 1)), channels, x, y,
                     w * patch_lod.blend, acc);
  }
  if (height_aware || turned) {
    // The same variance-preserving blend (eq. 13 of Heitz & Neyret 2018, DOI 10.1145/3233304) of
    // the patches kept apart, with the weights from their Gaussianised heights when height_blend is
    // on: sum w' = 1, normalised by sqrt(sum w'^2).
    if (height_aware) {
      const float heights[3] = {patch[0][data_.height_channel], patch[1][data_.height_channel],
                                patch[2][data_.height_channel]};
      height_blend_weights(weight, heights, static_cast<float>(data_.height_blend));
    }
    weight_squares = 0.0f;
    weighted_lod = 0.0;
    for (int v = 0; v < 3; ++v) {
      const float w = weight[v];
      weight_squares += w * w;
      weighted_lod += static_cast<double>(w) * w * patch_level[v];
      for (int c = 0; c < channels; ++c) acc[c] += w * patch[v][c];
    }
  }
  blend_to_gaussian(ScalarOps{}, channels, data_.blend == Blend::linear, data_.blend_mean.data(),
                    weight_squares, acc, g);
  return data_.scale_jitter > 0.0 ? split_level(weighted_lod / weight_squares) : lod;
}

void TilingModel::inverse_at_level(const float* g, int level, float* out) const noexcept {
  const std::span<const float> tables = level_tables(level);
  const int size = data_.table_size;
  for (const TableGroup& group : layout_.groups) {
    const float* gg = g + group.first;
    float* o = out + group.first;
    if (group.transform == GroupTransform::lut) {
      // Trilinear fetch of the 3-D table at U of eq. (22).
      const float* lut = level_lut(level).data();
      lut_value(
          ScalarOps{}, data_.lut_size, gg,
          [&](int corner, std::ptrdiff_t offset) { return (lut + corner)[offset]; }, o);
    } else if (group.transform == GroupTransform::decorrelated) {
      // 1-D tables per decorrelated channel, then back to the group's basis.
      const int cc = group.channels;
      float decorrelated[kMaxChannels];
      for (int c = 0; c < cc; ++c)
        decorrelated[c] = table_lookup(
            ScalarOps{}, tables.data() + static_cast<std::ptrdiff_t>(group.first_table + c) * size,
            0, size, gg[c]);
      from_decorrelated(ScalarOps{}, cc, data_.colour_basis.data() + group.first_basis,
                        data_.colour_mean.data() + group.first_mean, decorrelated, o);
    } else if (group.transform == GroupTransform::radial) {
      // The magnitude from the (prefiltered) radial table, along g's direction from the centre.
      const float dx = gg[0] - kGaussianMean;
      const float dy = gg[1] - kGaussianMean;
      const float rho = std::sqrt(dx * dx + dy * dy);
      const float magnitude =
          rho > 0.0f
              ? radial_lookup(tables.data() + static_cast<std::ptrdiff_t>(group.first_table) * size,
                              size, rho) /
                    rho
              : 0.0f;
      o[0] = magnitude * dx;
      o[1] = magnitude * dy;
    } else {
      o[0] = table_lookup(ScalarOps{},
                          tables.data() + static_cast<std::ptrdiff_t>(group.first_table) * size, 0,
                          size, gg[0]);
    }
  }
}

void TilingModel::inverse_transform(const float* g, LevelOfDetail lod, float* out) const noexcept {
  const int channels = data_.channels;
  if (data_.blend != Blend::histogram) {
    for (int c = 0; c < channels; ++c) out[c] = g[c];
    return;
  }
  inverse_at_level(g, lod.level, out);
  if (lod.blend > 0.0f) {
    float coarse[kMaxChannels];
    inverse_at_level(g, lod.level + 1, coarse);
    for (int c = 0; c < channels; ++c) out[c] = interpolate(out[c], coarse[c], lod.blend);
  }
}

void TilingModel::evaluate(std::span<const Vec2d> positions, std::span<const Footprint> footprints,
                           std::uint32_t seed, ImageView<float> out) const noexcept {
  if (simd_ready_ && simd_enabled()) return evaluate_simd(positions, footprints, seed, out);
  for (std::size_t index = 0; index < positions.size(); ++index) {
    float g[kMaxChannels];
    const LevelOfDetail lod = blended_gaussian(
        positions[index], footprint_width(footprints.empty() ? nullptr : &footprints[index]), seed,
        g);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    inverse_transform(g, lod, &out.at(x, y, 0));
  }
}

void TilingModel::evaluate_periodic(std::span<const Vec2d> positions,
                                    std::span<const Footprint> footprints, std::uint32_t seed,
                                    ImageView<float> out, Vec2d period) const noexcept {
  const PeriodicLattice periodic(period, edge_);
  for (std::size_t index = 0; index < positions.size(); ++index) {
    float g[kMaxChannels];
    const LevelOfDetail lod = blended_gaussian(
        reduce_position(positions[index], period),
        footprint_width(footprints.empty() ? nullptr : &footprints[index]), seed, g, &periodic);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    inverse_transform(g, lod, &out.at(x, y, 0));
  }
}

SimdTiling TilingModel::simd_tiling() const noexcept {
  SimdTiling m;
  m.channels = data_.channels;
  m.width = data_.width;
  m.height = data_.height;
  m.edge = edge_;
  m.linear = data_.blend == Blend::linear;
  m.inverse = data_.blend == Blend::histogram;
  m.blend_mean = data_.blend_mean.data();
  m.pyramid = pyramid_.data();
  m.level_count = level_count();
  for (int l = 0; l < m.level_count; ++l) {
    const MipLevel mip = level(l);
    const auto i = static_cast<std::size_t>(l);
    m.level_width[i] = mip.width;
    m.level_height[i] = mip.height;
    m.level_first[i] = static_cast<std::int32_t>(levels_[i].first);
    m.texels_per_pixel_x[i] = mip.texels_per_pixel_x;
    m.texels_per_pixel_y[i] = mip.texels_per_pixel_y;
  }
  m.groups = layout_.groups;
  m.lut_size = data_.lut_size;
  m.table_size = data_.table_size;
  m.luts = level_luts_.data();
  m.lut_floats = static_cast<std::int32_t>(lut_floats_);
  m.tables = level_tables_.data();
  m.table_floats = static_cast<std::int32_t>(table_floats_);
  m.colour_basis = data_.colour_basis.data();
  m.colour_mean = data_.colour_mean.data();
  return m;
}

void TilingModel::evaluate_simd(std::span<const Vec2d> positions,
                                std::span<const Footprint> footprints, std::uint32_t seed,
                                ImageView<float> out) const noexcept {
  const SimdTiling m = simd_tiling();
  std::int32_t levels[kSimdBatch];
  float blends[kSimdBatch];
  // A render's footprints repeat: the level of detail of the last one is kept.
  Footprint last{};
  LevelOfDetail last_lod = level_of_detail(&last);
  for (std::size_t first = 0; first < positions.size(); first += kSimdBatch) {
    const std::size_t size = std::min(kSimdBatch, positions.size() - first);
    for (std::size_t i = 0; i < size; ++i) {
      LevelOfDetail lod;
      if (!footprints.empty()) {
        const Footprint& f = footprints[first + i];
        if (f.dpdx.x != last.dpdx.x || f.dpdx.y != last.dpdx.y || f.dpdy.x != last.dpdy.x ||
            f.dpdy.y != last.dpdy.y) {
          last = f;
          last_lod = level_of_detail(&f);
        }
        lod = last_lod;
      }
      levels[i] = lod.level;
      blends[i] = lod.blend;
    }
    evaluate_lanes(m, positions.subspan(first, size), levels, blends, seed, out, first);
  }
}

void TilingModel::evaluate_triplanar(std::span<const SurfacePoint> points, double sharpness,
                                     std::uint32_t seed, ImageView<float> out) const noexcept {
  const int channels = data_.channels;
  const std::vector<float>& mean = data_.blend_mean;
  for (std::size_t index = 0; index < points.size(); ++index) {
    const SurfacePoint& p = points[index];
    const std::array<double, 3> weights = triplanar_weights(p.normal, sharpness);
    double acc[kMaxChannels] = {};
    double weight_squares = 0.0;
    double lod = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double w = weights[static_cast<std::size_t>(k)];
      if (w == 0.0) continue;
      // Plane k's footprint: the 3-D footprint projected on the plane, as a 2-D render's.
      const Footprint footprint{on_plane(p.dpdx, k), on_plane(p.dpdy, k)};
      float g[kMaxChannels];
      const LevelOfDetail plane_lod = blended_gaussian(
          on_plane(p.position, k), footprint_width(&footprint), triplanar_seed(k, seed), g);
      for (int c = 0; c < channels; ++c) acc[c] += w * (g[c] - mean[c]);
      weight_squares += w * w;
      lod += w * w * (plane_lod.level + static_cast<double>(plane_lod.blend));
    }
    // The same operator as the lattice blend (eq. 13), with the normal's weights.
    const double inverse_norm =
        data_.blend == Blend::linear ? 1.0 : 1.0 / std::sqrt(weight_squares);
    float g[kMaxChannels];
    for (int c = 0; c < channels; ++c) g[c] = static_cast<float>(acc[c] * inverse_norm + mean[c]);
    // One T^-1 look-up, prefiltered for the w^2-weighted mean of the planes' levels: the blend's
    // variance is the w^2-weighted mean of the planes' (eq. 13), so is, to first order, the
    // residual variance r^2 the prefiltered table assumes (prefilter_kernel, pyramid.cpp). It is
    // continuous where the dominant plane changes (the dominant plane's level jumps there).
    // Measured (metal_grey_256, normal (1, 0.5, 0), footprint 8 x 2 pixels, mean against a 12 x 12
    // supersampled reference): bias -0.0003 (w^2), -0.0003 (dominant plane), -0.0010 (w),
    // -0.0144 (finest level: a coarse plane's values read through too sharp a table).
    const LevelOfDetail look_up = split_level(lod / weight_squares);
    const auto x = static_cast<int>(index % static_cast<std::size_t>(out.width));
    const auto y = static_cast<int>(index / static_cast<std::size_t>(out.width));
    inverse_transform(g, look_up, &out.at(x, y, 0));
  }
}

}  // namespace stochtex::tiling
