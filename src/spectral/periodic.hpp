#pragma once
// Periodic + smooth decomposition (L. Moisan, "Periodic plus smooth image decomposition", JMIV
// 2011): u = p + s where p is periodic-friendly (no border discontinuities, so its spectrum has no
// cross artefact) and s is smooth. Texton noise and ADSN analyse p, never u.

#include "stochtex/image.hpp"

namespace stochtex {

// Returns the periodic component of every channel. mean(p) == mean(u) (s has zero mean).
ImageF periodic_component(ImageView<const float> image);

// The periodic component with each channel's histogram put back exactly: the k-th smallest value
// of a channel of p gets the k-th smallest value of the same channel of u (ties in the order of
// the pixels). The image made tileable without changing its values: a photo cut from a larger
// scene repeats without the step at its border, which p spreads into a smooth ramp (Moisan's
// s), then the rank order of p keeps the texture and u's values keep the histogram.
ImageF periodic_keeping_histogram(ImageView<const float> image);

}  // namespace stochtex
