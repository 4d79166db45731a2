#pragma once
// The .stx model file (docs/design.md §7), byte layout, all integers little-endian:
//   magic "STOCHTEX" (8 bytes) | format version u32 | header length u32 | header JSON (UTF-8)
//   | array data: each declared array's float32 values, in header order | FNV-1a 64 checksum u64
//     of every preceding byte.
// The header JSON is {"method": str, "params": {name: number}, "scalars": {name: number},
//   "arrays": [{"name": str, "shape": [int, ...]}, ...]}, and for a material (format version 2
//   only) "maps": [{"name": str, "kind": str, "channels": int[, "from": str, "scale": number]},
//   ...]
//   ("from": a normal map derived from that height map, channels 0), and (version 3 only) the
//   colour space of a model of one image, "colour_space": "linear" | "srgb", or of each map, the
//   same key in its entry. A model of one image of data is written as version 1, byte for byte
//   what stochtex wrote before materials; version 2 holds a material of data; version 3 a model
//   with a colour space, so that an older stochtex refuses it ("upgrade") rather than render it
//   as data. A srgb model of the Gaussian methods holds the array "colour_removed_deviation"
//   (model/model_colour.hpp).
// Reading validates magic, version, sizes (against the byte count actually present and against
// hard limits) and the checksum before allocating any array; every failure throws
// stochtex::Error(ErrorCode::format) with one sentence naming `source_name` and the problem.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/memory_budget.hpp"
#include "model/model_record.hpp"

namespace stochtex {

// The versions (docs/design.md §7). Every file is written in the newest; the older ones load.
inline constexpr std::uint32_t kModelFormatVersion = 4;             // the newest, XXH3 checksum
inline constexpr std::uint32_t kColourModelFormatVersion = 3;       // colour spaces
inline constexpr std::uint32_t kMaterialModelFormatVersion = 2;     // a material
inline constexpr std::uint32_t kSingleImageModelFormatVersion = 1;  // a model of one image
inline constexpr std::uint32_t kMaxModelHeaderBytes = 1u << 20;
// Loading a model peaks at about five times its file size (measured: the file's bytes, the
// decoded record, the method's model and what it derives), 20 bytes a value: the memory budget
// bounds how many values a file may hold. write_model_record refuses to write more, so that
// analysis never writes a model that loading would refuse.
inline constexpr std::uint64_t kMaxModelArrayValues = kMemoryBudgetBytes / 20;

// Whether the record has a colour space other than data (format version 3 or later).
bool has_colour(const ModelRecord& record);
// Throws stochtex::Error(ErrorCode::invalid_input) for a record of more than kMaxModelArrayValues.
std::vector<std::uint8_t> write_model_record(const ModelRecord& record);
// The checksum stored in the last 8 bytes of a model file, over all bytes before it, as the
// version the bytes declare has it: XXH3-64 from version 4 (a 512² colour model's 3 MB in 0.2
// ms), FNV-1a 64 before (3.2 ms: one multiplication after another, byte by byte).
std::uint64_t model_checksum(std::span<const std::uint8_t> bytes_before_checksum);
ModelRecord read_model_record(std::span<const std::uint8_t> bytes, const std::string& source_name);

}  // namespace stochtex
