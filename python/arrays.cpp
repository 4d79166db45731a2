#include "arrays.hpp"

#include <cstdint>
#include <memory>
#include <utility>

#include "stochtex/io.hpp"

namespace py = pybind11;

namespace stochtex::python {
namespace {

// (The scales are those of the PNG reader, src/io/image_io.cpp, so an array read from a PNG
// analyses like the file.)
template <class T>
void copy_pixels(const py::array& array, ImageF& image, float range) {
  const auto* base = static_cast<const char*>(array.data());
  const py::ssize_t row_stride = array.strides(0);
  const py::ssize_t column_stride = array.strides(1);
  const py::ssize_t channel_stride = array.ndim() == 3 ? array.strides(2) : 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < image.channels(); ++c) {
        const char* element = base + y * row_stride + x * column_stride + c * channel_stride;
        const float value = static_cast<float>(*reinterpret_cast<const T*>(element));
        image.at(x, y, c) = range == 1.0f ? value : value / range;
      }
}

}  // namespace

ImageShape image_shape(const py::array& array, const std::string& what, int max_channels) {
  if (array.ndim() != 2 && array.ndim() != 3)
    throw py::value_error(what + " must be an HxW or HxWxC array, not one of " +
                          std::to_string(array.ndim()) + " dimensions");
  if (array.size() == 0) throw py::value_error(what + " is empty");
  const auto height = static_cast<int>(array.shape(0));
  const auto width = static_cast<int>(array.shape(1));
  const auto channels = array.ndim() == 3 ? static_cast<int>(array.shape(2)) : 1;
  if (array.ndim() == 3 && (channels < 1 || channels > max_channels))
    throw py::value_error(what + " has " + std::to_string(channels) +
                          " channels (its last axis); give 1 to " + std::to_string(max_channels));
  // The image reader's limit (io.hpp): a broadcast view can claim any size without its memory.
  const std::int64_t max_pixels = ImageReadLimits{}.max_pixels;
  if (array.shape(0) > max_pixels || array.shape(1) > max_pixels / array.shape(0))
    throw py::value_error(what + " is " + std::to_string(array.shape(1)) + "x" +
                          std::to_string(array.shape(0)) + " pixels, more than the " +
                          std::to_string(max_pixels) + " an image may have; use a smaller one");
  return {width, height, channels};
}

ImageF image_from_array(const py::array& array, const std::string& what, int max_channels) {
  const ImageShape shape = image_shape(array, what, max_channels);
  const bool bytes = py::isinstance<py::array_t<std::uint8_t>>(array);
  const bool words = py::isinstance<py::array_t<std::uint16_t>>(array);
  if (!bytes && !words && !py::isinstance<py::array_t<float>>(array))
    throw py::type_error(what + " must be a uint8, uint16 or float32 array, not " +
                         py::str(array.dtype()).cast<std::string>() +
                         " (convert it with .astype(numpy.float32))");
  ImageF image(shape.width, shape.height, shape.channels);
  if (bytes)
    copy_pixels<std::uint8_t>(array, image, 255.0f);
  else if (words)
    copy_pixels<std::uint16_t>(array, image, 65535.0f);
  else
    copy_pixels<float>(array, image, 1.0f);
  return image;
}

py::array_t<float> to_array(ImageF&& image) {
  auto owned = std::make_unique<ImageF>(std::move(image));
  const ImageF& pixels = *owned;
  const py::capsule base(owned.get(), [](void* pointer) { delete static_cast<ImageF*>(pointer); });
  owned.release();
  return py::array_t<float>({pixels.height(), pixels.width(), pixels.channels()},
                            pixels.pixels().data(), base);
}

OutputArray output_array(int width, int height, int channels) {
  py::array_t<float> array({height, width, channels});
  return {array,
          {array.mutable_data(), width, height, channels,
           static_cast<std::ptrdiff_t>(width) * channels}};
}

}  // namespace stochtex::python
