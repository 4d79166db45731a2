#pragma once
// numpy arrays to and from the library's images, with the checks a Python caller meets as
// TypeError or ValueError (docs/python.md).

#include <pybind11/numpy.h>

#include <string>

#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::python {

// The size of an HxW or HxWxC array as an image, before any copy (a broadcast view claims any
// size without its memory): ValueError for another number of dimensions, more than
// `max_channels` channels, an empty array or more pixels than an image read from a file may have
// (ImageReadLimits); `what` names it in the error sentences.
struct ImageShape {
  int width = 0;
  int height = 0;
  int channels = 0;
};
ImageShape image_shape(const pybind11::array& array, const std::string& what,
                       int max_channels = kMaxImageChannels);

// An HxW or HxWxC array of uint8 (/255), uint16 (/65535) or float32, any strides, as an image:
// image_shape's checks, then TypeError for another dtype.
ImageF image_from_array(const pybind11::array& array, const std::string& what,
                        int max_channels = kMaxImageChannels);

// The image as a float32 HxWxC array that owns its pixels (no copy).
pybind11::array_t<float> to_array(ImageF&& image);

// A new float32 HxWxC array and the image view that writes into it.
struct OutputArray {
  pybind11::array_t<float> array;
  ImageView<float> view;
};
OutputArray output_array(int width, int height, int channels);

}  // namespace stochtex::python
