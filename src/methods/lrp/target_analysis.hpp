#pragma once
// lrp's continuous target spectrum in place of an exemplar (Gilet et al. 2014, section 6.1 and
// figure 10), the registry row's target capability (methods/capabilities.hpp): the text of
// `stochtex analyze --method lrp --target KIND:key=value,...` parsed into ring_spectrum or
// gaussian_spectrum (analysis.hpp).
//
//   ring:radius=R,width=W             a ring of radius R, Gaussian profile of deviation W
//   gaussian:cx=X,cy=Y,along=A,across=B  an anisotropic Gaussian pair at +-(X, Y), deviation A
//                                     along (X, Y) and B across (alias: anisotropic)
//   common, optional: variance=V (0.01), mean=M (0.5), size=N (128, the spectrum's grid)
// Frequencies are in cycles per pixel.

#include <cstdint>
#include <string>

#include "methods/capabilities.hpp"
#include "stochtex/model.hpp"

namespace stochtex::lrp {

// The lrp model of a target; bad text throws std::invalid_argument with one sentence that starts
// "the target spectrum 'TEXT': ".
Model target_model(const std::string& text, const ParamValues& params, std::uint32_t seed);

inline constexpr TargetCapability kTarget{
    "ring:radius=R,width=W or gaussian:cx=X,cy=Y,along=A,across=B, optional "
    "variance=V,mean=M,size=N (cycles per pixel)",
    &target_model};

}  // namespace stochtex::lrp
