#pragma once
// How the images stochtex writes are compressed: the one place that decides it, for every writer
// (write_image and encode_image, so render, synth, gaussian, the studio, exports and reports, and
// the tiled OpenEXR files). Chosen by measurement of 2048x2048 renders and of pictures
// (docs/performance.md, "Time to a file (issue 39)"). These settings change a file's bytes, never
// its pixels, and depend on nothing but the image: the same image gives the same bytes.

#include <ImfCompression.h>
#include <png.h>
#include <zlib.h>

namespace stochtex {

// PNG: every row with the Average filter, deflated with zlib's run-length strategy (matches of
// distance 1 only). A render's noise leaves deflate little to match but the filtered values'
// entropy: on 2048x2048 colour renders libpng's defaults (its filter trials, level 6's match
// search) gave the same size within 0.1% in 3.4 to 4 times the time; runs keep the flat parts of
// pictures small, which Huffman coding alone does not.
inline constexpr int kPngFilters = PNG_FILTER_AVG;
inline constexpr int kPngZlibStrategy = Z_RLE;

// OpenEXR float pixels, scanline or tiled: uncompressed. ZIP saved 2% of a render's bytes for
// twenty times the time of writing them.
inline constexpr Imf::Compression kExrFloatCompression = Imf::NO_COMPRESSION;
// OpenEXR half pixels (tiled files, --half): ZIP saves a third for half again the time
// (docs/large-renders.md).
inline constexpr Imf::Compression kExrHalfCompression = Imf::ZIP_COMPRESSION;

}  // namespace stochtex
