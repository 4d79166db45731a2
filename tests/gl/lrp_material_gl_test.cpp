// Local random-phase noise on whole materials (issue 18) on the GL renderer: one program per chunk
// of up to 4 decorrelated channels (src/methods/lrp/gl_pass.cpp), the N channels matching the CPU
// within the twins' tolerance (Gl.TilingAndLrpMatchTheCpuReference), with and without section 5.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "gl/gl_support.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::lrp_material_gl_test {
namespace {

using namespace gl_test;

struct MaterialCase {
  const char* set;
  std::vector<std::string> maps;
  ParamValues params;
  Grid grid;
  bool filter = true;
};

TEST(Gl, LrpMaterialsMatchTheCpuReference) {
  // rock_sandstone, every map: 9 channels (chunks of 4, 4 and 1); sand_pebbles: 8 (4 and 4).
  const std::vector<std::string> rock = {"albedo", "normal", "roughness", "height", "ao"};
  const std::vector<std::string> sand = {"albedo", "normal", "roughness", "metallic"};
  const std::vector<MaterialCase> cases = {
      {"rock_sandstone", rock, {{"cosines", 20}}, {{0.0, 0.0}, 1.0, 48, 40}},
      {"rock_sandstone", rock, {{"cosines", 10}}, {{1e7, -3e6}, 4.0, 40, 40}},
      {"sand_pebbles", sand, {{"cosines", 10}}, {{-9.5, 2.0}, 2.0, 40, 40}, false},
      // Section 5: each chunk its slice of the structure table, the same turbulence.
      {"rock_sandstone",
       rock,
       {{"cosines", 10}, {"ratio", 0.3}, {"turbulence", 2}},
       {{-30.0, 17.0}, 1.0, 40, 36}},
  };
  for (const auto& c : cases) {
    const ImageF exemplar = test_support::material_exemplar(c.set, c.maps);
    const Model model = analyze("lrp", exemplar.view(), c.params, 0);
    ASSERT_GT(model.channels(), 4);
    const ImageF cpu = render_cpu(model, c.grid, 9, c.filter);
    const ImageF gpu = render_gpu(model, c.grid, 9, 4096, c.filter);
    float worst = 0.0f;
    for (std::size_t i = 0; i < cpu.pixels().size(); ++i)
      worst = std::max(worst, std::abs(cpu.pixels()[i] - gpu.pixels()[i]));
    std::cout << "lrp " << c.set << " (" << model.channels() << " channels) scale " << c.grid.scale
              << ": max |cpu - gl| = " << worst << "\n";
    EXPECT_LT(worst, 1e-4f) << c.set << " scale " << c.grid.scale;
    EXPECT_TRUE(same_bytes(gpu, render_gpu(model, c.grid, 9, 16, c.filter)));
  }
}

TEST(Gl, ModelsOfManyChannelsWithoutMapsAreNotExported) {
  // An exemplar of 6 channels analysed as an image has no maps to name a material's members by
  // (export_material_test.cpp exports materials).
  const ImageF exemplar = test_support::material_exemplar("sand_pebbles", {"albedo", "normal"});
  const Model model = analyze("lrp", exemplar.view(), {{"cosines", 4}}, 0);
  try {
    export_shader(model);
    ADD_FAILURE() << "a 6-channel lrp model was exported";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("6 channels and no maps"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace stochtex::lrp_material_gl_test
