#pragma once

#include <complex>
#include <cstdint>
#include <functional>
#include <span>
#include <type_traits>
#include <vector>

#include "methods/texton/model.hpp"
#include "methods/texton/params.hpp"
#include "spectral/fft.hpp"
#include "stochtex/image.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::texton {

// Algorithm 1 of the paper with the colour projection and colour covariance correction of
// section 4.3. `progress` (may be empty) is called after each iteration with the fraction done; an
// exception it throws stops the analysis (stochtex::analyze).
TextonModel analyze(ImageView<const float> exemplar, const Params& params, std::uint32_t seed,
                    const std::function<void(double)>& progress = {});

// The DFT of each channel of t_u = (p - mean) / sqrt(|Omega|) (section 3.2), p a periodic image of
// fft's size: the kernel whose Gaussian model Algorithm 1 approximates.
std::vector<std::vector<std::complex<float>>> normalised_kernel_spectrum(
    const Fft2d& fft, ImageView<const float> periodic, std::span<const float> mean);

// Algorithm 1 for the kernel of DFT `kernel_spectrum` (one per channel, fft's half spectrum), then
// the colour covariance correction towards `target` (channels x channels, row-major, the kernel's
// lag-0 covariance): the texton coefficients, S x S x channels with S = min(support, width,
// height). The white-noise initialisation depends on the seed and the size only, so kernels of
// one size share it (texton noise mixing, section 7). `progress` as analyze's. `fade_border`:
// where the support is the whole exemplar, also bring the texton to 0 over its outer eighth
// (analyze's textons; the mixing's interpolated kernels keep the paper's projection).
std::vector<float> texton_coefficients(
    const Fft2d& fft, std::vector<std::vector<std::complex<float>>> kernel_spectrum,
    std::span<const double> target, const Params& params, std::uint32_t seed, bool fade_border,
    const std::function<void(double)>& progress = {});

// This method's row of the registry (src/registry.cpp).
constexpr RegistryRow<Params, kFields.size()> registry_row(std::type_identity<TextonModel>) {
  return {
      "texton noise (Galerne, Leclaire, Moisan 2017): a small texton summarising the "
      "spectrum, ~30 fetches per sample",
      kFields,
      {.per_pixel = 28, .per_channel = 20},
      kMaxChannels};
}

}  // namespace stochtex::texton
