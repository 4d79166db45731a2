// Deterministic mutation fuzzing of the .stx reader (docs/design.md §9): thousands of seeded
// mutations of valid model files must each load or be rejected with stochtex::Error, never crash,
// hang or allocate without bound. Half the mutants get their checksum recomputed so that they
// reach the header and array validation instead of stopping at the checksum.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "model/model_file.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex {
namespace {

std::vector<std::uint8_t> valid_model(int channels, int support) {
  std::mt19937 engine(static_cast<unsigned>(channels * 31 + support));
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF exemplar(24, 24, channels);
  for (float& value : exemplar.pixels()) value = uniform(engine);
  return serialize_model(
      analyze("texton", exemplar.view(), {{"support", support}, {"iterations", 3}}, 0));
}

void fix_checksum(std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < 8) return;
  const std::uint64_t hash =
      model_checksum(std::span<const std::uint8_t>(bytes).first(bytes.size() - 8));
  for (int i = 0; i < 8; ++i)
    bytes[bytes.size() - 8 + static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>(hash >> (8 * i));
}

// Replaces a run of decimal digits in the header with another number (sizes, shapes, versions).
void edit_number(std::vector<std::uint8_t>& bytes, std::mt19937& engine) {
  std::vector<std::size_t> digits;
  for (std::size_t i = 16; i < bytes.size(); ++i)
    if (bytes[i] >= '0' && bytes[i] <= '9') digits.push_back(i);
  if (digits.empty()) return;
  const std::size_t at = digits[engine() % digits.size()];
  static const std::vector<std::string> replacements = {"0",     "-1",        "99999999999", "4096",
                                                        "1e308", "268435456", "3.5",         "nan"};
  const std::string& text = replacements[engine() % replacements.size()];
  bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at));
  bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), text.begin(), text.end());
  // Keep the declared header length consistent with the edit so the header is re-parsed.
  std::uint32_t length = 0;
  for (int i = 0; i < 4; ++i) length |= static_cast<std::uint32_t>(bytes[12 + i]) << (8 * i);
  length = static_cast<std::uint32_t>(length + text.size() - 1);
  for (int i = 0; i < 4; ++i)
    bytes[12 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(length >> (8 * i));
}

// Overwrites one float of the array data (after the header, before the checksum) with a huge
// finite value or one at the edge of the model value range: either the file is refused or its
// model renders finite values (issue 19: values near 1e38 loaded and rendered NaN or Inf).
void write_huge_value(std::vector<std::uint8_t>& bytes, std::mt19937& engine) {
  if (bytes.size() < 16) return;
  std::uint32_t header = 0;
  for (int i = 0; i < 4; ++i) header |= static_cast<std::uint32_t>(bytes[12 + i]) << (8 * i);
  const std::size_t first = 16 + static_cast<std::size_t>(header);
  if (bytes.size() < first + 4 + 8) return;
  const std::size_t count = (bytes.size() - 8 - first) / 4;
  static const std::vector<float> values = {1e38f, -3e38f, 1e20f, -1e13f, 1e12f, -1e12f, 9e11f};
  const float value = values[engine() % values.size()];
  std::uint32_t word = 0;
  std::memcpy(&word, &value, 4);
  const std::size_t at = first + 4 * (engine() % count);
  for (int i = 0; i < 4; ++i)
    bytes[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(word >> (8 * i));
}

// Renders a few points of the model with and without footprints at several scales; every value
// must be finite.
void expect_finite_renders(const Model& model, int mutant) {
  const std::vector<Vec2d> points = {{0.5, 0.5}, {-3.25, 7.5}, {1e5, -2e5}};
  for (const double scale : {0.0, 1.0, 5.0, 300.0}) {
    const std::vector<Footprint> footprints(points.size(), Footprint{{scale, 0.0}, {0.0, scale}});
    ImageF out(static_cast<int>(points.size()), 1, model.channels());
    evaluate(model, points, scale == 0.0 ? std::span<const Footprint>{} : footprints, 1,
             out.view());
    for (const float value : out.pixels())
      ASSERT_TRUE(std::isfinite(value)) << "mutant " << mutant << " at scale " << scale;
  }
}

// Mutates the seeds `mutants` times (bit flips, bytes, truncations, insertions, header numbers,
// huge array values); every mutant must load and evaluate to finite values, or be refused with
// Error(format).
void fuzz_models(const std::vector<std::vector<std::uint8_t>>& seeds, int mutants,
                 std::uint32_t engine_seed) {
  std::mt19937 engine(engine_seed);
  int accepted = 0;
  int rejected = 0;
  for (int n = 0; n < mutants; ++n) {
    std::vector<std::uint8_t> bytes = seeds[static_cast<std::size_t>(n) % seeds.size()];
    const int edits = 1 + static_cast<int>(engine() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const std::size_t at = engine() % bytes.size();
      switch (engine() % 6) {
        case 0:
          bytes[at] ^= static_cast<std::uint8_t>(1u << (engine() % 8));
          break;
        case 1:
          bytes[at] = static_cast<std::uint8_t>(engine());
          break;
        case 2:
          bytes.resize(at);
          break;
        case 3:
          bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                       static_cast<std::uint8_t>(engine()));
          break;
        case 4:
          edit_number(bytes, engine);
          break;
        default:
          write_huge_value(bytes, engine);
          break;
      }
    }
    if (n % 2 == 0) fix_checksum(bytes);
    try {
      const Model model = deserialize_model(bytes, "fuzz.stx");
      // Whatever loads must evaluate to finite values.
      expect_finite_renders(model, n);
      if (testing::Test::HasFatalFailure()) return;
      ++accepted;
    } catch (const Error& error) {
      ASSERT_EQ(error.code(), ErrorCode::format) << "mutant " << n << ": " << error.what();
      ++rejected;
    }
  }
  EXPECT_EQ(accepted + rejected, mutants);
  EXPECT_GT(rejected, mutants / 2);
  EXPECT_GT(accepted, 0);  // some mutants (e.g. changed array values) are valid models
}

TEST(ModelFuzz, MutantsLoadOrFailCleanly) {
  fuzz_models({valid_model(1, 6), valid_model(3, 8), valid_model(4, 5)}, 6000, 20261122);
}

// Every method of the registry with its default parameters, on small random grey and colour
// exemplars: a new method's model file is fuzzed without a line here.
TEST(ModelFuzz, EveryMethodMutantsLoadOrFailCleanly) {
  std::uint32_t engine_seed = 20261124;
  for (const MethodInfo& method : methods()) {
    std::vector<std::vector<std::uint8_t>> seeds;
    for (const int channels : {1, 3}) {
      std::mt19937 engine(static_cast<unsigned>(channels * 7 + 1));
      std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
      ImageF exemplar(16, 16, channels);
      for (float& value : exemplar.pixels()) value = uniform(engine);
      seeds.push_back(serialize_model(analyze(method.name, exemplar.view(), {}, 0)));
    }
    SCOPED_TRACE(std::string(method.name));
    fuzz_models(seeds, 2000, engine_seed++);
  }
}

// A material's model (a version-2 file with its list of maps) of every method: a colour map and
// a scalar map of random values.
TEST(ModelFuzz, MaterialMutantsLoadOrFailCleanly) {
  std::mt19937 engine(20261125);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF albedo(16, 16, 3), roughness(16, 16, 1);
  for (ImageF* image : {&albedo, &roughness})
    for (float& value : image->pixels()) value = uniform(engine);
  const std::vector<MaterialMap> maps{{"albedo", {}, albedo.view(), "a"},
                                      {"roughness", {}, roughness.view(), "r"}};
  std::uint32_t engine_seed = 20261126;
  for (const MethodInfo& method : methods()) {
    SCOPED_TRACE(std::string(method.name));
    fuzz_models({serialize_model(analyze_material(method.name, maps))}, 1000, engine_seed++);
  }
}

// texton_mix models (texton paper section 7) are made by mix() from two exemplars, not by the
// registry's analyze, so the loop above does not reach them: a ramp model in colour and a mask
// model in grey, with few small textons.
std::vector<std::uint8_t> valid_mix_model(int channels, bool with_mask) {
  std::mt19937 engine(static_cast<unsigned>(channels * 13 + 5));
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF a(16, 16, channels), b(18, 14, channels), mask(3, 2, 1);
  for (ImageF* image : {&a, &b, &mask})
    for (float& value : image->pixels()) value = uniform(engine);
  MixInputs inputs;
  inputs.a = a.view();
  inputs.b = b.view();
  if (with_mask) inputs.mask = mask.view();
  return serialize_model(
      mix(inputs, {{"support", 6}, {"iterations", 3}, {"steps", 3}, {"mask_scale", 5}}, 0));
}

TEST(ModelFuzz, TextonMixMutantsLoadOrFailCleanly) {
  fuzz_models({valid_mix_model(3, false), valid_mix_model(1, true)}, 3000, 20261125);
}

// lrp models with every part of section 5 (structure blocks, turbulence strata, placement).
std::vector<std::uint8_t> valid_lrp_structure_model(int channels) {
  std::mt19937 engine(static_cast<unsigned>(channels * 17 + 3));
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF exemplar(20, 20, channels);
  for (float& value : exemplar.pixels()) value = uniform(engine);
  return serialize_model(analyze(
      "lrp", exemplar.view(),
      {{"cosines", 6}, {"strata", 2}, {"ratio", 0.5}, {"turbulence", 2}, {"placement", 1}}, 0));
}

TEST(ModelFuzz, LrpStructureMutantsLoadOrFailCleanly) {
  fuzz_models({valid_lrp_structure_model(1), valid_lrp_structure_model(3)}, 3000, 20261123);
}

}  // namespace
}  // namespace stochtex
