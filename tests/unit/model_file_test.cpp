// The .stx model file (docs/design.md §7): exact round trips, and every corrupt, truncated,
// hostile or foreign file rejected by stochtex::Error(format) with a sentence naming the file.

#include "model/model_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::model_file_test {
namespace {

Model small_model(int channels) {
  std::mt19937 engine(4);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  ImageF exemplar(32, 32, channels);
  for (float& value : exemplar.pixels()) value = uniform(engine);
  return analyze("texton", exemplar.view(), {{"support", 12}, {"iterations", 5}}, 1);
}

// The checksum recomputed, so mutated files get past it and reach the deeper validation
// (header, shapes, values).
std::vector<std::uint8_t> with_checksum(std::vector<std::uint8_t> bytes) {
  bytes.resize(bytes.size() - 8);
  const std::uint64_t hash = model_checksum(bytes);
  for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(hash >> (8 * i)));
  return bytes;
}

// The FNV-1a 64 hash (the checksum of model files before version 4).
std::uint64_t fnv1a(std::span<const std::uint8_t> bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const std::uint8_t byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
  return hash;
}

// A file made of a given header and `float_count` zero floats, with a valid checksum.
std::vector<std::uint8_t> file_with_header(const std::string& header, std::size_t float_count,
                                           std::uint32_t version = kSingleImageModelFormatVersion) {
  std::vector<std::uint8_t> bytes = {'S', 'T', 'O', 'C', 'H', 'T', 'E', 'X'};
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(version >> (8 * i)));
  const auto length = static_cast<std::uint32_t>(header.size());
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(length >> (8 * i)));
  bytes.insert(bytes.end(), header.begin(), header.end());
  bytes.resize(bytes.size() + 4 * float_count + 8, 0);
  return with_checksum(bytes);
}

void expect_rejected(const std::vector<std::uint8_t>& bytes, const std::string& what) {
  try {
    deserialize_model(bytes, "model.stx");
    ADD_FAILURE() << what << ": accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::format) << what;
    const std::string message = error.what();
    EXPECT_NE(message.find("'model.stx'"), std::string::npos) << what << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
  }
}

TEST(ModelFile, RoundTripIsExact) {
  // 9 and kMaxChannels: a material's maps (issue 18), which texton noise analyses jointly.
  for (const int channels : {1, 3, 4, 9, kMaxChannels}) {
    const Model model = small_model(channels);
    const std::vector<std::uint8_t> bytes = serialize_model(model);
    const Model loaded = deserialize_model(bytes, "memory");
    EXPECT_EQ(loaded.method(), "texton");
    EXPECT_EQ(loaded.channels(), channels);
    EXPECT_EQ(loaded.params(), model.params());
    EXPECT_EQ(serialize_model(loaded), bytes);
    // Same model, same evaluation, bit for bit.
    const std::vector<Vec2d> points = {{0.5, 0.5}, {100.25, -7.0}, {1e7, 3e6}};
    ImageF a(3, 1, channels);
    ImageF b(3, 1, channels);
    evaluate(model, points, {}, 5, a.view());
    evaluate(loaded, points, {}, 5, b.view());
    EXPECT_TRUE(test_support::same_bytes(a, b));
  }
}

TEST(ModelFile, SaveAndLoadThroughTheFileSystem) {
  const Model model = small_model(3);
  const auto folder = std::filesystem::temp_directory_path() / "stochtex_model_file_test";
  std::filesystem::create_directories(folder);
  const auto path = folder / "m.stx";
  save_model(model, path);
  EXPECT_FALSE(std::filesystem::exists(folder / "m.stx.tmp"));
  EXPECT_EQ(serialize_model(load_model(path)), serialize_model(model));
  EXPECT_THROW(save_model(model, folder / "missing" / "m.stx"), Error);
  EXPECT_FALSE(std::filesystem::exists(folder / "missing"));
  EXPECT_THROW(load_model(folder / "nothing.stx"), Error);
  std::filesystem::remove_all(folder);
}

TEST(ModelFile, EveryTruncationIsRejected) {
  const std::vector<std::uint8_t> bytes = serialize_model(small_model(3));
  for (std::size_t length = 0; length < bytes.size(); ++length)
    expect_rejected({bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(length)},
                    "truncated to " + std::to_string(length));
}

TEST(ModelFile, EveryByteFlipIsRejected) {
  const std::vector<std::uint8_t> bytes = serialize_model(small_model(1));
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::vector<std::uint8_t> corrupt = bytes;
    corrupt[i] ^= 0x20;
    expect_rejected(corrupt, "byte " + std::to_string(i) + " flipped");
  }
}

// Versions 1 to 3 end with the FNV-1a 64 checksum, version 4 with XXH3-64: each file is checked by
// its version's.
TEST(ModelFile, EachVersionHasItsChecksum) {
  const std::vector<std::uint8_t> bytes = serialize_model(small_model(1));
  ASSERT_EQ(bytes[8], kModelFormatVersion);
  const std::span<const std::uint8_t> payload = std::span(bytes).first(bytes.size() - 8);
  EXPECT_NE(model_checksum(payload), fnv1a(payload));
  std::vector<std::uint8_t> older = bytes;
  older[8] = static_cast<std::uint8_t>(kSingleImageModelFormatVersion);
  const std::span<const std::uint8_t> older_payload = std::span(older).first(older.size() - 8);
  EXPECT_EQ(model_checksum(older_payload), fnv1a(older_payload));
  EXPECT_NO_THROW(deserialize_model(with_checksum(older), "older.stx"));
  std::vector<std::uint8_t> mislabelled = with_checksum(older);
  mislabelled[8] = static_cast<std::uint8_t>(kModelFormatVersion);
  expect_rejected(mislabelled, "version 4 with FNV-1a's checksum");
}

TEST(ModelFile, OtherVersionsGetAClearMessage) {
  const std::string header = R"({"method":"texton","params":{},"scalars":{},"arrays":[]})";
  try {
    deserialize_model(file_with_header(header, 0, kModelFormatVersion + 1), "new.stx");
    FAIL() << "a newer version was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("upgrade stochtex"), std::string::npos);
  }
  try {
    deserialize_model(file_with_header(header, 0, 0), "old.stx");
    FAIL() << "an older version was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("re-run `stochtex analyze`"), std::string::npos);
  }
}

TEST(ModelFile, HostileAndInconsistentHeadersAreRejected) {
  const std::string good_arrays =
      R"([{"name":"texton","shape":[2,2,1]},{"name":"mean","shape":[1]}])";
  const std::string good_scalars = R"({"channels":1,"support":2,"order":1,"mni":30})";
  auto header = [](const std::string& scalars, const std::string& arrays) {
    return R"({"method":"texton","params":{"mni":30},"scalars":)" + scalars + R"(,"arrays":)" +
           arrays + "}";
  };
  // The well-formed reference file is accepted, so each rejection below is due to its one change.
  EXPECT_NO_THROW(deserialize_model(file_with_header(header(good_scalars, good_arrays), 5), "m"));

  expect_rejected(file_with_header("not json at all", 0), "not JSON");
  expect_rejected(file_with_header(std::string(100000, '[') + std::string(100000, ']'), 0),
                  "deep nesting");
  expect_rejected(file_with_header(R"({"method":"texton"})", 0), "missing fields");
  expect_rejected(
      file_with_header(R"({"method":"voronoi","params":{},"scalars":{},"arrays":[]})", 0),
      "unknown method");
  expect_rejected(
      file_with_header(
          header(good_scalars, R"([{"name":"texton","shape":[1000000,1000000,1000000]}])"), 0),
      "a declared size of 10^18 values");
  expect_rejected(file_with_header(header(good_scalars, R"([{"name":"texton","shape":[268435456]},)"
                                                        R"({"name":"mean","shape":[268435456]}])"),
                                   0),
                  "two arrays of 1 GiB");
  expect_rejected(file_with_header(header(good_scalars, R"([{"name":"texton","shape":[-4]}])"), 0),
                  "negative size");
  expect_rejected(file_with_header(header(good_scalars, good_arrays), 4),
                  "data shorter than declared");
  expect_rejected(file_with_header(header(good_scalars, good_arrays), 6),
                  "data longer than declared");
  expect_rejected(file_with_header(header(good_scalars, R"([{"name":"texton","shape":[3,3,1]},)"
                                                        R"({"name":"mean","shape":[1]}])"),
                                   10),
                  "shape disagrees with the support");
  expect_rejected(
      file_with_header(header(R"({"channels":1,"support":2,"order":2,"mni":30})", good_arrays), 5),
      "order 2");
  expect_rejected(
      file_with_header(header(R"({"channels":1,"support":2,"order":1,"mni":-1})", good_arrays), 5),
      "negative mni");
  expect_rejected(
      file_with_header(header(R"({"channels":1,"support":2,"order":1})", good_arrays), 5),
      "missing mni");
  expect_rejected(file_with_header(header(good_scalars, R"([{"name":"texton","shape":[2,2,1]},)"
                                                        R"({"name":"texton","shape":[1]}])"),
                                   5),
                  "repeated array name");
  // The exemplar's wrap steps: optional (a file without them loads, with none), two finite
  // numbers >= 0 when present.
  const auto with_wrap = [&](const std::string& wrap) {
    std::string text = header(good_scalars, good_arrays);
    text.insert(text.size() - 1, R"(,"exemplar_wrap_step":)" + wrap);
    return file_with_header(text, 5);
  };
  EXPECT_FALSE(deserialize_model(file_with_header(header(good_scalars, good_arrays), 5), "m")
                   .exemplar_wrap()
                   .has_value());
  const Model wrapped = deserialize_model(with_wrap("[4.5,0.75]"), "m");
  ASSERT_TRUE(wrapped.exemplar_wrap().has_value());
  EXPECT_EQ(wrapped.exemplar_wrap()->x, 4.5);
  EXPECT_EQ(wrapped.exemplar_wrap()->y, 0.75);
  for (const std::string wrap :
       {R"("4.5")", "[4.5]", "[4.5,-1]", "[4.5,1e400]", R"([1,"a"])", "[1,2,3]", "{}"})
    expect_rejected(with_wrap(wrap), "exemplar_wrap_step " + wrap);
}

TEST(ModelFile, NonFiniteValuesAreRejected) {
  const Model model = small_model(1);
  std::vector<std::uint8_t> bytes = serialize_model(model);
  // The first float of the texton array sits right after the header.
  std::uint32_t header_length = 0;
  std::memcpy(&header_length, bytes.data() + 12, 4);
  const std::uint32_t nan_bits = 0x7fc00000u;
  std::memcpy(bytes.data() + 16 + header_length, &nan_bits, 4);
  expect_rejected(with_checksum(bytes), "NaN texton value");
}

// FNV-1a 64 of a render's float32 values, row by row, little-endian.
std::uint64_t render_hash(const Model& model, double scale, std::uint32_t seed) {
  ImageF image(32, 24, model.channels());
  render(model, Grid{{0.0, 0.0}, scale, 32, 24}, seed, image.view());
  std::vector<std::uint8_t> bytes;
  for (const float value : image.pixels()) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
  }
  return fnv1a(bytes);
}

// Files written before colour spaces (the model corpus of the fuzz tests, written by earlier
// stochtex versions) load as data, are written again without a colour space, and render what they
// rendered before: the hashes of a 32x24 render at scale 1 (seed 0) and 3.7 (seed 5), measured
// with stochtex at 64f3d9b, before models had a colour space.
TEST(ModelFile, FilesWrittenBeforeColourSpacesRenderAsBefore) {
  const struct {
    const char* name;
    std::uint64_t scale_1;
    std::uint64_t scale_3_7;
  } files[] = {
      {"gabor", 0x092978c01bb39ca2ull, 0x4435ab813bacb818ull},
      {"lrp", 0xd0e7c85d37cb60b9ull, 0x1d6fb4bf5a24e940ull},
      {"lrp_structure", 0xbb7aacc27510d6f3ull, 0x5fdb2ca4088effd5ull},
      {"texton", 0x3ea748979d86c393ull, 0x069c0b4328a5e4cbull},
      {"texton_mix", 0xa150dcd4d07c5988ull, 0x423cb46804209b1aull},
      {"texton_mix_mask", 0x74a64b0bbebb630dull, 0x2f85c8ae951edc25ull},
      {"tiling", 0x17de620cc6225b99ull, 0x13f6a1f7427db4cbull},
      {"tiling_grey", 0x17b59e55a087975full, 0x24986b6ffcc0e2ceull},
  };
  for (const auto& file : files) {
    const std::filesystem::path path = std::filesystem::path(STOCHTEX_SOURCE_DIR) / "tests" /
                                       "fuzz" / "corpus" / "model" /
                                       (std::string(file.name) + ".stx");
    std::ifstream in(path, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                          std::istreambuf_iterator<char>());
    const Model model = deserialize_model(bytes, path.string());
    EXPECT_EQ(model.colour_space(), ColourSpace::data) << file.name;
    // Written again in the newest version without a colour space (texton's file predates its
    // `points` parameter, which is written now).
    const std::vector<std::uint8_t> again = serialize_model(model);
    EXPECT_LT(bytes[8], kModelFormatVersion) << file.name;
    EXPECT_EQ(again[8], kModelFormatVersion) << file.name;
    const ModelRecord record = read_model_record(again, path.string());
    EXPECT_FALSE(has_colour(record)) << file.name;
    EXPECT_TRUE(std::none_of(record.arrays.begin(), record.arrays.end(), [](const NamedArray& a) {
      return a.name == "colour_removed_deviation";
    })) << file.name;
    EXPECT_EQ(render_hash(model, 1.0, 0), file.scale_1) << file.name;
    EXPECT_EQ(render_hash(model, 3.7, 5), file.scale_3_7) << file.name;
  }
}

// A model keeps its colour space, with its table of removed deviations, through the file; a
// version-3 file without a colour space, a colour space in an older version, an unknown one, or a
// srgb model without its table are corrupt.
TEST(ModelFile, ColourSpacesRoundTrip) {
  const Model data = small_model(3);
  EXPECT_EQ(serialize_model(data)[8], kModelFormatVersion);
  const Model srgb = with_colour_space(data, ColourSpace::srgb);
  const std::vector<std::uint8_t> bytes = serialize_model(srgb);
  EXPECT_EQ(bytes[8], kModelFormatVersion);
  const Model loaded = deserialize_model(bytes, "srgb.stx");
  EXPECT_EQ(loaded.colour_space(), ColourSpace::srgb);
  EXPECT_EQ(serialize_model(loaded), bytes);
  EXPECT_EQ(render_hash(loaded, 5.0, 2), render_hash(srgb, 5.0, 2));
  EXPECT_NE(render_hash(loaded, 5.0, 2), render_hash(data, 5.0, 2));
  const Model back = with_colour_space(srgb, ColourSpace::data);
  EXPECT_EQ(serialize_model(back), serialize_model(data));
  EXPECT_NE(describe_model(srgb).find("\"colour_space\": \"srgb\""), std::string::npos);

  const std::string text(bytes.begin(), bytes.end());
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    changed.replace(changed.find(from), from.size(), to);
    std::vector<std::uint8_t> out(changed.begin(), changed.end());
    return with_checksum(out);
  };
  expect_rejected(replaced("\"colour_space\":\"srgb\"", "\"colour_space\":\"oklab\""),
                  "unknown colour space");
  std::vector<std::uint8_t> version_three = bytes;
  version_three[8] = static_cast<std::uint8_t>(kColourModelFormatVersion);
  const std::string three(version_three.begin(), version_three.end());
  std::string spade = three;
  spade.replace(spade.find("\"colour_space\":\"srgb\""), 22, "\"colour_spade\":\"srgb\"");
  // Same length, so the header's declared length still holds.
  expect_rejected(with_checksum(std::vector<std::uint8_t>(spade.begin(), spade.end())),
                  "version-3 model file without a colour space");
  EXPECT_NO_THROW(deserialize_model(with_checksum(version_three), "three.stx"));
  std::vector<std::uint8_t> older = with_checksum(bytes);
  older[8] = static_cast<std::uint8_t>(kSingleImageModelFormatVersion);
  expect_rejected(with_checksum(older), "colour space where its format version holds none");
  expect_rejected(replaced("colour_removed_deviation", "colour_removed_deviatioX"),
                  "removed deviations");
}

}  // namespace
}  // namespace stochtex::model_file_test
