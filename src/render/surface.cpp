#include "stochtex/surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/triplanar.hpp"
#include "model/model_data.hpp"
#include "render/mesh_geometry.hpp"
#include "render/surface_arguments.hpp"
#include "stochtex/render.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

// A method with surface noise (texton paper section 6) provides
//   void evaluate_surface(std::span<const SurfacePoint>, double surface_mni, std::uint32_t seed,
//                         ImageView<float> out) const noexcept;
template <typename MethodModel>
concept HasSurfaceNoise = requires(const MethodModel& m, std::span<const SurfacePoint> points,
                                   std::uint32_t seed, ImageView<float> out) {
  m.evaluate_surface(points, 60.0, seed, out);
};

// A method with its own triplanar operator (tiling, figure 16) provides
//   void evaluate_triplanar(std::span<const SurfacePoint>, double sharpness, std::uint32_t seed,
//                           ImageView<float> out) const noexcept;
template <typename MethodModel>
concept HasTriplanar = requires(const MethodModel& m, std::span<const SurfacePoint> points,
                                std::uint32_t seed, ImageView<float> out) {
  m.evaluate_triplanar(points, 4.0, seed, out);
};

struct MappingRow {
  SurfaceMapping mapping;
  std::string_view name;
};
constexpr std::array<MappingRow, 3> kMappings = {
    {{SurfaceMapping::surface, "surface"},
     {SurfaceMapping::triplanar, "triplanar"},
     {SurfaceMapping::triplanar_linear, "triplanar-linear"}}};

bool in_range(const Vec3d& v) {
  return std::abs(v.x) <= kPositionLimit && std::abs(v.y) <= kPositionLimit &&
         std::abs(v.z) <= kPositionLimit;
}

// Finite, within the precise range, and a frame orthonormal within 1e-3 (also false for NaN).
bool valid_point(const SurfacePoint& p) {
  constexpr double kTolerance = 1e-3;
  return in_range(p.position) && in_range(p.dpdx) && in_range(p.dpdy) &&
         std::abs(dot(p.normal, p.normal) - 1.0) <= kTolerance &&
         std::abs(dot(p.tangent, p.tangent) - 1.0) <= kTolerance &&
         std::abs(dot(p.normal, p.tangent)) <= kTolerance;
}

// Linear triplanar mapping for any method: each plane its own seed stream (seed + k), point
// batches of kBatch through the method's evaluate(), no allocation.
template <typename MethodModel>
void evaluate_triplanar_linear(const MethodModel& m, const ModelColour& colour,
                               std::span<const SurfacePoint> points, double sharpness,
                               std::uint32_t seed, ImageView<float> out) {
  constexpr int kBatch = 64;
  const int channels = out.channels;
  for (std::size_t first = 0; first < points.size(); first += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, points.size() - first));
    std::array<float, kBatch * kMaxChannels> sum{};
    std::array<std::array<double, 3>, kBatch> weights;
    for (int i = 0; i < count; ++i)
      weights[static_cast<std::size_t>(i)] =
          triplanar_weights(points[first + static_cast<std::size_t>(i)].normal, sharpness);
    for (int k = 0; k < 3; ++k) {
      // A plane of no weight at every point adds nothing (normals along an axis).
      if (std::all_of(weights.begin(), weights.begin() + count,
                      [&](const std::array<double, 3>& w) {
                        return w[static_cast<std::size_t>(k)] == 0.0;
                      }))
        continue;
      std::array<Vec2d, kBatch> positions;
      std::array<Footprint, kBatch> footprints;
      for (int i = 0; i < count; ++i) {
        const SurfacePoint& p = points[first + static_cast<std::size_t>(i)];
        positions[static_cast<std::size_t>(i)] = on_plane(p.position, k);
        footprints[static_cast<std::size_t>(i)] = {on_plane(p.dpdx, k), on_plane(p.dpdy, k)};
      }
      std::array<float, kBatch * kMaxChannels> values;
      m.evaluate(std::span(positions.data(), static_cast<std::size_t>(count)),
                 std::span(footprints.data(), static_cast<std::size_t>(count)),
                 seed + static_cast<std::uint32_t>(k),
                 ImageView<float>{values.data(), count, 1, channels, count * channels});
      // Each plane's values as linear light, then blended.
      decode_expectation(colour, static_cast<std::size_t>(count),
                         std::span(footprints.data(), static_cast<std::size_t>(count)),
                         ImageView<float>{values.data(), count, 1, channels, count * channels});
      for (int i = 0; i < count; ++i) {
        const double w = weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
        for (int c = 0; c < channels; ++c)
          sum[static_cast<std::size_t>(i * channels + c)] +=
              static_cast<float>(w) * values[static_cast<std::size_t>(i * channels + c)];
      }
    }
    for (int i = 0; i < count; ++i) {
      const auto index = static_cast<int>(first) + i;
      for (int c = 0; c < channels; ++c)
        out.at(index % out.width, index / out.width, c) =
            sum[static_cast<std::size_t>(i * channels + c)];
    }
  }
}

// decode_expectation of surface points: each point's footprint width is the square root of the
// area its 3-D footprint covers, |dpdx x dpdy|^(1/2).
void decode_surface(const ModelColour& colour, std::span<const SurfacePoint> points,
                    ImageView<float> out) {
  decode_expectation_with(
      colour, points.size(),
      [&](std::size_t i) {
        const Vec3d& a = points[i].dpdx;
        const Vec3d& b = points[i].dpdy;
        return std::sqrt(
            std::hypot(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x));
      },
      out);
}

// "[low, high]" for whole-number bounds.
std::string range_text(double low, double high) {
  return "[" + std::to_string(static_cast<int>(low)) + ", " +
         std::to_string(static_cast<int>(high)) + "]";
}

}  // namespace

std::string_view mapping_name(SurfaceMapping mapping) {
  for (const MappingRow& row : kMappings)
    if (row.mapping == mapping) return row.name;
  throw std::invalid_argument("mapping_name: not a SurfaceMapping value");
}

SurfaceMapping mapping_from_name(std::string_view name) {
  std::string known;
  for (const MappingRow& row : kMappings) {
    if (row.name == name) return row.mapping;
    known += (known.empty() ? "" : ", ") + std::string(row.name);
  }
  throw std::invalid_argument("unknown mapping '" + std::string(name) + "'; the mappings are " +
                              known);
}

bool supports_mapping(const Model& model, SurfaceMapping mapping) {
  if (model.empty()) return false;
  return std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        switch (mapping) {
          case SurfaceMapping::surface:
            return HasSurfaceNoise<M>;
          case SurfaceMapping::triplanar:
            return HasTriplanar<M>;
          case SurfaceMapping::triplanar_linear:
            return true;
        }
        return false;
      },
      model.data().model);
}

void check_surface_arguments(const Model& model, std::span<const SurfacePoint> points,
                             const SurfaceOptions& options, ImageView<float> out) {
  if (model.empty()) throw std::invalid_argument("evaluate_surface: the model is empty");
  if (!supports_mapping(model, options.mapping))
    throw std::invalid_argument("evaluate_surface: " + std::string(model.method()) +
                                " models have no " + std::string(mapping_name(options.mapping)) +
                                " mapping");
  if (!(options.surface_mni >= kMinSurfaceMni && options.surface_mni <= kMaxSurfaceMni))
    throw std::invalid_argument("evaluate_surface: surface_mni must be within " +
                                range_text(kMinSurfaceMni, kMaxSurfaceMni));
  if (!(options.triplanar_sharpness >= kMinTriplanarSharpness &&
        options.triplanar_sharpness <= kMaxTriplanarSharpness))
    throw std::invalid_argument("evaluate_surface: triplanar_sharpness must be within " +
                                range_text(kMinTriplanarSharpness, kMaxTriplanarSharpness));
  if (out.channels != model.channels() ||
      static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) < points.size())
    throw std::invalid_argument("evaluate_surface: the output view must hold one pixel of " +
                                std::to_string(model.channels()) + " channels per point");
  if (!std::all_of(points.begin(), points.end(), valid_point))
    throw std::invalid_argument(
        "evaluate_surface: a point is not finite, beyond +-2^32 exemplar pixels, or its normal "
        "and tangent are not orthonormal");
}

void evaluate_surface(const Model& model, std::span<const SurfacePoint> points,
                      const SurfaceOptions& options, std::uint32_t seed, ImageView<float> out) {
  check_surface_arguments(model, points, options, out);
  std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        const ModelColour& colour = model.data().colour;
        if (options.mapping == SurfaceMapping::triplanar_linear)
          evaluate_triplanar_linear(m, colour, points, options.triplanar_sharpness, seed, out);
        if constexpr (HasSurfaceNoise<M>)
          if (options.mapping == SurfaceMapping::surface) {
            m.evaluate_surface(points, options.surface_mni, seed, out);
            decode_surface(colour, points, out);
          }
        if constexpr (HasTriplanar<M>)
          if (options.mapping == SurfaceMapping::triplanar) {
            m.evaluate_triplanar(points, options.triplanar_sharpness, seed, out);
            decode_surface(colour, points, out);
          }
      },
      model.data().model);
}

}  // namespace stochtex
