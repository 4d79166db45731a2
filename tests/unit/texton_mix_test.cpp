// Texton noise mixing (texton paper section 7): the model file round trip and its refusals,
// determinism whatever the threads and tiles, the end textons against plain texton noise's, and
// the refusals of `stochtex::mix`.

#include <gtest/gtest.h>

#include <random>

#include "methods/texton_mix/model.hpp"
#include "model/model_data.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::texton_mix_test {
namespace {

ImageF noise_image(int width, int height, int channels, std::uint32_t seed, float sd) {
  std::mt19937 engine(seed);
  std::normal_distribution<float> normal(0.5f, sd);
  ImageF image(width, height, channels);
  for (float& value : image.pixels()) value = normal(engine);
  return image;
}

MixInputs pair(const ImageF& a, const ImageF& b, const std::string& a_name = "A",
               const std::string& b_name = "B") {
  MixInputs inputs;
  inputs.a = a.view();
  inputs.b = b.view();
  inputs.a_name = a_name;
  inputs.b_name = b_name;
  return inputs;
}

MixInputs with_mask(MixInputs inputs, const ImageF& mask, const std::string& mask_name) {
  inputs.mask = mask.view();
  inputs.mask_name = mask_name;
  return inputs;
}

const ParamValues kSmall = {
    {"support", 12}, {"iterations", 10}, {"steps", 5}, {"ramp_start", -20}, {"ramp_end", 40}};

Model ramp_model() {
  const ImageF a = noise_image(40, 40, 3, 1, 0.1f);
  const ImageF b = noise_image(48, 36, 3, 2, 0.2f);
  return mix(pair(a, b), kSmall, 5);
}

Model mask_model() {
  const ImageF a = noise_image(32, 32, 1, 3, 0.1f);
  const ImageF b = noise_image(32, 32, 1, 4, 0.2f);
  ImageF mask(4, 3, 1);
  for (std::size_t i = 0; i < mask.pixels().size(); ++i)
    mask.pixels()[i] = static_cast<float>(i) / 11.0f;
  return mix(with_mask(pair(a, b), mask, "m"), {{"support", 8}, {"mask_scale", 6}}, 5);
}

ImageF render_with(const Model& model, const Grid& grid, int threads, int tile) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.threads = threads;
  options.tile_size = tile;
  render(model, grid, 7, out.view(), options);
  return out;
}

using test_support::same_bytes;

TEST(TextonMix, ModelFileRoundTripIsExact) {
  for (const Model& model : {ramp_model(), mask_model()}) {
    const Model loaded = deserialize_model(serialize_model(model), "mix.stx");
    EXPECT_EQ(loaded.method(), "texton_mix");
    EXPECT_EQ(serialize_model(loaded), serialize_model(model));
    const Grid grid{{-30.0, 4.0}, 1.5, 60, 20};
    EXPECT_TRUE(same_bytes(render_with(model, grid, 1, 64), render_with(loaded, grid, 1, 64)));
  }
}

TEST(TextonMix, BitIdenticalWhateverTheThreadsAndTiles) {
  for (const Model& model : {ramp_model(), mask_model()})
    for (const double scale : {1.0, 5.0}) {
      const Grid grid{{-40.5, 12.25}, scale, 97, 45};
      const ImageF reference = render_with(model, grid, 1, 64);
      EXPECT_TRUE(same_bytes(reference, render_with(model, grid, 2, 13)));
      EXPECT_TRUE(same_bytes(reference, render_with(model, grid, 3, 1000)));
      EXPECT_TRUE(same_bytes(reference, render_with(model, grid, 4, 1)));
    }
}

TEST(TextonMix, CorruptFilesAreRefused) {
  const ModelRecord good = [] {
    const Model model = ramp_model();
    return std::get<texton_mix::TextonMixModel>(model.data().model).to_record(model.params());
  }();
  test_support::expect_corruptions_rejected<texton_mix::TextonMixModel>(
      good,
      {{"steps", 1},
       {"steps", 6},
       {"ramp_end", -20},
       {"direction_x", 0},
       {"mask", 1},
       {"channels", 2},
       {"support", 13}},
      {{"textons", {3, std::numeric_limits<float>::quiet_NaN()}}, {"mean_b", {1, 1e30f}}});
  const ModelRecord good_mask = [] {
    const Model model = mask_model();
    return std::get<texton_mix::TextonMixModel>(model.data().model).to_record(model.params());
  }();
  test_support::expect_corruptions_rejected<texton_mix::TextonMixModel>(
      good_mask, {{"mask_width", 5}, {"mask_scale", 0}}, {{"mask", {2, 1.5f}}});
}

TEST(TextonMix, ModelFilesOfMoreThanFourChannelsAreRefused) {
  // Texton noise mixing stays at 1 to 4 channels while texton noise takes kMaxChannels (a
  // material's maps, issue 18): a 5-channel file whose arrays have that shape is refused with a
  // sentence naming the file, and so are 5-channel exemplars.
  const ImageF five = noise_image(16, 16, 5, 7, 0.1f);
  try {
    mix(pair(five, five, "material_a", "material_b"), kSmall, 1);
    ADD_FAILURE() << "mix took 5 channels";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_EQ(error.code(), ErrorCode::invalid_input) << what;
    EXPECT_NE(what.find("'material_a' has 5 channels"), std::string::npos) << what;
  }
  const Model model = ramp_model();
  ModelRecord record =
      std::get<texton_mix::TextonMixModel>(model.data().model).to_record(model.params());
  record.scalars["channels"] = 5;
  for (NamedArray& array : record.arrays) {
    ASSERT_EQ(array.shape.back(), 3) << array.name;
    array.shape.back() = 5;
    std::vector<float> values;
    for (std::size_t i = 0; i < array.values.size(); i += 3)
      values.insert(values.end(), {array.values[i], array.values[i + 1], array.values[i + 2],
                                   array.values[i], array.values[i + 1]});
    array.values = values;
  }
  try {
    texton_mix::TextonMixModel::from_record(record, "mix.stx");
    ADD_FAILURE() << "texton_mix took 5 channels";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_EQ(error.code(), ErrorCode::format) << what;
    EXPECT_NE(what.find("'mix.stx'"), std::string::npos) << what;
    EXPECT_NE(what.find("channels"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// At rho = 0 and rho = 1 the kernels are A's (phase-aligned, same spectrum) and B's: the textons
// have the power of plain texton noise's of each exemplar (same initialisation, same Algorithm 1).
TEST(TextonMix, EndTextonsHaveThePowerOfEachExemplarsTexton) {
  const ImageF a = noise_image(40, 40, 1, 11, 0.1f);
  const ImageF b = noise_image(40, 40, 1, 12, 0.3f);
  const Model model = mix(pair(a, b), {{"support", 12}, {"steps", 3}}, 2);
  const auto& mixed = std::get<texton_mix::TextonMixModel>(model.data().model);
  const auto power = [](std::span<const float> values) {
    double sum = 0.0;
    for (const float v : values) sum += static_cast<double>(v) * v;
    return sum;
  };
  for (const auto& [image, step] : {std::pair{&a, 0}, std::pair{&b, 2}}) {
    const Model plain = analyze("texton", image->view(), {{"support", 12}}, 2);
    const double expected = power(std::get<texton::TextonModel>(plain.data().model).coefficients());
    EXPECT_NEAR(power(mixed.texton(step).coefficients()), expected, 0.02 * expected);
  }
  // rho = 1 is B's kernel itself: the same texton as plain texton noise, up to float rounding.
  const Model plain_b = analyze("texton", b.view(), {{"support", 12}}, 2);
  const auto expected = std::get<texton::TextonModel>(plain_b.data().model).coefficients();
  const auto got = mixed.texton(2).coefficients();
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-3);
}

TEST(TextonMix, BadInputIsRefusedWithOneSentence) {
  const ImageF grey = noise_image(32, 32, 1, 1, 0.1f);
  const ImageF colour = noise_image(32, 32, 3, 2, 0.1f);
  try {
    mix(pair(grey, colour, "g.png", "c.png"));
    ADD_FAILURE() << "different channel counts accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'g.png' (1 channels) with 'c.png' (3 channels)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(mix(with_mask(pair(grey, grey), colour, "m.png")), Error);
  EXPECT_THROW(mix(pair(grey, grey), {{"ramp_start", 5}, {"ramp_end", 5}}), std::invalid_argument);
  EXPECT_THROW(mix(pair(grey, grey), {{"direction_x", 0}}), std::invalid_argument);
  EXPECT_THROW(mix(pair(grey, grey), {{"steps", 1}}), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::texton_mix_test
