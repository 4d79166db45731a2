// The compiled half of the Python module (`stochtex._stochtex`, re-exported by
// python/stochtex/__init__.py; docs/python.md). Every long call releases the GIL; its progress
// hook takes the GIL back to check for Ctrl-C and call the user's callback.

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <charconv>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "core/memory_budget.hpp"
#include "model/map_layout.hpp"
#include "model/model_colour.hpp"
#include "registry.hpp"
#include "renderer/plan.hpp"
#include "renderer/render_file.hpp"
#include "report/compare.hpp"
#include "stochtex/io.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"

namespace py = pybind11;

namespace stochtex::python {
namespace {

py::object parse_json(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// A progress hook for a call that runs with the GIL released, from the calling thread: it takes
// the GIL, raises KeyboardInterrupt (or what a signal handler raises) on Ctrl-C, calls `callback`
// (None: none) and throws what either raises, which stops the call. After that it does nothing.
std::function<void(double)> progress_hook(const py::object& callback) {
  auto stopped = std::make_shared<bool>(false);
  return [callback, stopped](double fraction) {
    if (*stopped) return;
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback.is_none()) callback(fraction);
    } catch (...) {
      *stopped = true;
      throw;
    }
  };
}

// A double as the shortest text that reads back as it.
std::string number_text(double value) {
  std::array<char, 32> buffer{};
  return {buffer.data(), std::to_chars(buffer.data(), buffer.data() + buffer.size(), value).ptr};
}

// Keyword parameters as the CLI's -p values: numbers (written exactly, shortest round trip) or a
// choice's name.
std::map<std::string, std::string, std::less<>> text_params(const py::kwargs& params) {
  std::map<std::string, std::string, std::less<>> text;
  for (const auto& [key, value] : params) {
    const auto name = key.cast<std::string>();
    if (py::isinstance<py::str>(value)) {
      text[name] = value.cast<std::string>();
    } else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
      text[name] = number_text(value.cast<double>());
    } else {
      throw py::type_error("parameter " + name + " must be a number or a choice's name, not " +
                           py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    }
  }
  return text;
}

ImageF exemplar_from_array(const py::array& array, const std::string& what) {
  ImageF image = image_from_array(array, what);
  validate_exemplar(image.view(), what);
  return image;
}

// The colour space named `name` for a Python keyword, or a ValueError naming `what`.
ColourSpace colour_space_argument(const std::string& name, const char* what) {
  const auto space = colour_space_from_name(name);
  if (!space)
    throw py::value_error(std::string(what) + " must be 'data', 'linear' or 'srgb', not '" + name +
                          "'");
  return *space;
}

Model analyze_array(const py::array& array, const std::string& method, std::uint32_t seed,
                    const py::object& progress, const std::string& colour,
                    const py::kwargs& params) {
  const ColourSpace space = colour_space_argument(colour, "colour");
  const ParamValues values = resolve_params(method, text_params(params));
  const ImageShape shape = image_shape(array, "the exemplar array");
  check_analysis_request(method, shape.width, shape.height, shape.channels, "the exemplar array");
  const ImageF exemplar = image_from_array(array, "the exemplar array");
  const auto hook = progress_hook(progress);
  py::gil_scoped_release release;
  return analyze(method, exemplar.view(), values, seed, "the exemplar array", hook, space);
}

// analyze_material of a dict {name: array} (insertion order = channel order); `kinds` gives a
// map's kind by name where its name does not imply it.
Model analyze_maps(const py::dict& arrays, const std::string& method, std::uint32_t seed,
                   const py::dict& kinds, const std::string& normal_y, const py::object& progress,
                   const std::string& colour, const py::kwargs& params) {
  const ParamValues values = resolve_params(method, text_params(params));
  const ColourSpace colour_space = colour_space_argument(colour, "colour");
  if (normal_y != "up" && normal_y != "down")
    throw py::value_error("normal_y must be 'up' or 'down', not '" + normal_y + "'");
  // The copies of the arrays held at once, as `stochtex analyze --map` reads the files.
  std::vector<std::string> names;
  std::vector<py::array> given;
  HeldImages held;
  for (const auto& [key, value] : arrays) {
    names.push_back(key.cast<std::string>());
    given.push_back(value.cast<py::array>());
    const ImageShape shape = image_shape(given.back(), "the map '" + names.back() + "'");
    held.add(shape.width, shape.height, shape.channels, names.back() + " array");
  }
  std::vector<ImageF> images;
  for (std::size_t i = 0; i < names.size(); ++i)
    images.push_back(image_from_array(given[i], "the map '" + names[i] + "'"));
  std::vector<MaterialMap> maps;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::optional<MapKind> kind;
    if (kinds.contains(names[i])) {
      const auto kind_name = kinds[py::str(names[i])].cast<std::string>();
      kind = map_kind_from_name(kind_name);
      if (!kind)
        throw py::value_error("the kind '" + kind_name + "' of map '" + names[i] +
                              "' is not one of colour, normal, height, scalar");
    }
    // Colour maps (albedo, base colour, emission) in `colour`; every other kind is data.
    const bool colour_map = kind.value_or(default_map_kind(names[i])) == MapKind::colour;
    maps.push_back({names[i], kind, images[i].view(), names[i] + " array",
                    colour_map ? colour_space : ColourSpace::data});
  }
  const auto hook = progress_hook(progress);
  py::gil_scoped_release release;
  return analyze_material(method, maps, values, seed, {.normal_y_down = normal_y == "down"}, hook);
}

py::list map_list(const Model& model) {
  py::list maps;
  for (const MapInfo& map : model.maps()) {
    py::dict entry(py::arg("name") = map.name,
                   py::arg("kind") = std::string(map_kind_name(map.kind)),
                   py::arg("channels") = map.channels,
                   py::arg("colour_space") = std::string(colour_space_name(map.colour_space)));
    if (!map.derived_from.empty()) {
      entry["from"] = map.derived_from;
      entry["scale"] = map.slope_scale;
    }
    maps.append(entry);
  }
  return maps;
}

py::dict split_image(const Model& model, const py::array& image) {
  const ImageShape shape = image_shape(image, "the image array", kMaxChannels);
  if (shape.channels != model.channels())
    throw py::value_error("the image has " + std::to_string(shape.channels) +
                          " channels and the model " + std::to_string(model.channels()));
  check_memory_budget(renderer::maps_peak_bytes(model, shape.width, shape.height, false),
                      "splitting a " + std::to_string(shape.width) + "x" +
                          std::to_string(shape.height) + " image into the model's maps",
                      "split it in pieces");
  const ImageF rendered = image_from_array(image, "the image array", kMaxChannels);
  py::dict maps;
  for (auto& [name, map] : split_maps(model, rendered.view()))
    maps[py::str(name)] = to_array(std::move(map));
  return maps;
}

// A render request: its grid and its render options (threads).
struct RenderJob {
  Grid grid;
  RenderOptions options;
};

// The width and height of an image held in memory: refused, as `stochtex render` and `stochtex
// gaussian` refuse them, beyond renderer::fits_in_memory; `after` ends the sentence.
void check_in_memory_size(int width, int height, const std::string& what,
                          const std::string& after) {
  if (width < 1 || height < 1 || !renderer::fits_in_memory(width, height))
    throw py::value_error(what + "'s width and height must each be 1 to " +
                          std::to_string(renderer::kMaxInMemorySide) + ", and at most " +
                          std::to_string(renderer::kMaxInMemoryPixels) + " pixels together, not " +
                          std::to_string(width) + "x" + std::to_string(height) + after);
}

// A render request checked as `stochtex render` checks it: sizes, scale, threads, positions and
// the memory budget, within which threads=0 takes as many cores as fit
// (renderer::budgeted_threads, docs/design.md §9; a larger image is rendered in pieces with
// offset, or as a dask array, whose chunks each stay within it).
// The period of `periodic` (render's argument): none for False or None, the render's own width x
// height for True, or the whole image's (width, height) in output pixels (a chunk of it), times
// scale.
std::optional<Vec2d> periodic_period(const py::object& periodic, int width, int height,
                                     double scale) {
  if (periodic.is_none()) return std::nullopt;
  if (py::isinstance<py::bool_>(periodic)) {
    if (!periodic.cast<bool>()) return std::nullopt;
    return Vec2d{width * scale, height * scale};
  }
  const auto whole = periodic.cast<std::array<std::int64_t, 2>>();
  if (whole[0] < 1 || whole[1] < 1)
    throw py::value_error(
        "periodic must be True, False or the whole image's (width, height) in "
        "pixels, each at least 1");
  return Vec2d{static_cast<double>(whole[0]) * scale, static_cast<double>(whole[1]) * scale};
}

RenderJob checked_render(int width, int height, int channels, std::array<double, 2> origin,
                         double scale, int threads, std::array<std::int64_t, 2> offset,
                         const py::object& periodic = py::none()) {
  check_in_memory_size(
      width, height, "render",
      " (render a larger image in pieces with offset, or with stochtex.dask.render)");
  if (!(scale >= renderer::kMinScale && scale <= renderer::kMaxScale))
    throw py::value_error("scale must be " + number_text(renderer::kMinScale) + " to " +
                          number_text(renderer::kMaxScale) +
                          " exemplar pixels per output pixel, not " + number_text(scale));
  if (threads < 0 || threads > kMaxThreads)
    throw py::value_error("threads must be 0 (all) to " + std::to_string(kMaxThreads));
  RenderJob job;
  job.grid = {{origin[0], origin[1]}, scale, width, height, offset[0], offset[1]};
  check_grid(job.grid, "render's grid");
  // render() refuses a model that cannot be periodic (periodic_refusal) as a ValueError.
  job.options.period = periodic_period(periodic, width, height, scale);
  job.options.threads = renderer::budgeted_threads(
      width, height, job.options.tile_size, job.options.supersample, threads,
      [&](int) {
        return "rendering " + std::to_string(width) + "x" + std::to_string(height) + " pixels";
      },
      "render it in pieces with offset, or with stochtex.dask.render", channels);
  return job;
}

py::dict render_material(const Model& model, int width, int height, std::array<double, 2> origin,
                         double scale, std::uint32_t seed, int threads,
                         std::array<std::int64_t, 2> offset, bool encoded,
                         const py::object& periodic) {
  const RenderJob job =
      checked_render(width, height, model.channels(), origin, scale, threads, offset, periodic);
  check_memory_budget(
      renderer::maps_peak_bytes(model, width, height, false),
      "rendering the maps of " + std::to_string(width) + "x" + std::to_string(height) + " pixels",
      "render it in pieces with offset, or with stochtex.dask.render_maps");
  std::vector<NamedImage> maps;
  {
    py::gil_scoped_release release;
    maps = render_maps(model, job.grid, [&](const Grid& part, ImageView<float> out) {
      render(model, part, seed, out, job.options);
    });
    // A colour map's linear light back to sRGB-encoded values, as its PNG holds them.
    if (encoded)
      for (NamedImage& map : maps)
        for (const MapInfo& info : model.maps())
          if (info.name == map.name && info.colour_space != ColourSpace::data)
            encode_colour_channels(map.image.view());
  }
  py::dict result;
  for (auto& [name, map] : maps) result[py::str(name)] = to_array(std::move(map));
  return result;
}

py::array_t<float> render_model(const Model& model, int width, int height,
                                std::array<double, 2> origin, double scale, std::uint32_t seed,
                                int threads, std::array<std::int64_t, 2> offset,
                                const py::object& progress, bool encoded,
                                const py::object& periodic) {
  RenderJob job =
      checked_render(width, height, model.channels(), origin, scale, threads, offset, periodic);
  OutputArray output = output_array(width, height, model.channels());
  job.options.progress = progress_hook(progress);
  py::gil_scoped_release release;
  render(model, job.grid, seed, output.view, job.options);
  // Linear light back to sRGB-encoded values, as a PNG output holds them.
  if (encoded && model.maps().empty() && model.colour_space() != ColourSpace::data)
    encode_colour_channels(output.view);
  return output.array;
}

// evaluate of any array-like points (and footprints), their shapes and the memory budget checked
// before anything proportional to them is copied or converted.
py::array_t<float> evaluate_model(const Model& model, const py::object& points_given,
                                  const py::object& footprints_given, std::uint32_t seed) {
  const py::array points = py::array::ensure(points_given);
  if (!points || points.ndim() != 2 || points.shape(1) != 2)
    throw py::value_error("points must be an Nx2 array of positions");
  const py::ssize_t rows = points.shape(0);
  const bool filtered = !footprints_given.is_none();
  const py::array footprints = filtered ? py::array::ensure(footprints_given) : py::array();
  if (filtered && (!footprints || footprints.ndim() != 3 || footprints.shape(0) != rows ||
                   footprints.shape(1) != 2 || footprints.shape(2) != 2))
    throw py::value_error("footprints must be an Nx2x2 array (dpdx, dpdy of each point)");
  const int channels = model.channels();
  const auto count = static_cast<std::size_t>(rows);
  check_memory_budget(evaluate_peak_bytes(count, channels),
                      "evaluating " + std::to_string(count) + " points",
                      "evaluate fewer at a time");
  const auto as_doubles = [](const py::array& array, const char* what) {
    auto doubles = py::array_t<double, py::array::forcecast>::ensure(array);
    if (!doubles) throw py::type_error(std::string(what) + " must be an array of numbers");
    return doubles;
  };
  std::vector<Vec2d> positions(count);
  const auto p = as_doubles(points, "points").unchecked<2>();
  for (std::size_t i = 0; i < count; ++i) positions[i] = {p(i, 0), p(i, 1)};
  std::vector<Footprint> areas;
  if (filtered) {
    const auto v = as_doubles(footprints, "footprints").unchecked<3>();
    for (std::size_t i = 0; i < count; ++i)
      areas.push_back({{v(i, 0, 0), v(i, 0, 1)}, {v(i, 1, 0), v(i, 1, 1)}});
  }
  py::array_t<float> values({rows, static_cast<py::ssize_t>(channels)});
  const ImageView<float> out{values.mutable_data(), 1, static_cast<int>(rows), channels, channels};
  py::gil_scoped_release release;
  evaluate(model, positions, areas, seed, out);
  return values;
}

py::bytes model_bytes(const Model& model) {
  const std::vector<std::uint8_t> bytes = serialize_model(model);
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

Model model_from_bytes(const py::bytes& data) {
  const std::string_view bytes = data;
  return deserialize_model({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()},
                           "the pickled model");
}

// The model a Model object holds; nullptr for one made by Model.__new__ alone (unpickling makes
// one, then __setstate__ fills it), whose C++ model pybind11 never constructed.
std::shared_ptr<const Model> held_model(const py::handle& self) {
  try {
    return self.cast<std::shared_ptr<Model>>();
  } catch (const py::cast_error&) {
    return nullptr;
  }
}

// The model of a Model method's `self`, which pybind11 would otherwise read as a model whether
// or not it holds one.
const Model& model_of(const py::handle& self) {
  if (!py::isinstance<Model>(self))
    throw py::type_error("a stochtex.Model's method was called on an object of type " +
                         py::str(py::type::of(self).attr("__name__")).cast<std::string>() +
                         "; call it on a stochtex.Model");
  const std::shared_ptr<const Model> model = held_model(self);
  if (!model)
    throw std::runtime_error(
        "this stochtex.Model was not initialised (Model.__new__ alone makes an empty one); load "
        "one with stochtex.load or make one with stochtex.analyze");
  return *model;
}

// `function` as a method of Model whose `self` is checked by model_of before it is read (the
// object keeps the model alive meanwhile).
template <class Result, class... Args>
auto method(Result (*function)(const Model&, Args...)) {
  return [function](const py::object& self, Args... args) {
    return function(model_of(self), std::forward<Args>(args)...);
  };
}

std::string model_repr(const py::object& self) {
  const std::shared_ptr<const Model> model = held_model(self);
  if (!model) return "<stochtex.Model, not initialised>";
  return "<stochtex.Model " + std::string(model->method()) + ", " +
         std::to_string(model->channels()) + " channels>";
}

// pickle (every protocol), copy.copy and copy.deepcopy: copyreg.__newobj__(type(self)), then
// __setstate__ with the model's file bytes, as protocol 2 and above reduce it by themselves (the
// same pickles); object's own reduction at protocols 0 and 1 would call the pybind11 base class,
// which aborts the interpreter.
py::tuple reduce_model(const py::object& self) {
  return py::make_tuple(py::module_::import("copyreg").attr("__newobj__"),
                        py::make_tuple(py::type::of(self)), self.attr("__getstate__")());
}

}  // namespace
}  // namespace stochtex::python

PYBIND11_MODULE(_stochtex, m) {
  using namespace stochtex;
  using namespace stochtex::python;
  m.doc() = "Procedural texture synthesis by example (docs/python.md).";
  // stochtex::Error: OSError for files that cannot be opened, read or written, ValueError for the
  // rest (bad data, formats); std::invalid_argument is pybind11's ValueError already.
  py::register_exception_translator([](std::exception_ptr failure) {
    try {
      if (failure) std::rethrow_exception(failure);
    } catch (const Error& e) {
      PyErr_SetString(e.code() == ErrorCode::io ? PyExc_OSError : PyExc_ValueError, e.what());
    }
  });

  py::class_<Model, std::shared_ptr<Model>>(m, "Model",
                                            "A texture model: analysed, loaded or unpickled.")
      .def_property_readonly(
          "method", method(+[](const Model& model) { return std::string(model.method()); }))
      .def_property_readonly("channels",
                             method(+[](const Model& model) { return model.channels(); }))
      .def_property_readonly(
          "colour_space", method(+[](const Model& model) {
            return std::string(colour_space_name(model.colour_space()));
          }),
          "What the exemplar's values were (docs/design.md §14): 'data' (rendered as they are), "
          "'linear' or 'srgb' (rendered as linear light); a material's maps each have theirs.")
      .def_property_readonly("maps", method(&map_list),
                             "A material's maps in channel order, each {name, kind, channels} "
                             "(and from, scale for a normal map derived from a height map); "
                             "empty for a model of one image.")
      .def("render_maps", method(&render_material), py::arg("width"), py::arg("height"),
           py::arg("origin") = std::array<double, 2>{0.0, 0.0}, py::arg("scale") = 1.0,
           py::arg("seed") = 0, py::arg("threads") = 0,
           py::arg("offset") = std::array<std::int64_t, 2>{0, 0}, py::arg("encoded") = false,
           py::arg("periodic") = false,
           "A material's maps of the render's grid, {name: HxWxC array} (a derived normal map "
           "from the height around each pixel); render's arguments. A colour map of srgb or "
           "linear colour is linear light, or with encoded=True sRGB-encoded as its PNG holds it.")
      .def("split", method(&split_image), py::arg("image"),
           "A render of a material cut into its maps: {name: HxWxC array}, a normal map as "
           "unit normals encoded 0.5 + 0.5 n (stochtex.split_maps).")
      .def_property_readonly(
          "info", method(+[](const Model& model) { return parse_json(describe_model(model)); }),
          "The model's description (stochtex info --json): method, parameters, array sizes.")
      .def("render", method(&render_model), py::arg("width"), py::arg("height"),
           py::arg("origin") = std::array<double, 2>{0.0, 0.0}, py::arg("scale") = 1.0,
           py::arg("seed") = 0, py::arg("threads") = 0,
           py::arg("offset") = std::array<std::int64_t, 2>{0, 0}, py::arg("progress") = py::none(),
           py::arg("encoded") = false, py::arg("periodic") = false,
           "A height x width x channels float32 image: pixel (i, j) samples origin + scale * "
           "(offset + (i, j) + 1/2), so a chunk rendered with offset equals the same pixels of "
           "the whole render, bit for bit. A srgb or linear model renders linear light (each "
           "pixel the mean of the colour over its footprint); encoded=True gives its colour "
           "channels sRGB-encoded, as a PNG holds them. periodic=True: a tileable bake, the "
           "texture repeats with this width x height (docs/render.md); a chunk of a larger "
           "tileable image passes the whole image's (width, height) instead.")
      .def("evaluate", method(&evaluate_model), py::arg("points"),
           py::arg("footprints") = py::none(), py::arg("seed") = 0,
           "The model at N positions (Nx2, exemplar pixels), with optional Nx2x2 footprints "
           "(dpdx, dpdy): an N x channels float32 array.")
      .def("save", method(+[](const Model& model, const std::filesystem::path& path) {
             save_model(model, path);
           }),
           py::arg("path"))
      .def("__repr__", &model_repr)
      .def(py::pickle(method(&model_bytes), &model_from_bytes))
      .def("__reduce__", &reduce_model);

  m.def("analyze", &analyze_array, py::arg("array"), py::arg("method"), py::arg("seed") = 0,
        py::arg("progress") = py::none(), py::arg("colour") = "data",
        "Analyses an HxW or HxWxC exemplar (uint8, uint16 or float32) with a method; keyword "
        "arguments are its parameters (numbers or a choice's name). colour says what its values "
        "are: 'data' (as they are, the default), 'srgb' (an ordinary photo: the model renders "
        "linear light) or 'linear'.");
  m.def("analyze_material", &analyze_maps, py::arg("maps"), py::arg("method"), py::arg("seed") = 0,
        py::arg("kinds") = py::dict(), py::arg("normal_y") = "up", py::arg("progress") = py::none(),
        py::arg("colour") = "srgb",
        "Analyses a material: maps is a dict {name: HxW or HxWxC array} of aligned maps, in "
        "channel order (docs/materials.md); kinds {name: 'colour' | 'normal' | 'height' | "
        "'scalar'} where the name does not imply it; normal_y 'down' for DirectX normal maps. "
        "colour is what the colour maps' values are: 'srgb' (the convention for an albedo, the "
        "default: render_maps returns its linear light), 'linear' or 'data'; the other maps are "
        "data.");
  m.def(
      "load", [](const std::filesystem::path& path) { return load_model(path); }, py::arg("path"));
  m.def(
      "read_image",
      [](const std::filesystem::path& path) {
        ImageF image = [&] {
          py::gil_scoped_release release;
          return read_image(path);
        }();
        return to_array(std::move(image));
      },
      py::arg("path"),
      "The image file at path (PNG, JPEG, TIFF, WebP, TGA, OpenEXR or PFM) as `stochtex analyze` "
      "reads it: a float32 HxWxC array, 8- and 16-bit values divided by 255 or 65535 as stored.");
  m.def(
      "write_image",
      [](const std::filesystem::path& path, const py::array& image, int bit_depth,
         const std::string& colour) {
        const ColourSpace space = colour_space_argument(colour, "colour");
        const ImageF copy = image_from_array(image, "the image array");
        py::gil_scoped_release release;
        write_image(path, copy.view(), bit_depth, space);
      },
      py::arg("path"), py::arg("image"), py::arg("bit_depth") = 8, py::arg("colour") = "data",
      "Writes an HxW or HxWxC array as `stochtex render` writes an image: PNG (8 or 16 bits, "
      "values clamped to 0..1), OpenEXR or PFM by the extension; never a partial file. colour "
      "says what its values are: 'data' (written as they are), 'linear' (a render of a srgb "
      "model: a PNG encodes it, with an sRGB chunk) or 'srgb' (encoded: OpenEXR and PFM decode "
      "it).");
  m.def(
      "methods", [] { return parse_json(methods_json()); },
      "Every method with its parameters: names, defaults, ranges, help, choices.");
  m.def(
      "compare",
      [](const py::array& exemplar, const py::object& images) {
        // One array, or a list of renders of one model with different seeds.
        std::vector<py::array> arrays;
        if (py::isinstance<py::array>(images))
          arrays.push_back(images.cast<py::array>());
        else
          for (const py::handle item : images) arrays.push_back(py::cast<py::array>(item));
        if (arrays.empty()) throw py::value_error("compare needs at least one image array");
        const auto name = [&](std::size_t i) {
          return arrays.size() == 1 ? std::string("the image array")
                                    : "image array " + std::to_string(i);
        };
        // Every request checked before any copy; then one image in memory at a time, as
        // `stochtex compare` reads them.
        const ImageShape reference_shape = image_shape(exemplar, "the exemplar array");
        for (std::size_t i = 0; i < arrays.size(); ++i) {
          const ImageShape shape = image_shape(arrays[i], name(i));
          check_compare_budget(reference_shape.width, reference_shape.height, shape.width,
                               shape.height, shape.channels);
        }
        const ImageF reference = exemplar_from_array(exemplar, "the exemplar array");
        Comparison comparison(reference.view());
        for (std::size_t i = 0; i < arrays.size(); ++i) {
          const ImageF synthesis = image_from_array(arrays[i], name(i));
          py::gil_scoped_release release;
          add_checked(comparison, reference.view(), "the exemplar array", synthesis.view(),
                      name(i));
        }
        return parse_json(comparison_json(comparison.report()).dump());
      },
      py::arg("exemplar"), py::arg("image"),
      "The measures of `stochtex compare --json` for an image against its exemplar; a list of "
      "images (one model, different seeds) gives their mean measures and the averaged spectral "
      "error.");
  m.def(
      "gaussian",
      [](const py::array& exemplar, int width, int height, std::uint32_t seed) {
        check_in_memory_size(width, height, "gaussian", "");
        const ImageShape shape = image_shape(exemplar, "the exemplar array");
        check_memory_budget(
            gaussian_peak_bytes(width, height, shape.width, shape.height, shape.channels),
            "the Gaussian version at " + std::to_string(width) + "x" + std::to_string(height) +
                " of the " + std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                " exemplar array",
            "ask for a smaller one or give a smaller exemplar");
        const ImageF image = exemplar_from_array(exemplar, "the exemplar array");
        ImageF result = [&] {
          py::gil_scoped_release release;
          return gaussian_version(image.view(), width, height, seed);
        }();
        return to_array(std::move(result));
      },
      py::arg("exemplar"), py::arg("width"), py::arg("height"), py::arg("seed") = 0,
      "The exemplar's Gaussian version (ADSN) at width x height, float32 HxWxC.");
  m.def(
      "cpu_targets",
      [] {
        std::vector<std::string> names;
        for (const CpuTarget target : available_cpu_targets())
          names.emplace_back(cpu_target_name(target));
        return names;
      },
      "The CPU evaluators' instruction sets this machine runs: 'reference' (the scalar "
      "evaluator) first, the default (the best) last; every one gives the same bytes.");
  m.def(
      "cpu_target", [] { return std::string(cpu_target_name(cpu_target())); },
      "The CPU target evaluation uses now.");
  m.def(
      "set_cpu_target", [](const std::string& name) { set_cpu_target(available_cpu_target(name)); },
      py::arg("name"),
      "Forces a CPU target for every later evaluation in the process (speed only, never the "
      "output); call it while no render runs.");
  m.def(
      "mix",
      [](const py::array& a, const py::array& b, const py::object& mask, std::uint32_t seed,
         const py::kwargs& params) {
        const ParamValues values = resolve_params("texton_mix", text_params(params));
        // The copies of the arrays held at once, as `stochtex mix` holds its images.
        HeldImages held;
        const auto hold = [&](const py::array& array, const std::string& name) {
          const ImageShape shape = image_shape(array, name);
          held.add(shape.width, shape.height, shape.channels, name);
        };
        hold(a, "array a");
        hold(b, "array b");
        if (!mask.is_none()) hold(mask, "the mask array");
        const ImageF first = image_from_array(a, "array a");
        const ImageF second = image_from_array(b, "array b");
        const ImageF grey = mask.is_none() ? ImageF() : image_from_array(mask, "the mask array");
        MixInputs inputs{first.view(), second.view(), "array a",
                         "array b",    std::nullopt,  "the mask array"};
        if (!grey.empty()) inputs.mask = grey.view();
        py::gil_scoped_release release;
        return mix(inputs, values, seed);
      },
      py::arg("a"), py::arg("b"), py::arg("mask") = py::none(), py::arg("seed") = 0,
      "Texton noise mixing of two exemplars (stochtex mix): a texton_mix model.");
}
