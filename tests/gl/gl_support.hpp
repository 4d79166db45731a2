#pragma once
// Shared by the OpenGL tests: CPU and GL renders of one grid, and their comparison.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gl/program.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/material.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::gl_test {

inline const std::string kTextureDir = STOCHTEX_TEXTURE_DIR;

inline ImageF render_cpu(const Model& model, const Grid& grid, std::uint32_t seed,
                         bool filter = true) {
  ImageF out(grid.width, grid.height, model.channels());
  RenderOptions options;
  options.filter = filter;
  render(model, grid, seed, out.view(), options);
  return out;
}

inline ImageF render_gpu(const Model& model, const Grid& grid, std::uint32_t seed, int tile = 512,
                         bool filter = true) {
  ImageF out(grid.width, grid.height, model.channels());
  GpuRenderOptions options;
  options.tile_size = tile;
  options.filter = filter;
  render_gl(model, grid, seed, out.view(), options);
  return out;
}

using test_support::same_bytes;

// The largest slope of the decoding of an srgb model's values (D(m, s) of model/model_colour.hpp,
// 2.4 / 1.055 ((2 + 0.055) / 1.055)^1.4 at the table's top mean, 2): a difference between two
// renders of a model as data becomes at most this many times larger once decoded, so the GL tests
// bound an srgb model's gap by its data model's times this.
inline constexpr float kDecodingSlope = 5.8f;

// A model to export (tests of export-shader): method, exemplar, parameters and the side of the
// grid its renders are compared on; texton_mix (`stochtex mix`) also the second exemplar and,
// for a mask field, the mask image.
struct ExportCase {
  const char* method;
  const char* exemplar;
  ParamValues params;
  int size;
  const char* second = nullptr;
  const char* mask = nullptr;
};

// The model of an export case: analysed from its exemplar, or mixed from its two.
inline Model case_model(const ExportCase& c) {
  const ImageF exemplar = read_image(kTextureDir + "/" + c.exemplar);
  if (c.second == nullptr) return analyze(c.method, exemplar.view(), c.params, 0);
  const ImageF second = read_image(kTextureDir + "/" + c.second);
  const ImageF mask = c.mask != nullptr ? read_image(kTextureDir + "/" + c.mask) : ImageF();
  MixInputs inputs;
  inputs.a = exemplar.view();
  inputs.b = second.view();
  if (c.mask != nullptr) inputs.mask = mask.view();
  return mix(inputs, c.params, 0);
}

// The export cases: every method of the registry at least once (checked), every lrp section 5
// option, both tiling transports, texton_mix with a colour ramp and a grey mask.
inline std::vector<ExportCase> export_cases() {
  std::vector<ExportCase> cases = {
      {"texton", "grass_lawn_128.png", {{"support", 48}}, 48},
      {"tiling", "grass_lawn_128.png", {}, 48},
      {"tiling", "metal_grey_256.png", {{"transport", 1}}, 48},
      {"lrp", "metal_grey_256.png", {{"cosines", 10}}, 32},
      // Section 5: fixed phases, turbulence and random placement.
      {"lrp",
       "wool_knit_blue_256.png",
       {{"cosines", 10}, {"ratio", 0.3}, {"turbulence", 2.0}, {"placement", 1}},
       32},
      {"gabor", "grass_lawn_128.png", {{"impulses", 256}}, 24},
      {"texton_mix",
       "grass_lawn_128.png",
       {{"support", 16}, {"iterations", 5}, {"steps", 5}, {"ramp_start", -10}, {"ramp_end", 60}},
       32,
       "wood_planks_256.png"},
      {"texton_mix",
       "metal_grey_256.png",
       {{"support", 16}, {"iterations", 5}, {"steps", 4}, {"mask_scale", 0.5}},
       32,
       "nuts_grey_256.png",
       "metal_grey_256.png"},
  };
  for (const MethodInfo& method : methods())
    EXPECT_TRUE(std::any_of(cases.begin(), cases.end(),
                            [&](const ExportCase& c) { return c.method == method.name; }))
        << "no export case for " << method.name;
  return cases;
}

inline std::filesystem::path case_model_path(const std::filesystem::path& folder, std::size_t k,
                                             bool srgb) {
  return folder / ("export_case_" + std::to_string(k) + (srgb ? "_srgb.stx" : "_data.stx"));
}

// The models of export case `c`: of data (the exemplar's values), and the same in the srgb colour
// space.
inline std::array<Model, 2> make_case_models(const ExportCase& c) {
  Model data = case_model(c);
  Model srgb = with_colour_space(data, ColourSpace::srgb);
  return {std::move(data), std::move(srgb)};
}

// The models of export_cases(): [k][0] of data (the exemplar's values), [k][1] the same in the
// srgb colour space, whose exports return linear light (gl/colour.glsl). Made once per process
// or, under CTest, loaded from the files that the fixture test GlShared.ExportCaseModels made
// once per run (gl_shared, tests/CMakeLists.txt): making them takes seconds (measuring the srgb
// models' removed deviations), and six tests use them, each in a process of its own under CTest.
// A model file holds the model exactly, so both render the same bytes.
inline const std::vector<std::array<Model, 2>>& case_models() {
  static const std::vector<std::array<Model, 2>> models = [] {
    const std::vector<ExportCase> cases = export_cases();
    const auto folder = test_support::shared_folder();
    std::vector<std::array<Model, 2>> made;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      if (folder && std::filesystem::exists(case_model_path(*folder, k, true))) {
        made.push_back({load_model(case_model_path(*folder, k, false)),
                        load_model(case_model_path(*folder, k, true))});
        continue;
      }
      made.push_back(make_case_models(cases[k]));
    }
    return made;
  }();
  return models;
}

// The maps `names` of the shipped material set `set` (data/materials/<set>/<name>.png) for
// analyze_material, named `prefix` + name, their kinds from their names.
struct MaterialFiles {
  std::vector<ImageF> images;
  std::vector<MaterialMap> maps;
};

inline MaterialFiles material_files(const std::string& set, const std::vector<std::string>& names,
                                    const std::string& prefix = "") {
  MaterialFiles files;
  for (const auto& name : names)
    files.images.push_back(
        read_image(std::filesystem::path(STOCHTEX_MATERIAL_DIR) / set / (name + ".png")));
  for (std::size_t i = 0; i < names.size(); ++i)
    files.maps.push_back(
        {prefix + names[i], default_map_kind(names[i]), files.images[i].view(), names[i] + ".png"});
  return files;
}

inline float max_difference(const ImageF& a, const ImageF& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    worst = std::max(worst, std::abs(a.pixels()[i] - b.pixels()[i]));
  return worst;
}

// Runs an exported shader as an engine would: a compute shader after `#version 450` and the
// exported GLSL whose `store` (GLSL statements) writes the `floats` values of one pixel to
// values[pixel.y * width + pixel.x] from p = scale * (pixel + 0.5), its footprint (scale, 0),
// (0, scale) as `dpdx`, `dpdy` and `seed`, for size x size pixels (size a multiple of 8), with
// `textures[i]` bound to the sampler of files.textures[i]. Returns the values, pixel by pixel.
inline std::vector<float> run_export_program(const ShaderExport& files, const std::string& store,
                                             int floats, const std::vector<GLuint>& textures,
                                             int size, float scale, std::uint32_t seed) {
  const std::string source = "#version 450\n" + files.shader.text +
                             "\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                             "struct Values { float v[" +
                             std::to_string(floats) + R"glsl(]; };
layout(std430, binding = 0) writeonly buffer Out { Values values[]; };
uniform int width;
uniform float scale;
uniform uint seed;
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  vec2 p = scale * (vec2(pixel) + 0.5);
  vec2 dpdx = vec2(scale, 0.0);
  vec2 dpdy = vec2(0.0, scale);
  int index = pixel.y * width + pixel.x;
)glsl" + store + "}\n";
  const gl::Program program(source);
  for (std::size_t i = 0; i < textures.size(); ++i) {
    glBindTextureUnit(static_cast<GLuint>(i), textures[i]);
    program.set(("stochtex_" + files.textures[i].name).c_str(), static_cast<int>(i));
  }
  program.set("width", size);
  program.set("scale", scale);
  program.set("seed", static_cast<unsigned>(seed));
  const auto count = static_cast<std::size_t>(size) * size * static_cast<std::size_t>(floats);
  const gl::Buffer buffer(count * sizeof(float));
  glUseProgram(program.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
  glDispatchCompute(static_cast<GLuint>(size / 8), static_cast<GLuint>(size / 8), 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> values(count);
  glGetNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(values.size() * sizeof(float)),
                          values.data());
  gl::check_gl("running an exported shader");
  return values;
}

// run_export_program of stochtex_<method>(p, dpdx, dpdy, seed): the image of the model's
// `channels` channels.
inline ImageF run_export(const ShaderExport& files, const std::string& method,
                         const std::vector<GLuint>& textures, int channels, int size, float scale,
                         std::uint32_t seed) {
  const std::vector<float> values = run_export_program(
      files,
      "  vec4 value = stochtex_" + method +
          "(p, dpdx, dpdy, seed);\n  values[index].v = float[4](value.x, value.y, value.z, "
          "value.w);\n",
      4, textures, size, scale, seed);
  ImageF image(size, size, channels);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < channels; ++c)
        image.at(x, y, c) =
            values[(static_cast<std::size_t>(y) * size + x) * 4 + static_cast<std::size_t>(c)];
  return image;
}

}  // namespace stochtex::gl_test
