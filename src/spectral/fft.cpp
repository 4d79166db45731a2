#include "spectral/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <mutex>
#include <new>
#include <stdexcept>

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

struct RowPrunedFft2d::Plans {
  float* real = nullptr;
  fftwf_complex* complex = nullptr;
  fftwf_plan rows_forward = nullptr;
  fftwf_plan columns_forward = nullptr;
  fftwf_plan columns_inverse = nullptr;
  fftwf_plan rows_inverse = nullptr;
  std::mutex mutex;

  ~Plans() {
    std::lock_guard lock(planner_mutex());
    for (fftwf_plan plan : {rows_forward, columns_forward, columns_inverse, rows_inverse})
      if (plan) fftwf_destroy_plan(plan);
    fftwf_free(real);
    fftwf_free(complex);
  }
};

RowPrunedFft2d::RowPrunedFft2d(int width, int height, int rows)
    : width_(width), height_(height), rows_(rows), plans_(new Plans) {
  if (rows < 1 || rows > height) throw std::invalid_argument("RowPrunedFft2d: rows out of range");
  plans_->real = fftwf_alloc_real(rows_size());
  plans_->complex = fftwf_alloc_complex(spectrum_size());
  if (!plans_->real || !plans_->complex) throw std::bad_alloc();
  std::lock_guard lock(planner_mutex());
  const int columns = spectrum_width();
  const int flags = FFTW_ESTIMATE | FFTW_DESTROY_INPUT;
  // Rows: `rows` real transforms of length width, one after the other in memory.
  plans_->rows_forward =
      fftwf_plan_many_dft_r2c(1, &width_, rows_, plans_->real, nullptr, 1, width_, plans_->complex,
                              nullptr, 1, columns, flags);
  plans_->rows_inverse = fftwf_plan_many_dft_c2r(1, &width_, rows_, plans_->complex, nullptr, 1,
                                                 columns, plans_->real, nullptr, 1, width_, flags);
  // Columns: `columns` complex transforms of length height, in place, stride = a row.
  plans_->columns_forward =
      fftwf_plan_many_dft(1, &height_, columns, plans_->complex, nullptr, columns, 1,
                          plans_->complex, nullptr, columns, 1, FFTW_FORWARD, flags);
  plans_->columns_inverse =
      fftwf_plan_many_dft(1, &height_, columns, plans_->complex, nullptr, columns, 1,
                          plans_->complex, nullptr, columns, 1, FFTW_BACKWARD, flags);
  if (!plans_->rows_forward || !plans_->rows_inverse || !plans_->columns_forward ||
      !plans_->columns_inverse)
    throw std::bad_alloc();
}

RowPrunedFft2d::~RowPrunedFft2d() = default;

void RowPrunedFft2d::forward(std::span<const float> in, std::span<std::complex<float>> out) const {
  std::lock_guard lock(plans_->mutex);
  std::copy_n(in.data(), rows_size(), plans_->real);
  fftwf_execute(plans_->rows_forward);
  // The row transforms of the zero rows are zero.
  auto* spectrum = reinterpret_cast<std::complex<float>*>(plans_->complex);
  std::fill(spectrum + static_cast<std::size_t>(rows_) * spectrum_width(),
            spectrum + spectrum_size(), std::complex<float>(0.0f));
  fftwf_execute(plans_->columns_forward);
  std::copy_n(spectrum, spectrum_size(), out.data());
}

void RowPrunedFft2d::inverse(std::span<const std::complex<float>> in, std::span<float> out) const {
  std::lock_guard lock(plans_->mutex);
  std::copy_n(in.data(), spectrum_size(), reinterpret_cast<std::complex<float>*>(plans_->complex));
  fftwf_execute(plans_->columns_inverse);
  fftwf_execute(plans_->rows_inverse);
  const float normalisation = 1.0f / (static_cast<float>(width_) * static_cast<float>(height_));
  for (std::size_t i = 0; i < rows_size(); ++i) out[i] = plans_->real[i] * normalisation;
}

}  // namespace stochtex
