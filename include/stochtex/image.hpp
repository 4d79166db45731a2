#pragma once
// Images: float pixels, interleaved channels, row-major. `Image` owns its pixels; `ImageView` and
// `ConstImageView` are non-owning strided views (inputs are views, outputs are owned values).

#include <cstddef>
#include <span>
#include <vector>

namespace stochtex {

template <typename T>
struct ImageView {
  T* data = nullptr;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::ptrdiff_t row_stride = 0;  // elements between the starts of two consecutive rows

  T* row(int y) const { return data + y * row_stride; }
  T& at(int x, int y, int c) const { return data[y * row_stride + x * channels + c]; }
  // A rectangular sub-region sharing the same pixels.
  ImageView sub(int x0, int y0, int w, int h) const {
    return {data + y0 * row_stride + x0 * channels, w, h, channels, row_stride};
  }
  operator ImageView<const T>() const { return {data, width, height, channels, row_stride}; }
};

template <typename T>
class Image {
 public:
  Image() = default;
  Image(int width, int height, int channels, T fill = T{})
      : width_(width),
        height_(height),
        channels_(channels),
        pixels_(static_cast<std::size_t>(width) * height * channels, fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * height_; }
  bool empty() const { return pixels_.empty(); }

  T& at(int x, int y, int c) { return pixels_[index(x, y, c)]; }
  const T& at(int x, int y, int c) const { return pixels_[index(x, y, c)]; }
  std::span<T> pixels() { return pixels_; }
  std::span<const T> pixels() const { return pixels_; }

  ImageView<T> view() { return {pixels_.data(), width_, height_, channels_, row_stride()}; }
  ImageView<const T> view() const {
    return {pixels_.data(), width_, height_, channels_, row_stride()};
  }

 private:
  std::ptrdiff_t row_stride() const { return static_cast<std::ptrdiff_t>(width_) * channels_; }
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * width_ + x) * channels_ + c;
  }

  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  std::vector<T> pixels_;
};

using ImageF = Image<float>;

}  // namespace stochtex
