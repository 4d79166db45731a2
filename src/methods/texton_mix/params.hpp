#pragma once
// Texton noise mixing parameters (Galerne, Leclaire, Moisan, "Texton Noise", CGF 2017, DOI
// 10.1111/cgf.13073, section 7), described once (methods/param_record.hpp): texton noise's own
// record (the textons are computed by its Algorithm 1), the number R of textons, and the mixing
// field. The record feeds `stochtex mix`, the model file and docs/methods/texton_mix.md.

#include <array>
#include <cstddef>

#include "methods/param_record.hpp"
#include "methods/texton/params.hpp"

namespace stochtex::texton_mix {

struct Params {
  texton::Params texton;
  int steps = 21;
  double ramp_start = 0;
  double ramp_end = 1024;
  double direction_x = 1;
  double direction_y = 0;
  double mask_scale = 1;

  bool operator==(const Params&) const = default;
};

namespace detail {
// Texton noise's field I, reading and writing Params::texton.
template <std::size_t I>
constexpr ParamField<Params> texton_field() {
  return {texton::kFields[I].info,
          [](const Params& params) { return texton::kFields[I].get(params.texton); },
          [](Params& params, double value) { texton::kFields[I].set(params.texton, value); }};
}
}  // namespace detail

// The mixing field's coordinates are model-space positions (exemplar pixels); the bound keeps
// them, and positions computed from them, exact enough in double.
inline constexpr double kMaxCoordinate = 1e9;

inline constexpr std::array<ParamField<Params>, 10> kFields = {{
    detail::texton_field<0>(),
    detail::texton_field<1>(),
    detail::texton_field<2>(),
    detail::texton_field<3>(),
    number_field<&Params::steps>("steps", 2, 256,
                                 "number R of textons, for rho = k / (R - 1), k = 0 .. R - 1 "
                                 "(section 7; the paper uses 21)"),
    number_field<&Params::ramp_start>(
        "ramp_start", -kMaxCoordinate, kMaxCoordinate,
        "ramp field: rho = 0 (exemplar A) at and before this position along the direction"),
    number_field<&Params::ramp_end>(
        "ramp_end", -kMaxCoordinate, kMaxCoordinate,
        "ramp field: rho = 1 (exemplar B) at and beyond this position along the direction; must "
        "differ from ramp_start"),
    number_field<&Params::direction_x>("direction_x", -1e6, 1e6,
                                       "ramp field: x component of the ramp's direction "
                                       "(normalised; not both components zero)"),
    number_field<&Params::direction_y>("direction_y", -1e6, 1e6,
                                       "ramp field: y component of the ramp's direction"),
    number_field<&Params::mask_scale>(
        "mask_scale", 1.0 / 1024.0, 1024,
        "mask field: model-space pixels per mask pixel; the mask covers [0, scale W) x [0, scale "
        "H) from the origin, bilinear, clamped to its edge pixels beyond"),
}};

inline constexpr auto kParams = param_infos(kFields);

}  // namespace stochtex::texton_mix
