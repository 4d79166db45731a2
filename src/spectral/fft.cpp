#include "spectral/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <mutex>
#include <new>

namespace stochtex {
namespace {
// FFTW's planner is not thread-safe; execution of distinct plans is.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

struct Fft2d::Plans {
  float* real = nullptr;
  fftwf_complex* complex = nullptr;
  fftwf_plan forward = nullptr;
  fftwf_plan inverse = nullptr;
  std::mutex mutex;  // the buffers are shared by the calls on one object

  ~Plans() {
    std::lock_guard lock(planner_mutex());
    if (forward) fftwf_destroy_plan(forward);
    if (inverse) fftwf_destroy_plan(inverse);
    fftwf_free(real);
    fftwf_free(complex);
  }
};

Fft2d::Fft2d(int width, int height) : width_(width), height_(height), plans_(new Plans) {
  plans_->real = fftwf_alloc_real(image_size());
  plans_->complex = fftwf_alloc_complex(spectrum_size());
  if (!plans_->real || !plans_->complex) throw std::bad_alloc();
  std::lock_guard lock(planner_mutex());
  // FFTW takes sizes slowest-varying first: rows (height) then columns (width).
  plans_->forward = fftwf_plan_dft_r2c_2d(height_, width_, plans_->real, plans_->complex,
                                          FFTW_ESTIMATE | FFTW_DESTROY_INPUT);
  plans_->inverse = fftwf_plan_dft_c2r_2d(height_, width_, plans_->complex, plans_->real,
                                          FFTW_ESTIMATE | FFTW_DESTROY_INPUT);
  if (!plans_->forward || !plans_->inverse) throw std::bad_alloc();
}

Fft2d::~Fft2d() = default;

void Fft2d::forward(std::span<const float> in, std::span<std::complex<float>> out) const {
  std::lock_guard lock(plans_->mutex);
  std::copy(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(image_size()), plans_->real);
  fftwf_execute(plans_->forward);
  // std::complex<float> is layout-compatible with float[2] ([complex.numbers.general]).
  std::copy_n(reinterpret_cast<const std::complex<float>*>(plans_->complex), spectrum_size(),
              out.data());
}

void Fft2d::inverse(std::span<const std::complex<float>> in, std::span<float> out) const {
  std::lock_guard lock(plans_->mutex);
  std::copy_n(in.data(), spectrum_size(), reinterpret_cast<std::complex<float>*>(plans_->complex));
  fftwf_execute(plans_->inverse);
  const float normalisation = 1.0f / static_cast<float>(image_size());
  for (std::size_t i = 0; i < image_size(); ++i) out[i] = plans_->real[i] * normalisation;
}

}  // namespace stochtex
