#pragma once
// 2-D real FFT of one image channel (FFTW, single precision). Plans are made with FFTW_ESTIMATE so
// the same input gives the same bytes on every run (FFTW_MEASURE may pick other algorithms).
// Spectra are half-planes: (width / 2 + 1) x height complex values, row-major.

#include <complex>
#include <memory>
#include <span>

namespace stochtex {

class Fft2d {
 public:
  Fft2d(int width, int height);
  ~Fft2d();
  Fft2d(const Fft2d&) = delete;
  Fft2d& operator=(const Fft2d&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int spectrum_width() const { return width_ / 2 + 1; }
  std::size_t spectrum_size() const { return static_cast<std::size_t>(spectrum_width()) * height_; }
  std::size_t image_size() const { return static_cast<std::size_t>(width_) * height_; }

  // Unnormalised forward transform: out(k) = sum_x in(x) exp(-2 i pi <k, x / size>).
  void forward(std::span<const float> in, std::span<std::complex<float>> out) const;
  // Inverse transform divided by width * height, so inverse(forward(x)) == x.
  void inverse(std::span<const std::complex<float>> in, std::span<float> out) const;

 private:
  struct Plans;
  int width_;
  int height_;
  std::unique_ptr<Plans> plans_;
};

// The same transforms for images that are zero outside their first `rows` rows (the texton
// coefficients of Algorithm 1 live in a small square). Rows that are known to be zero are not
// transformed (forward), and rows that are not wanted are not computed (inverse): the row pass
// costs rows / height of a full transform. Images are passed as their first `rows` rows only.
class RowPrunedFft2d {
 public:
  RowPrunedFft2d(int width, int height, int rows);
  ~RowPrunedFft2d();
  RowPrunedFft2d(const RowPrunedFft2d&) = delete;
  RowPrunedFft2d& operator=(const RowPrunedFft2d&) = delete;

  int spectrum_width() const { return width_ / 2 + 1; }
  std::size_t spectrum_size() const { return static_cast<std::size_t>(spectrum_width()) * height_; }
  std::size_t rows_size() const { return static_cast<std::size_t>(width_) * rows_; }

  // in: rows x width values (the image's nonzero rows); out: the full half-plane spectrum.
  void forward(std::span<const float> in, std::span<std::complex<float>> out) const;
  // The first `rows` rows of the inverse transform divided by width * height.
  void inverse(std::span<const std::complex<float>> in, std::span<float> out) const;

 private:
  struct Plans;
  int width_;
  int height_;
  int rows_;
  std::unique_ptr<Plans> plans_;
};

}  // namespace stochtex
