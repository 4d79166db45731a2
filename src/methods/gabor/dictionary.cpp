#include "methods/gabor/dictionary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "methods/gabor/model.hpp"

namespace stochtex::gabor {
namespace {

using Complex = std::complex<float>;
// The operators skip the bins where a band's kernel spectrum is below this fraction of its peak:
// the level of the single-precision FFT's own rounding error (~1e-7 log2 n of the peak), not a
// Gaussian's tail worth keeping. The fits change within the solver's tolerance (docs).
constexpr float kSupportThreshold = 1e-6f;

// Step of band b's sub-grid (section 5.3): about half the band's FWHM of 2^-b * size bins, so
// neighbouring Gaussians overlap at half height, and a power of two that divides the size so the
// band can be transformed on the coarse grid alone.
int grid_step(int size, int band) {
  const double target = std::ldexp(static_cast<double>(size), -band) / 2.0;
  int step = 1;
  while (2 * step <= target && size % (2 * step) == 0) step *= 2;
  return step;
}

// Calls visit(plane index, grid index) for every bin (i step_x, j step_y) of a sub-grid of the
// width x height plane, in the grid's row-major order.
template <typename Visit>
void for_each_grid_bin(int width, int height, int step_x, int step_y, Visit&& visit) {
  const int grid_width = width / step_x;
  for (int j = 0; j < height / step_y; ++j)
    for (int i = 0; i < grid_width; ++i)
      visit(static_cast<std::size_t>(j * step_y) * width + i * step_x,
            static_cast<std::size_t>(j) * grid_width + i);
}

}  // namespace

GaussianDictionary::GaussianDictionary(int width, int height, int narrowest)
    : width_(width), height_(height), fft_(std::make_unique<Fft2d>(width, height)) {
  const int longest = std::max(width, height);
  const std::size_t plane = plane_size();
  work_spectrum_.resize(fft_->spectrum_size());
  sum_spectrum_.resize(fft_->spectrum_size());
  // Band b has a FWHM of 2^-b cycles per pixel = 2^-b * size bins (section 4.3); the narrowest
  // band kept spans `narrowest` bins of the longer side (one: the paper's), band 0 always.
  for (int b = 0;
       b < kMaxBands && (b == 0 || std::ldexp(static_cast<double>(longest), -b) >= narrowest);
       ++b) {
    Band band;
    band.band = b;
    const double sigma = bandwidth(b) / (2.0 * std::sqrt(kPi));  // cycles per pixel (eq. 3)
    const int step_x = grid_step(width, b);
    const int step_y = grid_step(height, b);
    band.step_x = step_x;
    band.step_y = step_y;
    if (step_x > 1 || step_y > 1) {
      band.coarse_fft = std::make_unique<Fft2d>(width / step_x, height / step_y);
      band.coarse_spectrum.resize(band.coarse_fft->spectrum_size());
      band.coarse_row.resize(band.coarse_fft->image_size());
    }
    band.kernel.assign(plane, 0.0f);
    double squared = 0.0;
    for (int y = 0; y < height; ++y) {
      const int signed_y = y <= height / 2 ? y : y - height;
      for (int x = 0; x < width; ++x) {
        const int signed_x = x <= width / 2 ? x : x - width;
        double value = 0.0;
        for (int ky = -2; ky <= 2; ++ky)
          for (int kx = -2; kx <= 2; ++kx) {
            const double fx = (signed_x + kx * width) / static_cast<double>(width);
            const double fy = (signed_y + ky * height) / static_cast<double>(height);
            value += std::exp(-(fx * fx + fy * fy) / (2.0 * sigma * sigma));
          }
        band.kernel[static_cast<std::size_t>(y) * width + x] = static_cast<float>(value);
        squared += value * value;
      }
    }
    const double norm = std::sqrt(squared);
    band.mass = 0.0;
    for (float& v : band.kernel) {
      v = static_cast<float>(v / norm);
      band.mass += v;
    }
    fft_->forward(band.kernel, work_spectrum_);
    band.kernel_spectrum.resize(work_spectrum_.size());
    for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
      band.kernel_spectrum[i] = work_spectrum_[i].real();
    // Support of the kernel's spectrum: a Gaussian of sd ~2^b / (2 pi 0.42) bins for band b.
    const int half = fft_->spectrum_width();
    float peak = 0.0f;
    for (const float v : band.kernel_spectrum) peak = std::max(peak, std::abs(v));
    int reach_x = 0;
    int reach_y = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < half; ++x)
        if (std::abs(band.kernel_spectrum[static_cast<std::size_t>(y) * half + x]) >
            kSupportThreshold * peak) {
          reach_x = std::max(reach_x, x);
          reach_y = std::max(reach_y, std::min(y, height - y));
        }
    const int coarse_width = width / step_x;
    const int coarse_height = height / step_y;
    for (int y = 0; y < height; ++y)
      if (std::min(y, height - y) <= reach_y) {
        band.support_rows.push_back(y);
        band.support_coarse_rows.push_back(y % coarse_height);
      }
    for (int x = 0; x < width; ++x) {
      if (std::min(x, width - x) > reach_x) continue;
      std::vector<ColumnRun>& runs = x < half ? band.stored_runs : band.mirrored_runs;
      const int coarse_x = x % coarse_width;
      if (!runs.empty() && runs.back().column + runs.back().length == x &&
          runs.back().coarse_column + runs.back().length == coarse_x)
        ++runs.back().length;
      else
        runs.push_back({x, coarse_x, 1});
    }
    bands_.push_back(std::move(band));
  }
}

std::size_t GaussianDictionary::grid_size(int index) const {
  const Band& band = bands_[static_cast<std::size_t>(index)];
  return static_cast<std::size_t>(width_ / band.step_x) *
         static_cast<std::size_t>(height_ / band.step_y);
}

std::vector<std::vector<float>> GaussianDictionary::to_planes(
    const std::vector<std::vector<float>>& grids) const {
  std::vector<std::vector<float>> planes(bands_.size(), std::vector<float>(plane_size(), 0.0f));
  for (std::size_t b = 0; b < bands_.size(); ++b)
    for_each_grid_bin(width_, height_, bands_[b].step_x, bands_[b].step_y,
                      [&](std::size_t in_plane, std::size_t in_grid) {
                        planes[b][in_plane] = grids[b][in_grid];
                      });
  return planes;
}

std::vector<std::vector<float>> GaussianDictionary::to_grids(
    const std::vector<std::vector<float>>& planes) const {
  std::vector<std::vector<float>> grids(bands_.size());
  for (std::size_t b = 0; b < bands_.size(); ++b) {
    grids[b].resize(grid_size(static_cast<int>(b)));
    for_each_grid_bin(width_, height_, bands_[b].step_x, bands_[b].step_y,
                      [&](std::size_t in_plane, std::size_t in_grid) {
                        grids[b][in_grid] = planes[b][in_plane];
                      });
  }
  return grids;
}

void GaussianDictionary::apply(const std::vector<std::vector<float>>& alpha,
                               std::vector<float>& spectrum) const {
  apply_grid(to_grids(alpha), spectrum);
}

void GaussianDictionary::adjoint(std::span<const float> spectrum,
                                 std::vector<std::vector<float>>& out) const {
  std::vector<std::vector<float>> grids;
  adjoint_grid(spectrum, grids);
  out = to_planes(grids);
}

// A band on a sub-grid of steps (sx, sy) is an upsampled image of (W / sx) x (H / sy) values:
// its DFT is the coarse DFT repeated sx x sy times, and decimating a full image to the sub-grid
// folds its DFT onto the coarse one. So a sub-sampled band costs a coarse FFT, not a full one.
void GaussianDictionary::apply_grid(const std::vector<std::vector<float>>& coefficients,
                                    std::vector<float>& spectrum) const {
  std::fill(sum_spectrum_.begin(), sum_spectrum_.end(), Complex(0.0f, 0.0f));
  const int half = width_ / 2 + 1;
  for (std::size_t b = 0; b < bands_.size(); ++b) {
    const Band& band = bands_[b];
    const std::vector<float>& kernel = band.kernel_spectrum;
    if (!band.coarse_fft) {
      fft_->forward(coefficients[b], work_spectrum_);
      for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
        sum_spectrum_[i] += work_spectrum_[i] * kernel[i];
      continue;
    }
    const int coarse_width = width_ / band.step_x;
    const int coarse_height = height_ / band.step_y;
    const int coarse_half = coarse_width / 2 + 1;
    band.coarse_fft->forward(coefficients[b], band.coarse_spectrum);
    // The coarse DFT is Hermitian: its missing half comes from the conjugate at -k. Bin k of the
    // full spectrum reads coarse bin k mod (coarse size), tiled row by row without divisions.
    const std::size_t coarse_rows = static_cast<std::size_t>(coarse_height);
    std::vector<Complex>& row = band.coarse_row;
    for (std::size_t cy = 0; cy < coarse_rows; ++cy) {
      const std::size_t mirror_y = (coarse_rows - cy) % coarse_rows;
      for (int cx = 0; cx < coarse_width; ++cx)
        row[static_cast<std::size_t>(cy) * coarse_width + cx] =
            cx < coarse_half
                ? band.coarse_spectrum[cy * coarse_half + cx]
                : std::conj(band.coarse_spectrum[mirror_y * coarse_half + (coarse_width - cx)]);
    }
    // Only where the kernel's spectrum is not negligible. The complex values are read as
    // (real, imaginary) float pairs, so that a run is one loop the compiler can vectorise.
    for (std::size_t r = 0; r < band.support_rows.size(); ++r) {
      const float* coarse = reinterpret_cast<const float*>(
          &row[static_cast<std::size_t>(band.support_coarse_rows[r]) * coarse_width]);
      const std::size_t offset = static_cast<std::size_t>(band.support_rows[r]) * half;
      float* sum = reinterpret_cast<float*>(&sum_spectrum_[offset]);
      for (const ColumnRun& run : band.stored_runs) {
        float* __restrict into = sum + 2 * run.column;
        const float* __restrict in = coarse + 2 * run.coarse_column;
        const float* __restrict gain = &kernel[offset + run.column];
        for (int i = 0; i < run.length; ++i) {
          into[2 * i] += in[2 * i] * gain[i];
          into[2 * i + 1] += in[2 * i + 1] * gain[i];
        }
      }
    }
  }
  spectrum.resize(plane_size());
  fft_->inverse(sum_spectrum_, spectrum);
  if (!weights_.empty())
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= weights_[i];
}

void GaussianDictionary::adjoint_grid(std::span<const float> spectrum,
                                      std::vector<std::vector<float>>& out) const {
  // The kernels are even, so the adjoint of a convolution by them is the same convolution.
  if (weights_.empty()) {
    fft_->forward(spectrum, sum_spectrum_);
  } else {
    weighted_.resize(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) weighted_[i] = spectrum[i] * weights_[i];
    fft_->forward(weighted_, sum_spectrum_);
  }
  out.resize(bands_.size());
  const int half = width_ / 2 + 1;
  for (std::size_t b = 0; b < bands_.size(); ++b) {
    const Band& band = bands_[b];
    const std::vector<float>& kernel = band.kernel_spectrum;
    out[b].resize(grid_size(static_cast<int>(b)));
    if (!band.coarse_fft) {
      for (std::size_t i = 0; i < work_spectrum_.size(); ++i)
        work_spectrum_[i] = sum_spectrum_[i] * kernel[i];
      fft_->inverse(work_spectrum_, out[b]);
      continue;
    }
    const int coarse_width = width_ / band.step_x;
    const int coarse_height = height_ / band.step_y;
    const int coarse_half = coarse_width / 2 + 1;
    // Fold the product onto the coarse spectrum: every full bin k adds to coarse bin
    // k mod (coarse size); bins where the kernel's spectrum is negligible are skipped. The full
    // spectrum's missing half is the conjugate at -k (the kernel is even and real).
    // As float pairs, run by run (apply); the runs of the other half-plane read their bins
    // backwards from the stored conjugates.
    std::vector<Complex>& row = band.coarse_row;
    std::fill(row.begin(), row.end(), Complex(0.0f, 0.0f));
    const auto* sum = reinterpret_cast<const float*>(sum_spectrum_.data());
    for (std::size_t r = 0; r < band.support_rows.size(); ++r) {
      const int ky = band.support_rows[r];
      auto* coarse = reinterpret_cast<float*>(
          &row[static_cast<std::size_t>(band.support_coarse_rows[r]) * coarse_width]);
      const std::size_t offset = static_cast<std::size_t>(ky) * half;
      const std::size_t mirror = static_cast<std::size_t>((height_ - ky) % height_) * half;
      for (const ColumnRun& run : band.stored_runs) {
        float* __restrict into = coarse + 2 * run.coarse_column;
        const float* __restrict in = sum + 2 * (offset + run.column);
        const float* __restrict gain = &kernel[offset + run.column];
        for (int i = 0; i < run.length; ++i) {
          into[2 * i] += in[2 * i] * gain[i];
          into[2 * i + 1] += in[2 * i + 1] * gain[i];
        }
      }
      for (const ColumnRun& run : band.mirrored_runs) {
        // Bin x reads the conjugate at mirror + width - x: i steps backwards through it.
        const std::size_t first = mirror + static_cast<std::size_t>(width_ - run.column);
        float* __restrict into = coarse + 2 * run.coarse_column;
        const float* __restrict in = sum + 2 * first;
        const float* __restrict gain = &kernel[first];
        for (int i = 0; i < run.length; ++i) {
          into[2 * i] += in[-2 * i] * gain[-i];
          into[2 * i + 1] += -in[-2 * i + 1] * gain[-i];
        }
      }
    }
    for (int cy = 0; cy < coarse_height; ++cy)
      for (int cx = 0; cx < coarse_half; ++cx)
        band.coarse_spectrum[static_cast<std::size_t>(cy) * coarse_half + cx] =
            row[static_cast<std::size_t>(cy) * coarse_width + cx];
    // Decimation keeps 1 / (sx sy) of the samples; Fft2d::inverse divides by the coarse size.
    const auto fold = static_cast<float>(1.0 / (band.step_x * band.step_y));
    for (Complex& value : band.coarse_spectrum) value *= fold;
    band.coarse_fft->inverse(band.coarse_spectrum, out[b]);
  }
}

}  // namespace stochtex::gabor
