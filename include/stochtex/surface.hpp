#pragma once
// Evaluation on surfaces, with or without texture coordinates (docs/surface.md): the papers'
// applications beyond the plane. A batch of surface points, each with its local frame and
// footprint, evaluated by one mapping:
//  - surface: surface noise (texton noise, section 6 of "Texton Noise", Galerne, Leclaire and
//    Moisan, CGF 2017, doi:10.1111/cgf.13073; section 9.1 of "Gabor Noise by Example", Galerne,
//    Lagae, Lefebvre and Drettakis, ACM TOG 2012, doi:10.1145/2185520.2185569): a 3-D impulse
//    process projected on the tangent plane, no parameterisation needed;
//  - triplanar: histogram-preserving triplanar blending of tiling models (figure 16 of
//    "High-Performance By-Example Noise using a Histogram-Preserving Blending Operator", Heitz and
//    Neyret, HPG 2018, doi:10.1145/3233304);
//  - triplanar_linear: the three planar projections blended linearly, any method (the baseline).
// Same contract as evaluate() (render.hpp): a pure function of (model, points, options, seed),
// bit-identical whatever the batch split or thread count; arguments are checked before any work.

#include <cstdint>
#include <span>
#include <string_view>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex {

struct Vec3d {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// A point of a surface in model space (one unit = one exemplar pixel; scale mesh coordinates
// before calling) with its local orthonormal frame (u1, u2, u3) = (tangent, normal x tangent,
// normal): `normal` and `tangent` unit length and orthogonal. dpdx and dpdy are the derivatives of
// the position along the output's x and y (the screen-space footprint); zero = a point sample.
struct SurfacePoint {
  Vec3d position;
  Vec3d normal;
  Vec3d tangent;
  Vec3d dpdx;
  Vec3d dpdy;
};

enum class SurfaceMapping { surface, triplanar, triplanar_linear };

// The mapping's name as the CLI writes it ("surface", "triplanar", "triplanar-linear"), and back;
// mapping_from_name throws std::invalid_argument naming the known mappings.
std::string_view mapping_name(SurfaceMapping mapping);
SurfaceMapping mapping_from_name(std::string_view name);

// The accepted ranges of SurfaceOptions' numbers.
inline constexpr double kMinSurfaceMni = 1.0;
inline constexpr double kMaxSurfaceMni = 1000.0;
inline constexpr double kMinTriplanarSharpness = 1.0;
inline constexpr double kMaxTriplanarSharpness = 64.0;

struct SurfaceOptions {
  SurfaceMapping mapping = SurfaceMapping::surface;
  // Surface noise: the mean number of impulses per texton-sized cube, lambda r^3 (texton paper
  // section 6; 60 as in its figure 4).
  double surface_mni = 60.0;
  // Triplanar: the weight of axis k is |n_k|^sharpness, normalised to sum 1.
  double triplanar_sharpness = 4.0;
};

// Whether evaluate_surface() accepts this model with this mapping.
bool supports_mapping(const Model& model, SurfaceMapping mapping);

// Evaluates the model at each surface point; `out` holds points.size() pixels of model.channels()
// channels in row-major order (as evaluate()'s). Throws std::invalid_argument, before any work,
// when the model does not support the mapping, an option is out of range, or a point is not
// finite, beyond kPositionLimit, or its frame is not orthonormal (within 1e-3).
void evaluate_surface(const Model& model, std::span<const SurfacePoint> points,
                      const SurfaceOptions& options, std::uint32_t seed, ImageView<float> out);

}  // namespace stochtex
