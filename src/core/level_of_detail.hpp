#pragma once
// The level-of-detail bias of the texton and tiling pyramids, shared with their GLSL twins.

namespace stochtex {

// A texel of level l reconstructs box(2^l) * tent(2^l) (a box-prefiltered level read with
// bilinear interpolation), whose variance per axis is 4^l / 4; an ideal box filter of width w
// has variance w^2 / 12. Equal variances give 2^l = w / sqrt(3): the level of detail is
// log2(w) - log2(3) / 2, not log2(w), or the filtered noise is too blurred (measured in
// docs/methods/texton.md).
inline constexpr double kLodBias = 0.79248125036057809;  // log2(3) / 2

}  // namespace stochtex
