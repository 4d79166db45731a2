// Checks what README.md's library example wrote: check_outputs EXEMPLAR MODEL TEXTURE.
// The model loads as a texton model of the exemplar's channels, the texture is 512x512 with those
// channels, varies, and keeps each channel's mean: texton noise is the exemplar's mean plus a
// zero-mean fluctuation (Galerne et al., "Texton Noise", eq. (2)), so a wrong model or a garbled
// file shows here.

#include <cmath>
#include <cstdio>
#include <stochtex/io.hpp>
#include <stochtex/model.hpp>
#include <stochtex/render.hpp>
#include <vector>

namespace {

std::vector<double> channel_means(const stochtex::ImageF& image) {
  std::vector<double> means(image.channels(), 0.0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < image.channels(); ++c) means[c] += image.at(x, y, c);
  for (double& mean : means) mean /= static_cast<double>(image.pixel_count());
  return means;
}

bool varies(const stochtex::ImageF& image) {
  for (const float value : image.pixels())
    if (value != image.pixels()[0]) return true;
  return false;
}

int fail(const char* message) {
  std::fprintf(stderr, "check_outputs: %s\n", message);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) return fail("usage: check_outputs EXEMPLAR MODEL TEXTURE");
  const stochtex::ImageF exemplar = stochtex::read_image(argv[1]);
  const stochtex::Model model = stochtex::load_model(argv[2]);
  const stochtex::ImageF texture = stochtex::read_image(argv[3]);

  if (model.method() != "texton") return fail("the model is not a texton model");
  if (model.channels() != exemplar.channels())
    return fail("the model's channels differ from the exemplar's");
  if (texture.width() != 512 || texture.height() != 512 ||
      texture.channels() != exemplar.channels())
    return fail("the texture is not 512x512 with the exemplar's channels");
  if (!varies(texture)) return fail("the texture is constant");
  const std::vector<double> exemplar_means = channel_means(exemplar);
  const std::vector<double> texture_means = channel_means(texture);
  for (int c = 0; c < exemplar.channels(); ++c) {
    std::printf("channel %d: exemplar mean %.4f, texture mean %.4f\n", c, exemplar_means[c],
                texture_means[c]);
    if (std::abs(texture_means[c] - exemplar_means[c]) > 0.03)
      return fail("the texture's mean is not the exemplar's");
  }

  stochtex::ImageF render(64, 64, model.channels());
  stochtex::render(model, stochtex::Grid{{0, 0}, 1.0, 64, 64}, /*seed=*/1, render.view());
  for (const float value : render.pixels())
    if (!std::isfinite(value)) return fail("the loaded model renders non-finite values");
  return 0;
}
