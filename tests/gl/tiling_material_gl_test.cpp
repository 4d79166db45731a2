// Histogram-preserving tiling on whole materials (issue 18) on the GL renderer: the Gaussian in
// chunks of up to 4 channels from the same patches, then each map's group through its own T^-1
// (src/methods/tiling/gl_pass.cpp, groups.glsl), all N channels matching the CPU within the twins'
// tolerance (Gl.TilingAndLrpMatchTheCpuReference: 1e-4, GLSL's erf polynomial before the
// tables).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_support.hpp"
#include "methods/tiling/gl_twin.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::tiling_material_gl_test {
namespace {

using namespace gl_test;

struct MaterialCase {
  std::vector<std::string> maps;
  ParamValues params;
  Grid grid;
  bool filter = true;
};

// Measured maxima on llvmpipe (Mesa 22.3.6): 2.1e-5 without the artist controls, 5.4e-5 with
// rotation and scale jitter, both on the AO map, whose 1-D table is the steepest (GLSL's erf
// polynomial, sin and cos differ from the C++'s by about 1e-7 before it); albedo within 5e-6.
TEST(Gl, TilingMaterialsMatchTheCpuReference) {
  const std::vector<std::string> rock = {"albedo", "normal", "roughness", "height", "ao"};
  const std::vector<std::string> no_normal = {"albedo", "height", "ao"};
  const std::vector<MaterialCase> cases = {
      // 8 channels: chunks of 4 and 4, the normal map's slopes (channels 3 and 4) straddling them.
      {rock, {}, {{0.0, 0.0}, 1.0, 48, 40}},
      {rock, {}, {{1e7, -3e6}, 3.0, 40, 32}},
      // Zoomed out: levels of the pyramid and of the prefiltered tables blended.
      {rock, {}, {{-77.5, 12.0}, 11.0, 32, 32}},
      {rock, {}, {{5.0, 5.0}, 2.0, 40, 40}, false},
      {rock, {{"sharpness", 4}}, {{3.0, -4.0}, 0.5, 40, 40}},
      // Rotation and scale jitter (without a normal map: its turned slopes are CPU only): each
      // patch its own level, T^-1 at their w^2-weighted mean, which the first chunk hands to the
      // groups' pass.
      {no_normal, {{"rotation", 180}, {"scale_jitter", 0.5}}, {{1e7, -3e6}, 1.0, 48, 40}},
      {no_normal, {{"scale_jitter", 0.7}, {"rotation", 45}}, {{-9.5, 2.0}, 5.0, 40, 40}},
      // The variance-preserving blend: no T^-1, so no groups' pass (chunks only).
      {rock, {{"blend", 1}}, {{3.0, 4.0}, 2.0, 40, 40}},
      // One chunk: the normal map and the height, 3 channels in 2 groups.
      {{"normal", "height"}, {}, {{2.0, 3.0}, 4.0, 40, 40}},
      // The patches kept apart (render.glsl's TILING_PATCH_OUTPUT, groups.glsl): a normal map's
      // slopes turned with their patches (its radial group), then scaled through its table...
      {rock, {{"rotation", 180}}, {{1e7, -3e6}, 1.0, 48, 40}},
      {rock, {{"rotation", 60}, {"scale_jitter", 0.6}}, {{-9.5, 2.0}, 5.0, 40, 40}},
      {rock, {{"rotation", 120}, {"scale_jitter", 0.3}}, {{4.0, 8.0}, 1.0, 40, 40}, false},
      // ...and the height-aware blend, alone and with the turned slopes.
      {no_normal, {{"height_blend", 0.1}}, {{3.0, -4.0}, 1.0, 48, 40}},
      {rock, {{"height_blend", 0.05}, {"rotation", 180}}, {{-77.5, 12.0}, 7.0, 32, 32}},
  };
  for (const auto& c : cases) {
    const MaterialFiles files = material_files("rock_sandstone", c.maps);
    const Model model = analyze_material("tiling", files.maps, c.params);
    for (const std::uint32_t seed : {9u, 1234567u}) {
      const ImageF cpu = render_cpu(model, c.grid, seed, c.filter);
      const ImageF gpu = render_gpu(model, c.grid, seed, 4096, c.filter);
      const float worst = max_difference(cpu, gpu);
      std::cout << "tiling rock (" << model.channels() << " channels) scale " << c.grid.scale
                << " seed " << seed << ": max |cpu - gl| = " << worst << "\n";
      EXPECT_LT(worst, 1e-4f) << model.channels() << " channels, scale " << c.grid.scale;
      // Tiles of the dispatch (each its levels of detail) change nothing.
      EXPECT_TRUE(same_bytes(gpu, render_gpu(model, c.grid, seed, 16, c.filter)));
    }
  }
}

TEST(Gl, TilingMaterialsOfFifteenChannelsAndWideImagesMatchTheCpuReference) {
  // Two materials side by side: 15 channels, chunks of 4, 4, 4 and 3.
  const MaterialFiles rock =
      material_files("rock_sandstone", {"albedo", "normal", "roughness", "height", "ao"});
  const MaterialFiles sand =
      material_files("sand_pebbles", {"albedo", "normal", "roughness", "metallic"}, "sand_");
  std::vector<MaterialMap> maps = rock.maps;
  maps.insert(maps.end(), sand.maps.begin(), sand.maps.end());
  const Model material = analyze_material("tiling", maps);
  ASSERT_EQ(material.channels(), 15);
  // An image of 9 channels (no maps): one group of 9 on its principal axes.
  const Model image =
      analyze("tiling",
              test_support::material_exemplar("rock_sandstone",
                                              {"albedo", "normal", "roughness", "height", "ao"})
                  .view(),
              {}, 0);
  ASSERT_EQ(image.channels(), 9);
  for (const Model* model : {&material, &image}) {
    const Grid grid{{-30.0, 17.0}, 3.0, 40, 36};
    const float worst = max_difference(render_cpu(*model, grid, 5), render_gpu(*model, grid, 5));
    std::cout << "tiling (" << model->channels() << " channels): max |cpu - gl| = " << worst
              << "\n";
    EXPECT_LT(worst, 1e-4f) << model->channels() << " channels";
  }
}

TEST(Gl, TilingMaterialsHaveNoSurfaceTwin) {
  // 3 channels (a vec4 would hold them), but the groups' T^-1 is the renderer's second pass and
  // the export's material function; the surface shaders take an image's colour and alpha.
  const MaterialFiles files = material_files("rock_sandstone", {"normal", "height"});
  const Model model = analyze_material("tiling", files.maps);
  ASSERT_EQ(model.channels(), 3);
  EXPECT_NE(export_shader(model).shader.text.find("stochtex_tiling_material("), std::string::npos);
  const std::vector<SurfacePoint> points = test_support::sphere_points(4, 10.0, 1.0, 0.5, 17);
  ImageF out(4, 1, model.channels());
  SurfaceOptions triplanar;
  triplanar.mapping = SurfaceMapping::triplanar;
  try {
    evaluate_surface_gl(model, points, triplanar, 0, out.view());
    ADD_FAILURE() << "a tiling material was accepted by the triplanar surface twin";
  } catch (const Error& error) {
    const std::string sentence = error.what();
    EXPECT_NE(sentence.find("3 channels go through T^-1 in 2 groups"), std::string::npos)
        << sentence;
    EXPECT_EQ(sentence.find('\n'), std::string::npos) << sentence;
  }
}

// A tiny model of 4 channels in the groups `groups` (4 x 4 exemplar, 2^3 table, 1-D tables of 16).
tiling::TilingModel grouped_model(std::vector<tiling::GroupSpec> groups) {
  tiling::TilingData d;
  d.channels = 4;
  d.width = 4;
  d.height = 4;
  d.lut_size = 2;
  d.table_size = 16;
  d.gaussian.assign(4 * 4 * 4, 0.5f);
  d.blend_mean.assign(4, 0.5f);
  d.groups = std::move(groups);
  const tiling::TilingLayout layout = tiling::tiling_layout(4, d.transport, d.blend, d.groups);
  d.lut.assign(layout.colour_lut ? 2 * 2 * 2 * 3 : 0, 0.5f);
  d.tables.assign(static_cast<std::size_t>(layout.table_count) * 16, 0.5f);
  d.colour_basis.assign(static_cast<std::size_t>(layout.basis_size), 0.0f);
  d.colour_mean.assign(static_cast<std::size_t>(layout.mean_size), 0.0f);
  return tiling::TilingModel(std::move(d));
}

TEST(Gl, TilingGroupsThroughTheThreeDTableAreRefused) {
  // groups.glsl has a case per kind a material's maps use; the 3-D table is an image's colour
  // (blend.glsl), never a material map's, and gets a sentence, as a kind added later without a
  // GLSL case would (a model file holds only the three kinds).
  using tiling::GroupTransform;
  EXPECT_NO_THROW(gl::tiling_groups_glsl(
      grouped_model({{GroupTransform::decorrelated, 3}, {GroupTransform::direct, 1}})));
  try {
    gl::tiling_groups_glsl(grouped_model({{GroupTransform::lut, 3}, {GroupTransform::direct, 1}}));
    ADD_FAILURE() << "a 3-D table group was accepted";
  } catch (const Error& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("channels 0 to 2"), std::string::npos) << what;
    EXPECT_NE(what.find("--backend cpu"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace stochtex::tiling_material_gl_test
