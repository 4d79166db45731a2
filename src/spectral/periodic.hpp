#pragma once
// Periodic + smooth decomposition (L. Moisan, "Periodic plus smooth image decomposition", JMIV
// 2011): u = p + s where p is periodic-friendly (no border discontinuities, so its spectrum has no
// cross artefact) and s is smooth. Texton noise and ADSN analyse p, never u.

#include "stochtex/image.hpp"

namespace stochtex {

// Returns the periodic component of every channel. mean(p) == mean(u) (s has zero mean).
ImageF periodic_component(ImageView<const float> image);

}  // namespace stochtex
