// Materials (stochtex/material.hpp): the maps' checks, normal maps as slopes and back, the layout
// in the model file.

#include "stochtex/material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/model_file.hpp"
#include "stochtex/io.hpp"
#include "test_support.hpp"

namespace stochtex::material_test {
namespace {

using test_support::kRock;

ImageF rock(const std::string& map) {
  return read_image(kRock + map + ".png");
}

// The sentence of the Error(invalid_input) that `call` throws, or "" when it throws none.
template <typename Call>
std::string refusal(Call call) {
  try {
    call();
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::invalid_input) << error.what();
    return error.what();
  }
  return "";
}

bool mentions(const std::string& sentence, const std::string& part) {
  return sentence.find(part) != std::string::npos;
}

TEST(Material, NormalMapsBecomeSlopesAndComeBackAsUnitNormals) {
  const ImageF albedo = rock("albedo");
  const ImageF normal = rock("normal");
  const std::vector<MaterialMap> maps{{"albedo", {}, albedo.view(), "albedo.png"},
                                      {"normal", {}, normal.view(), "normal.png"}};
  const MaterialExemplar material = material_exemplar(maps);
  ASSERT_EQ(material.maps.size(), 2u);
  EXPECT_EQ(material.maps[0].kind, MapKind::colour);
  EXPECT_EQ(material.maps[1].kind, MapKind::normal);
  ASSERT_EQ(material.exemplar.channels(), 5);

  // The slopes are those of the decoded normal (renormalising does not change them); split_maps
  // turns them back into the renormalised normal, encoded 0.5 + 0.5 n.
  const Model model = analyze_material("tiling", std::vector<MaterialMap>{maps[1]});
  ASSERT_EQ(model.maps().size(), 1u);
  const MaterialExemplar slopes = material_exemplar(std::vector<MaterialMap>{maps[1]});
  const std::vector<NamedImage> split = split_maps(model, slopes.exemplar.view());
  ASSERT_EQ(split.size(), 1u);
  ASSERT_EQ(split[0].name, "normal");
  ASSERT_EQ(split[0].image.channels(), 3);
  double slope_error = 0.0;
  double normal_error = 0.0;
  for (int y = 0; y < normal.height(); ++y)
    for (int x = 0; x < normal.width(); ++x) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(material.exemplar.at(x, y, c), albedo.at(x, y, c));
      double n[3];
      for (int c = 0; c < 3; ++c) n[c] = 2.0 * normal.at(x, y, c) - 1.0;
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      slope_error = std::max({slope_error, std::abs(material.exemplar.at(x, y, 3) + n[0] / n[2]),
                              std::abs(material.exemplar.at(x, y, 4) + n[1] / n[2])});
      for (int c = 0; c < 3; ++c)
        normal_error = std::max(normal_error,
                                std::abs(split[0].image.at(x, y, c) - (0.5 + 0.5 * n[c] / length)));
    }
  EXPECT_LT(slope_error, 1e-5);
  EXPECT_LT(normal_error, 1e-6);
}

TEST(Material, GreenDownNormalsFlipTheYSlope) {
  const ImageF normal = rock("normal");
  const std::vector<MaterialMap> maps{{"normal", {}, normal.view(), "normal.png"}};
  const ImageF up = material_exemplar(maps).exemplar;
  const ImageF down = material_exemplar(maps, {.normal_y_down = true}).exemplar;
  for (int y = 0; y < normal.height(); y += 7)
    for (int x = 0; x < normal.width(); x += 5) {
      EXPECT_EQ(up.at(x, y, 0), down.at(x, y, 0));
      EXPECT_EQ(up.at(x, y, 1), -down.at(x, y, 1));
    }
}

TEST(Material, KindsComeFromNamesAndGreyRgbIsOneChannel) {
  EXPECT_EQ(default_map_kind("normal"), MapKind::normal);
  EXPECT_EQ(default_map_kind("displacement"), MapKind::height);
  EXPECT_EQ(default_map_kind("roughness"), MapKind::scalar);
  EXPECT_EQ(default_map_kind("ao"), MapKind::scalar);
  EXPECT_EQ(default_map_kind("albedo"), MapKind::colour);
  const ImageF grey = rock("roughness");
  ImageF rgb(grey.width(), grey.height(), 3);
  for (int y = 0; y < grey.height(); ++y)
    for (int x = 0; x < grey.width(); ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = grey.at(x, y, 0);
  const MaterialExemplar material =
      material_exemplar(std::vector<MaterialMap>{{"roughness", {}, rgb.view(), "r.png"}});
  EXPECT_EQ(material.exemplar.channels(), 1);
  EXPECT_TRUE(test_support::same_bytes(material.exemplar, grey));
}

TEST(Material, UnusableMapsAreRefusedWithASentence) {
  const ImageF albedo = rock("albedo");
  const ImageF normal = rock("normal");
  const ImageF small = read_image(std::string(STOCHTEX_TEXTURE_DIR) + "/grass_lawn_128.png");
  ImageF rgba(albedo.width(), albedo.height(), 4, 1.0f);
  rgba.at(3, 3, 0) = 0.5f;
  const ImageF constant(albedo.width(), albedo.height(), 1, 0.25f);
  const auto refused = [](std::vector<MaterialMap> maps) {
    return refusal([&] { material_exemplar(maps); });
  };
  EXPECT_TRUE(mentions(
      refused({{"albedo", {}, albedo.view(), "a.png"}, {"roughness", {}, small.view(), "s.png"}}),
      "'s.png' (roughness) is 128x128 but 'a.png' (albedo) is 256x256"));
  EXPECT_TRUE(mentions(refused({{"albedo", {}, rgba.view(), "a.png"}}), "alpha channel"));
  EXPECT_TRUE(mentions(refused({{"roughness", {}, albedo.view(), "a.png"}}), "one channel"));
  EXPECT_TRUE(mentions(refused({{"metallic", {}, constant.view(), "m.png"}}), "constant"));
  EXPECT_TRUE(mentions(
      refused({{"albedo", {}, albedo.view(), "a.png"}, {"albedo", {}, albedo.view(), "b.png"}}),
      "names the map 'albedo' twice"));
  EXPECT_TRUE(mentions(refused({{"Albedo", {}, albedo.view(), "a.png"}}), "map names are"));
  EXPECT_TRUE(mentions(refused({{"normal", {}, constant.view(), "n.png"}}), "constant"));
  EXPECT_TRUE(mentions(refused({{"normal", {}, small.view(), "n.png"}}),
                       "'n.png' (normal) is not a tangent-space normal map"));
  EXPECT_EQ(refused({{"normal", {}, normal.view(), "n.png"}}), "");
  EXPECT_EQ(refused({{"bump", MapKind::colour, albedo.view(), "a.png"}}), "");
}

// Every 3-channel exemplar of the corpus given as a normal map is refused: the four rules
// (length, facing out, upright on average) tell photos from normal maps.
TEST(Material, NoPhotoOfTheCorpusPassesForANormalMap) {
  int photos = 0;
  for (const auto& entry : std::filesystem::directory_iterator(STOCHTEX_TEXTURE_DIR)) {
    if (entry.path().extension() != ".png") continue;
    const ImageF image = read_image(entry.path());
    if (image.channels() != 3) continue;
    ++photos;
    const std::string sentence = refusal([&] {
      material_exemplar(std::vector<MaterialMap>{{"normal", {}, image.view(), "photo.png"}});
    });
    EXPECT_TRUE(mentions(sentence, "is not a tangent-space normal map"))
        << entry.path() << ": " << sentence;
  }
  EXPECT_GE(photos, 10);
  for (const std::string set : {"rock_sandstone", "sand_pebbles"}) {
    const ImageF normal =
        read_image(std::string(STOCHTEX_MATERIAL_DIR) + "/" + set + "/normal.png");
    EXPECT_EQ(
        refusal([&] {
          material_exemplar(std::vector<MaterialMap>{{"normal", {}, normal.view(), "normal.png"}});
        }),
        "")
        << set;
  }
}

TEST(Material, MoreChannelsThanTheMethodTakesAreRefusedBeforeAnalysis) {
  const ImageF albedo = rock("albedo");
  const ImageF roughness = rock("roughness");
  for (const MethodInfo& method : methods()) {
    if (method.max_channels >= kMaxChannels) continue;
    std::vector<MaterialMap> maps;
    int channels = 0;
    while (channels + 3 <= method.max_channels + 1) {
      maps.push_back({"albedo" + std::to_string(maps.size()), {}, albedo.view(), "a.png"});
      channels += 3;
    }
    while (channels < method.max_channels + 1) {
      maps.push_back({"roughness" + std::to_string(maps.size()), {}, roughness.view(), "r.png"});
      channels += 1;
    }
    const std::string sentence = refusal([&] { analyze_material(method.name, maps); });
    EXPECT_TRUE(mentions(sentence, "this material has " + std::to_string(channels)))
        << method.name << ": " << sentence;
  }
  std::vector<MaterialMap> seventeen;
  for (int i = 0; i < 5; ++i)
    seventeen.push_back({"colour" + std::to_string(i), {}, albedo.view(), "a.png"});
  seventeen.push_back({"roughness", {}, roughness.view(), "r.png"});
  seventeen.push_back({"ao", {}, roughness.view(), "r.png"});
  EXPECT_TRUE(mentions(refusal([&] { material_exemplar(seventeen); }),
                       "has 17 channels in 7 maps, more than the 16"));
}

TEST(Material, ModelFilesKeepTheMaps) {
  const ImageF albedo = rock("albedo");
  const ImageF roughness = rock("roughness");
  const Model material = analyze_material(
      "tiling", std::vector<MaterialMap>{{"albedo", {}, albedo.view(), "a.png"},
                                         {"roughness", {}, roughness.view(), "r.png"}});
  const std::vector<std::uint8_t> bytes = serialize_model(material);
  EXPECT_EQ(bytes[8], kModelFormatVersion);
  const Model loaded = deserialize_model(bytes, "m.stx");
  ASSERT_EQ(loaded.maps().size(), 2u);
  EXPECT_EQ(loaded.maps()[0].name, "albedo");
  EXPECT_EQ(loaded.maps()[1].kind, MapKind::scalar);
  EXPECT_EQ(serialize_model(loaded), bytes);
  EXPECT_NE(describe_model(loaded).find("\"maps\""), std::string::npos);

  const Model image = analyze("tiling", albedo.view());
  EXPECT_EQ(serialize_model(image)[8], kModelFormatVersion);
  EXPECT_TRUE(image.maps().empty());
  EXPECT_EQ(describe_model(image).find("\"maps\""), std::string::npos);
}

// A hostile or corrupt list of maps is refused with a format error naming the file.
TEST(Material, CorruptMapListsAreRefused) {
  const ImageF albedo = rock("albedo");
  const ImageF roughness = rock("roughness");
  const Model material = analyze_material(
      "tiling", std::vector<MaterialMap>{{"albedo", {}, albedo.view(), "a.png"},
                                         {"roughness", {}, roughness.view(), "r.png"}});
  const std::vector<std::uint8_t> good = serialize_model(material);
  // The file with `from` replaced by `to` in its header (same length), its checksum redone.
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::vector<std::uint8_t> bytes = good;
    const std::string text(bytes.begin(), bytes.end());
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    EXPECT_EQ(from.size(), to.size());
    std::copy(to.begin(), to.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at));
    const std::uint64_t sum = model_checksum(std::span(bytes).first(bytes.size() - 8));
    for (int i = 0; i < 8; ++i)
      bytes[bytes.size() - 8 + i] = static_cast<std::uint8_t>(sum >> (8 * i));
    return bytes;
  };
  const auto refused = [](const std::vector<std::uint8_t>& bytes) {
    try {
      deserialize_model(bytes, "bad.stx");
    } catch (const Error& error) {
      EXPECT_EQ(error.code(), ErrorCode::format);
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_TRUE(mentions(refused(edited("\"scalar\"", "\"volume\"")), "malformed map"));
  EXPECT_TRUE(mentions(refused(edited("roughness", "Roughness")), "map names are"));
  EXPECT_TRUE(mentions(refused(edited("\"channels\":1}", "\"channels\":3}")),
                       "gives the scalar map 'roughness' 3 channels"));
  EXPECT_TRUE(mentions(
      refused(edited("\"kind\":\"scalar\",\"channels\":1", "\"kind\":\"colour\",\"channels\":3")),
      "declares maps of 6 channels for a model of 4"));
  std::vector<std::uint8_t> version_one = good;
  version_one[8] = 1;
  const std::uint64_t sum = model_checksum(std::span(version_one).first(version_one.size() - 8));
  for (int i = 0; i < 8; ++i)
    version_one[version_one.size() - 8 + i] = static_cast<std::uint8_t>(sum >> (8 * i));
  EXPECT_TRUE(mentions(refused(version_one), "list of maps in a version-1"));
}

// With a height map, texton (a method that derives normals) derives the normal map: no channels
// of its own, its slopes the scale times the rendered height's central differences.
TEST(Material, NormalMapsDeriveFromTheHeight) {
  const ImageF albedo = rock("albedo");
  const ImageF normal = rock("normal");
  const ImageF height = rock("height");
  const std::vector<MaterialMap> maps{{"albedo", {}, albedo.view(), "a.png"},
                                      {"normal", {}, normal.view(), "n.png"},
                                      {"height", {}, height.view(), "h.png"}};
  const Model model = analyze_material("texton", maps, {{"iterations", 3}});
  ASSERT_EQ(model.channels(), 4);
  const MapInfo& derived = model.maps()[1];
  EXPECT_EQ(derived.channels, 0);
  EXPECT_EQ(derived.derived_from, "height");
  EXPECT_GT(derived.slope_scale, 0.0);
  const Model loaded = deserialize_model(serialize_model(model), "m.stx");
  EXPECT_EQ(loaded.maps()[1].slope_scale, derived.slope_scale);
  EXPECT_THROW(split_maps(model, ImageF(4, 4, 4).view()), std::invalid_argument);

  const Grid grid{{3.0, -5.0}, 2.0, 24, 16};
  const std::vector<NamedImage> parts = render_maps(
      model, grid, [&](const Grid& part, ImageView<float> out) { render(model, part, 9, out); });
  ASSERT_EQ(parts.size(), 3u);
  // The height's neighbours: the same grid one pixel wider on each side.
  ImageF wide(grid.width + 2, grid.height + 2, 4);
  render(model, Grid{grid.origin, grid.scale, grid.width + 2, grid.height + 2, -1, -1}, 9,
         wide.view());
  const double k = derived.slope_scale / (2.0 * grid.scale);
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const double sx = k * (wide.at(x + 2, y + 1, 3) - wide.at(x, y + 1, 3));
      const double sy = -k * (wide.at(x + 1, y + 2, 3) - wide.at(x + 1, y, 3));
      const double length = std::sqrt(sx * sx + sy * sy + 1.0);
      EXPECT_NEAR(parts[1].image.at(x, y, 0), 0.5 - 0.5 * sx / length, 1e-6);
      EXPECT_NEAR(parts[1].image.at(x, y, 1), 0.5 - 0.5 * sy / length, 1e-6);
      EXPECT_EQ(parts[2].image.at(x, y, 0), wide.at(x + 1, y + 1, 3));
    }
  // tiling copies the normal map from the same patches: two channels of its own.
  EXPECT_EQ(analyze_material("tiling", maps).maps()[1].channels, 2);
  // So does texton when asked to synthesise it.
  EXPECT_EQ(analyze_material("texton", maps, {{"iterations", 3}}, 0, {.derive_normals = false})
                .maps()[1]
                .channels,
            2);
}

}  // namespace
}  // namespace stochtex::material_test
