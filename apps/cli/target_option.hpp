#pragma once
// `stochtex analyze --method lrp --target KIND:key=value,...`: a continuous target spectrum in
// place of an exemplar (Gilet et al. 2014, section 6.1 and figure 10), parsed into the library's
// lrp::ring_spectrum / lrp::gaussian_spectrum.
//
//   ring:radius=R,width=W             a ring of radius R, Gaussian profile of deviation W
//   gaussian:cx=X,cy=Y,along=A,across=B  an anisotropic Gaussian pair at +-(X, Y), deviation A
//                                     along (X, Y) and B across (alias: anisotropic)
//   common, optional: variance=V (0.01), mean=M (0.5), size=N (128, the spectrum's grid)
// Frequencies are in cycles per pixel. Bad text throws std::invalid_argument with one sentence.

#include <cstdint>
#include <string>
#include <string_view>

#include "stochtex/stochtex.hpp"

namespace stochtex::cli {

// The text after `--target`, for the help line.
inline constexpr std::string_view kTargetHelp =
    "continuous target spectrum instead of INPUT (lrp only): ring:radius=R,width=W or "
    "gaussian:cx=X,cy=Y,along=A,across=B, optional variance=V,mean=M,size=N (cycles per pixel)";

// The lrp model of a target; `method` must be lrp.
Model target_model(const std::string& text, std::string_view method, const ParamValues& params,
                   std::uint32_t seed);

}  // namespace stochtex::cli
