#include "methods/texton_mix/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <vector>

#include "core/colour_statistics.hpp"
#include "core/memory_budget.hpp"
#include "methods/texton/analysis.hpp"
#include "model/model_data.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::texton_mix {
namespace {

using Complex = std::complex<float>;
using Spectra = std::vector<std::vector<Complex>>;

// The centred width x height part of an image.
ImageView<const float> centre_crop(ImageView<const float> image, int width, int height) {
  return image.sub((image.width - width) / 2, (image.height - height) / 2, width, height);
}

std::vector<float> float_means(ImageView<const float> image) {
  std::vector<float> mean;
  for (const double value : channel_means(image)) mean.push_back(static_cast<float>(value));
  return mean;
}

// The lag-0 covariance sum_x tau(x) tau(x)^T of the kernel of DFT `spectrum`: the covariance of
// its Gaussian model, the target of the colour correction (row-major, channels x channels).
std::vector<double> kernel_covariance(const Fft2d& fft, const Spectra& spectrum) {
  const std::size_t channels = spectrum.size();
  std::vector<std::vector<float>> planes(channels, std::vector<float>(fft.image_size()));
  for (std::size_t c = 0; c < channels; ++c) fft.inverse(spectrum[c], planes[c]);
  std::vector<double> covariance(channels * channels, 0.0);
  for (std::size_t i = 0; i < channels; ++i)
    for (std::size_t j = 0; j < channels; ++j) {
      double sum = 0.0;
      for (std::size_t x = 0; x < fft.image_size(); ++x)
        sum += static_cast<double>(planes[i][x]) * planes[j][x];
      covariance[i * channels + j] = sum;
    }
  return covariance;
}

}  // namespace

TextonMixModel analyze(ImageView<const float> a, ImageView<const float> b, const Params& params,
                       MixField field, std::uint32_t seed) {
  const int width = std::min(a.width, b.width);
  const int height = std::min(a.height, b.height);
  const int channels = a.channels;
  // Preprocess as texton noise does (section 4.2): the periodic component, then
  // t = (p - mean(p)) / sqrt(|Omega|) (section 3.2).
  const ImageF periodic_a = periodic_component(centre_crop(a, width, height));
  const ImageF periodic_b = periodic_component(centre_crop(b, width, height));
  std::vector<float> mean_a = float_means(periodic_a.view());
  std::vector<float> mean_b = float_means(periodic_b.view());
  const Fft2d fft(width, height);
  const Spectra t_a = texton::normalised_kernel_spectrum(fft, periodic_a.view(), mean_a);
  const Spectra t_b = texton::normalised_kernel_spectrum(fft, periodic_b.view(), mean_b);

  // tau_0-hat = (t_A-hat* t_B-hat / |t_A-hat* t_B-hat|) t_A-hat: A's model with the phase that
  // aligns it with B (section 7, after [XFPA14]); * is the conjugate transpose over channels.
  Spectra tau_0 = t_a;
  for (std::size_t i = 0; i < fft.spectrum_size(); ++i) {
    Complex inner = 0.0f;
    for (int c = 0; c < channels; ++c) inner += std::conj(t_a[c][i]) * t_b[c][i];
    const float magnitude = std::abs(inner);
    const Complex phase = magnitude > 0.0f ? inner / magnitude : Complex(1.0f);
    for (int c = 0; c < channels; ++c) tau_0[c][i] = phase * t_a[c][i];
  }

  // tau_rho = (1 - rho) tau_0 + rho t_B, each through Algorithm 1 from the same initialisation.
  const int support = texton::texton_support(params.texton.support, width, height);
  std::vector<float> textons;
  textons.reserve(static_cast<std::size_t>(params.steps) * support * support * channels);
  Spectra tau(static_cast<std::size_t>(channels), std::vector<Complex>(fft.spectrum_size()));
  for (int step = 0; step < params.steps; ++step) {
    const float rho = static_cast<float>(step) / static_cast<float>(params.steps - 1);
    for (int c = 0; c < channels; ++c)
      for (std::size_t i = 0; i < fft.spectrum_size(); ++i)
        tau[c][i] = (1.0f - rho) * tau_0[c][i] + rho * t_b[c][i];
    const std::vector<double> target = kernel_covariance(fft, tau);
    const std::vector<float> coefficients =
        texton::texton_coefficients(fft, tau, target, params.texton, seed, false);
    textons.insert(textons.end(), coefficients.begin(), coefficients.end());
  }
  return TextonMixModel(params, channels, support, std::move(textons), std::move(mean_a),
                        std::move(mean_b), std::move(field));
}

}  // namespace stochtex::texton_mix

namespace stochtex {

Model mix(const MixInputs& inputs, const ParamValues& params, std::uint32_t seed) {
  using texton_mix::kFields;
  ParamValues resolved = resolve_params(texton_mix::TextonMixModel::kMethodName, params);
  const texton_mix::Params typed = params_from_values(kFields, resolved);
  const ImageView<const float> a = inputs.a;
  const ImageView<const float> b = inputs.b;
  check_memory_budget(
      mix_peak_bytes(std::min(a.width, b.width), std::min(a.height, b.height), a.channels,
                     typed.steps,
                     texton::texton_support(typed.texton.support, std::min(a.width, b.width),
                                            std::min(a.height, b.height))),
      "mixing the exemplars '" + inputs.a_name + "' and '" + inputs.b_name + "' into " +
          std::to_string(typed.steps) + " textons",
      "crop or downscale the exemplars, or lower --steps or -p support");
  validate_exemplar(a, inputs.a_name);
  validate_exemplar(b, inputs.b_name);
  if (a.channels != b.channels)
    throw Error(ErrorCode::invalid_input,
                "cannot mix '" + inputs.a_name + "' (" + std::to_string(a.channels) +
                    " channels) with '" + inputs.b_name + "' (" + std::to_string(b.channels) +
                    " channels); convert one so that both are grey or both colour");
  texton_mix::MixField field = [&] {
    if (!inputs.mask)
      return texton_mix::MixField(typed.ramp_start, typed.ramp_end, typed.direction_x,
                                  typed.direction_y);
    const ImageView<const float> mask = *inputs.mask;
    if (mask.channels != 1)
      throw Error(ErrorCode::invalid_input,
                  "the mask '" + inputs.mask_name + "' has " + std::to_string(mask.channels) +
                      " channels; give a grey image (black = the first exemplar, white = the "
                      "second)");
    std::vector<float> values;
    values.reserve(static_cast<std::size_t>(mask.width) * mask.height);
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) values.push_back(mask.at(x, y, 0));
    if (std::any_of(values.begin(), values.end(),
                    [](float v) { return !(v >= 0.0f && v <= 1.0f); }))
      throw Error(ErrorCode::invalid_input, "the mask '" + inputs.mask_name +
                                                "' has values outside [0, 1]; give an 8- or "
                                                "16-bit grey image");
    return texton_mix::MixField(std::move(values), mask.width, mask.height, typed.mask_scale);
  }();
  texton_mix::TextonMixModel model = [&] {
    try {
      return texton_mix::analyze(a, b, typed, std::move(field), seed);
    } catch (const Error& e) {
      throw Error(e.code(),
                  "cannot mix '" + inputs.a_name + "' and '" + inputs.b_name + "': " + e.what());
    }
  }();
  return assemble_model(std::move(resolved), std::move(model), {}, {});
}

}  // namespace stochtex
