// Coverage-guided fuzzing (libFuzzer) of the .stx reader and of evaluation after it
// (docs/design.md §7, §9): every input must be refused with stochtex::Error(format), or load as a
// model whose renders (point samples and filtered, near and far from the origin) are finite.
// Bugs hide in evaluating a model that validated, so both halves are fuzzed together. An input
// whose first byte is odd gets its checksum recomputed first, so that mutations of the header and
// of the array values reach validation instead of stopping at the checksum. Seeds:
// tests/fuzz/corpus/model (a small model of every method). Built by scripts/sanitize.sh.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "model/model_file.hpp"
#include "stochtex/error.hpp"
#include "stochtex/model.hpp"
#include "stochtex/render.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size > 8 && (data[0] & 1u) != 0) {
    const std::uint64_t hash =
        stochtex::model_checksum(std::span<const std::uint8_t>(bytes).first(size - 8));
    for (std::size_t i = 0; i < 8; ++i)
      bytes[size - 8 + i] = static_cast<std::uint8_t>(hash >> (8 * i));
  }
  try {
    const stochtex::Model model = stochtex::deserialize_model(bytes, "fuzz.stx");
    stochtex::ImageF out(4, 4, model.channels());
    stochtex::RenderOptions options;
    options.threads = 1;
    for (const double scale : {1.0, 8.0}) {
      for (const stochtex::Vec2d origin : {stochtex::Vec2d{0.0, 0.0}, {-1e6, 3e5}}) {
        stochtex::render(model, stochtex::Grid{origin, scale, 4, 4}, 7, out.view(), options);
        for (const float value : out.pixels())
          if (!std::isfinite(value)) std::abort();
      }
    }
  } catch (const stochtex::Error& error) {
    if (error.code() != stochtex::ErrorCode::format) std::abort();
  }
  return 0;
}
