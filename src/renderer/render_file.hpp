#pragma once
// Renders to images: in memory, or to files as `stochtex render` and `synth` write them (docs/
// large-renders.md, docs/materials.md): one image, held in memory or streamed strip by strip into
// a tiled OpenEXR file, or a material's maps to one file each.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/grid_backend.hpp"
#include "renderer/plan.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::renderer {

// The file of a material's map: `output` with each {map} replaced by the map's name.
std::string map_output(std::string output, std::string_view name);

// A material's maps of width x rows pixels rendered at once (split_maps; a model of one image as
// its one map): the render, 4 bytes a channel, and each map cut from it with its encoded copy, 6
// bytes a channel as written (a normal map's 3), or for a strip streamed into every map's file 8,
// with a pixel of margin either side. `stochtex render` checks a material's maps with it, the
// Python module Model.render_maps and Model.split.
std::uint64_t maps_peak_bytes(const Model& model, int width, int rows, bool streamed);

// The model's render of `grid` on `backend`, in memory; `progress` gets the fraction done.
ImageF render_image(const Model& model, const Grid& grid, GridBackend& backend,
                    const std::function<void(double)>& progress = {});

// Checks the output path (which may not be the `input` file) and plans the request
// (plan_render), sets its CPU target, then makes the model with `make_model` (called after those
// checks, so that usage errors come first) and checks what the model needs of the output: a
// model of one image one file that can hold its channels; a material's maps one file each,
// `output` naming them with {map} (map_output), each writable and the render of them within the
// memory budget; a tiled file the free space of its folder. Then renders the model on the backend
// `make_backend` gives and writes it: in memory, or strip by strip into a tiled OpenEXR file
// (plan.streamed), a material's maps in memory or strip by strip alike; a PNG of one image
// strip by strip, each encoded on another thread while the next renders (write_png_strips).
// `progress` gets the fraction of every grid's pixels done, from the calling thread. Returns the
// files written.
std::vector<std::string> render_to_file(const std::function<Model()>& make_model,
                                        const RenderRequest& request, const std::string& output,
                                        const std::string& input,
                                        const BackendFactory& make_backend,
                                        const std::function<void(double)>& progress = {});

}  // namespace stochtex::renderer
