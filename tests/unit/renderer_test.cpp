// The renderer shared by the CLI, the Python module and the studio (src/renderer): its plan keeps
// an output in memory or streams it into a tiled OpenEXR file, refuses what cannot be rendered
// with the sentences `stochtex render` prints, fits the threads in the memory budget, and its
// renders to files are the plain render's bytes.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/memory_budget.hpp"
#include "io/image_io.hpp"
#include "model/model_colour.hpp"
#include "renderer/plan.hpp"
#include "renderer/render_file.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::renderer::renderer_test {
namespace {

// The sentence `plan_render(request, output)` refuses the request with.
std::string refusal(const RenderRequest& request, const std::string& output) {
  try {
    plan_render(request, output);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(planned)";
}

RenderRequest sized(int width, int height) {
  RenderRequest request;
  request.width = width;
  request.height = height;
  return request;
}

TEST(RendererPlan, InMemoryUnlessATiledOpenExrFileIsAskedForOrNeeded) {
  RenderRequest request = sized(300, 200);
  request.origin = {17.5, -3.0};
  request.scale = 1.5;
  request.region = PixelRegion{10, 20, 30, 40};
  const RenderPlan png = plan_render(request, "out.png");
  EXPECT_FALSE(png.streamed);
  EXPECT_EQ(png.grid.width, 30);
  EXPECT_EQ(png.grid.height, 40);
  EXPECT_EQ(png.grid.first_pixel_x, 10);
  EXPECT_EQ(png.grid.first_pixel_y, 20);
  EXPECT_EQ(png.grid.origin.x, 17.5);
  EXPECT_EQ(png.grid.scale, 1.5);
  EXPECT_FALSE(plan_render(request, "out.exr").streamed);
  request.half = true;
  EXPECT_TRUE(plan_render(request, "out.EXR").streamed);
  // Beyond the in-memory limit, an OpenEXR output is streamed whatever its options.
  const RenderPlan large = plan_render(sized(40000, 40000), "large.exr");
  EXPECT_TRUE(large.streamed);
  EXPECT_FALSE(large.exr.mipmap);
  EXPECT_GE(large.threads, 1);
}

TEST(RendererPlan, RefusesWithTheSentencesOfStochtexRender) {
  EXPECT_EQ(refusal(sized(40000, 40000), "large.png"),
            "--size 40000x40000 is 1600000000 pixels; .png output is rendered in memory and holds "
            "at most 67108864 pixels and 32768 a side: write a .exr file, which is streamed tile "
            "by tile");
  EXPECT_EQ(refusal(sized(0, 10), "out.exr"),
            "--size 0x10 is out of range: each side must be 1 to 1048576");
  RenderRequest tiled = sized(64, 64);
  tiled.tiled = true;
  EXPECT_EQ(refusal(tiled, "out.png"),
            "--tiled, --mipmap and --half write a tiled OpenEXR file: name the output .exr, not "
            "'out.png'");
  RenderRequest mipmap = sized(64, 64);
  mipmap.mipmap = true;
  mipmap.region = PixelRegion{0, 0, 32, 32};
  EXPECT_EQ(refusal(mipmap, "out.exr"),
            "--mipmap cannot be combined with --region: a region has no mip levels of its own; "
            "render the whole --size image with --mipmap");
  RenderRequest outside = sized(64, 64);
  outside.region = PixelRegion{40, 0, 32, 32};
  EXPECT_EQ(refusal(outside, "out.png"),
            "--region 40,0,32,32 is not inside the 64x64 image of --size: it needs a width and "
            "height of at least 1 and X + WIDTH <= 64, Y + HEIGHT <= 64");
  RenderRequest gl = sized(40000, 40000);
  gl.backend = Backend::gl;
  EXPECT_EQ(refusal(gl, "large.exr"),
            "--size 40000x40000 is 40000x40000 pixels, more than --backend gl renders (67108864 "
            "pixels and 32768 a side); use --backend cpu, which streams it tile by tile");
  // The caller's text of the origin is quoted as given, before the grid check's own words.
  RenderRequest far = sized(8, 8);
  far.origin = {1e300, 0.0};
  far.text.origin = "1e300,0";
  EXPECT_EQ(refusal(far, "out.png").rfind("--origin 1e300,0 with --scale 1 and --size 8x8 ", 0), 0u)
      << refusal(far, "out.png");
}

TEST(RendererPlan, ThreadsFitTheMemoryBudget) {
  // 64x64 tiles supersampled 64x64 hold 512 MiB of samples each: 8 tiles of a 512x64 image fit
  // three threads in the 2 GiB budget, not four.
  const auto request = [](int threads) { return std::to_string(threads) + " threads"; };
  const int fitted = budgeted_threads(512, 64, 64, 64, 0, request, "use fewer");
  EXPECT_GE(fitted, 1);
  EXPECT_LE(fitted, 3);
  EXPECT_EQ(budgeted_threads(512, 64, 64, 64, 3, request, "use fewer"), 3);
  try {
    budgeted_threads(512, 64, 64, 64, 4, request, "use fewer");
    ADD_FAILURE() << "four threads were not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "4 threads needs about 2.1 GB of memory, more than the budget of 2 GiB; use fewer");
  }
}

using RendererFile = test_support::FolderTest;

TEST_F(RendererFile, WritesThePlainRendersBytesInMemoryAndStreamed) {
  const Model model = test_support::white_noise_model("texton");
  RenderRequest request = sized(70, 90);
  request.origin = {3.0, -4.5};
  request.scale = 1.25;
  request.seed = 7;
  request.threads = 2;
  ImageF plain(70, 90, model.channels());
  RenderOptions options;
  options.threads = 2;
  render(model, {request.origin, request.scale, 70, 90}, request.seed, plain.view(), options);

  double last = 0.0;
  const auto progress = [&](double fraction) {
    EXPECT_GE(fraction, last);
    last = fraction;
  };
  const std::string pfm = file("render.pfm").string();
  EXPECT_EQ(
      render_to_file([&] { return model; }, request, pfm, "model.stx", make_cpu_backend, progress),
      std::vector<std::string>{pfm});
  EXPECT_DOUBLE_EQ(last, 1.0);
  EXPECT_TRUE(test_support::same_bytes(read_image(pfm), plain));

  request.tiled = true;  // 90 rows: two strips
  const std::string exr = file("render.exr").string();
  render_to_file([&] { return model; }, request, exr, "model.stx", make_cpu_backend);
  EXPECT_TRUE(test_support::same_bytes(read_image(exr), plain));
}

// A PNG is rendered strip by strip while each strip is encoded (write_png_strips): the file holds
// write_image's bytes of the plain render, at both bit depths.
TEST_F(RendererFile, WritesThePlainRendersPngWhileRenderingStrips) {
  const Model model = test_support::white_noise_model("texton");
  const int height = 2 * kPngStripRows + 22;
  RenderRequest request = sized(70, height);
  request.origin = {-2.0, 5.5};
  request.seed = 3;
  request.threads = 2;
  ImageF plain(70, height, model.channels());
  RenderOptions options;
  options.threads = 2;
  render(model, {request.origin, request.scale, 70, height}, request.seed, plain.view(), options);
  for (const int bit_depth : {8, 16}) {
    request.bit_depth = bit_depth;
    double last = 0.0;
    const std::string png = file("render.png").string();
    render_to_file([&] { return model; }, request, png, "model.stx", make_cpu_backend,
                   [&](double fraction) {
                     EXPECT_GE(fraction, last);
                     last = fraction;
                   });
    EXPECT_DOUBLE_EQ(last, 1.0);
    const std::string expected = file("plain.png").string();
    write_image(expected, plain.view(), bit_depth, rendered_space(model.colour_space()));
    EXPECT_EQ(test_support::file_bytes(png), test_support::file_bytes(expected)) << bit_depth;
  }
}

}  // namespace
}  // namespace stochtex::renderer::renderer_test
