// The CPU targets (render.hpp's CpuTarget, docs/design.md §4): every SIMD target Highway can run
// on this machine gives the scalar reference's bytes, forced one after the other as FastNoise2's
// cross-ISA tests do, for every method: renders at scale 1 (point samples and filtered) and zoomed
// out, far from the origin, grids whose width is no multiple of any lane count, and scattered
// positions with footprints of their own (the lanes of one batch then see different lattice
// cells).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "stochtex/surface.hpp"
#include "test_support.hpp"

namespace stochtex::cpu_target_test {
namespace {

using test_support::same_bytes;

// The best target again after each test: the setting is process-wide.
class CpuTargets : public testing::Test {
 protected:
  void TearDown() override { set_cpu_target(available_cpu_targets().back()); }
};

ImageF corpus_crop(const std::string& name, int side) {
  const ImageF image = read_image(std::filesystem::path(STOCHTEX_TEXTURE_DIR) / name);
  ImageF crop(side, side, image.channels());
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < image.channels(); ++c) crop.at(x, y, c) = image.at(x, y, c);
  return crop;
}

ImageF colour_exemplar() {
  return corpus_crop("grass_lawn_128.png", 64);
}
ImageF grey_exemplar() {
  return corpus_crop("sand_height_grey_512.png", 64);
}
// 6 channels: a material's albedo and normal maps.
ImageF material_exemplar() {
  const ImageF maps = test_support::material_exemplar("rock_sandstone", {"albedo", "normal"});
  ImageF crop(64, 64, maps.channels());
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < maps.channels(); ++c) crop.at(x, y, c) = maps.at(x, y, c);
  return crop;
}

// Texton noise mixing from the colour exemplar's two halves, along a ramp.
Model texton_mix_model() {
  const ImageF exemplar = colour_exemplar();
  ImageF a(32, 64, 3);
  ImageF b(32, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) {
        a.at(x, y, c) = exemplar.at(x, y, c);
        b.at(x, y, c) = exemplar.at(x + 32, y, c);
      }
  MixInputs inputs;
  inputs.a = a.view();
  inputs.b = b.view();
  return mix(
      inputs,
      {{"support", 12}, {"iterations", 10}, {"steps", 4}, {"ramp_start", -30}, {"ramp_end", 30}},
      5);
}

struct Case {
  std::string name;
  std::function<Model()> make;
};

std::vector<Case> cases() {
  const auto model = [](std::string method, ImageF (*exemplar)(), ParamValues params) {
    return [=] { return analyze(method, exemplar().view(), params, 5); };
  };
  return {
      {"lrp grey", model("lrp", grey_exemplar, {{"cosines", 24}})},
      {"lrp colour", model("lrp", colour_exemplar, {{"cosines", 24}})},
      {"lrp section 5",
       model("lrp", colour_exemplar, {{"cosines", 24}, {"ratio", 0.3}, {"turbulence", 2}})},
      {"lrp material", model("lrp", material_exemplar, {{"cosines", 12}})},
      {"texton colour", model("texton", colour_exemplar, {{"support", 12}, {"iterations", 10}})},
      {"texton grey", model("texton", grey_exemplar, {{"support", 12}, {"iterations", 10}})},
      {"texton poisson",
       model("texton", colour_exemplar, {{"support", 12}, {"iterations", 10}, {"points", 0}})},
      {"texton material",
       model("texton", material_exemplar, {{"support", 12}, {"iterations", 10}})},
      {"texton nearest",
       model("texton", colour_exemplar, {{"support", 12}, {"iterations", 10}, {"order", 0}})},
      {"texton cubic",
       model("texton", grey_exemplar, {{"support", 13}, {"iterations", 10}, {"order", 3}})},
      {"texton quintic",
       model("texton", colour_exemplar, {{"support", 12}, {"iterations", 10}, {"order", 5}})},
      // Cells of more points than the cell cache keeps.
      {"texton mni 600",
       model("texton", grey_exemplar, {{"support", 12}, {"iterations", 10}, {"mni", 600}})},
      {"texton_mix", texton_mix_model},
      {"tiling colour", model("tiling", colour_exemplar, {})},
      {"tiling grey", model("tiling", grey_exemplar, {})},
      {"tiling decorrelated colour", model("tiling", colour_exemplar, {{"transport", 1}})},
      {"tiling variance blend", model("tiling", colour_exemplar, {{"blend", 1}})},
      {"tiling linear blend", model("tiling", grey_exemplar, {{"blend", 2}})},
      {"tiling material", model("tiling", material_exemplar, {})},
      {"tiling rotation", model("tiling", colour_exemplar, {{"rotation", 30}})},
      {"gabor colour", model("gabor", colour_exemplar, {{"impulses", 64}, {"iterations", 20}})},
      {"gabor grey", model("gabor", grey_exemplar, {{"impulses", 64}, {"iterations", 20}})},
      {"gabor pca", model("gabor", colour_exemplar,
                          {{"impulses", 64}, {"iterations", 20}, {"colour_space", 1}})},
      {"gabor material", model("gabor", material_exemplar, {{"impulses", 32}, {"iterations", 10}})},
  };
}

// The renders and scattered evaluations compared across targets.
std::vector<ImageF> outputs(const Model& model) {
  std::vector<ImageF> images;
  const auto render_grid = [&](const Grid& grid, bool filter) {
    ImageF out(grid.width, grid.height, model.channels());
    RenderOptions options;
    options.threads = 1;
    options.filter = filter;
    render(model, grid, 9, out.view(), options);
    images.push_back(std::move(out));
  };
  render_grid({{1e7 + 0.3, -2.5e6}, 1.0, 37, 29}, false);
  render_grid({{-40.25, 17.5}, 1.0, 37, 29}, true);
  render_grid({{12.0, -300.0}, 6.0, 23, 19}, true);
  // Zoomed out by 8 and 2: levels whose texels the samples meet 1 or 2 apart.
  render_grid({{-5000.5, 77.0}, 8.0, 35, 9}, true);
  render_grid({{3.0, 2.0}, 2.0, 33, 17}, true);

  std::mt19937 engine(4);
  std::uniform_real_distribution<double> place(-200.0, 200.0);
  std::uniform_real_distribution<double> axis(-4.0, 4.0);
  std::vector<Vec2d> positions(301);
  std::vector<Footprint> footprints(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    positions[i] = {place(engine), place(engine)};
    footprints[i] = {{axis(engine), axis(engine)}, {axis(engine), axis(engine)}};
  }
  for (const bool filtered : {false, true}) {
    ImageF out(1, static_cast<int>(positions.size()), model.channels());
    evaluate(model, positions,
             filtered ? std::span<const Footprint>(footprints) : std::span<const Footprint>(), 3,
             out.view());
    images.push_back(std::move(out));
  }
  // One anisotropic footprint (several probes) shared by scattered positions and by a grid's.
  const std::vector<Footprint> shared(positions.size(), Footprint{{3.0, 1.0}, {-0.5, 0.7}});
  ImageF scattered(1, static_cast<int>(positions.size()), model.channels());
  evaluate(model, positions, shared, 3, scattered.view());
  images.push_back(std::move(scattered));
  std::vector<Vec2d> row_major;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 43; ++x) row_major.push_back({-60.3 + 2.0 * x, 25.1 + 2.0 * y});
  ImageF grid(43, 7, model.channels());
  evaluate(model, row_major,
           std::vector<Footprint>(row_major.size(), Footprint{{2.0, 0.0}, {0.0, 0.5}}), 3,
           grid.view());
  images.push_back(std::move(grid));
  return images;
}

TEST_F(CpuTargets, TheReferenceComesFirstAndTheBestLast) {
  const std::vector<CpuTarget> targets = available_cpu_targets();
  ASSERT_FALSE(targets.empty());
  EXPECT_EQ(targets.front(), CpuTarget::reference);
  EXPECT_EQ(cpu_target(), targets.back());
  for (const CpuTarget target : targets) {
    set_cpu_target(target);
    EXPECT_EQ(cpu_target(), target) << cpu_target_name(target);
  }
}

TEST_F(CpuTargets, NamesFindTheTargetsThisMachineRuns) {
  for (const CpuTarget target : available_cpu_targets())
    EXPECT_EQ(available_cpu_target(cpu_target_name(target)), target);
  try {
    available_cpu_target("neon");
    ADD_FAILURE() << "an unknown target was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot run 'neon'; its CPU targets are reference"),
              std::string::npos)
        << e.what();
  }
}

// Every CPU target gives the scalar reference's bytes for `outputs()`.
void expect_the_references_bytes(const std::function<std::vector<ImageF>()>& outputs,
                                 const std::string& what) {
  set_cpu_target(CpuTarget::reference);
  const std::vector<ImageF> reference = outputs();
  for (const CpuTarget target : available_cpu_targets()) {
    if (target == CpuTarget::reference) continue;
    set_cpu_target(target);
    const std::vector<ImageF> images = outputs();
    for (std::size_t i = 0; i < images.size(); ++i)
      EXPECT_TRUE(same_bytes(reference[i], images[i]))
          << what << ", " << cpu_target_name(target) << ", output " << i;
  }
}

// One-thread renders of `model` on each grid, unfiltered and filtered, in tiles of 64.
std::vector<ImageF> renders(const Model& model, const std::vector<Grid>& grids) {
  std::vector<ImageF> images;
  for (const Grid& grid : grids)
    for (const bool filter : {false, true}) {
      ImageF out(grid.width, grid.height, model.channels());
      RenderOptions options;
      options.threads = 1;
      options.tile_size = 64;
      options.filter = filter;
      render(model, grid, 9, out.view(), options);
      images.push_back(std::move(out));
    }
  return images;
}

TEST_F(CpuTargets, EveryTargetGivesTheReferencesBytes) {
  // The test must compare a hardware vector target: an x86-64 machine runs SSE4 at least (the
  // sanitizer build on an AVX-512 machine compiles AVX-512 alone, scripts/sanitize.sh).
  const std::vector<CpuTarget> targets = available_cpu_targets();
  ASSERT_TRUE(std::any_of(targets.begin(), targets.end(), [](CpuTarget target) {
    return target != CpuTarget::reference && target != CpuTarget::portable;
  }));
  for (const Case& c : cases()) {
    const Model model = c.make();
    expect_the_references_bytes([&] { return outputs(model); }, c.name);
  }
}

TEST_F(CpuTargets, GaborStripsOfATileGiveTheReferencesBytes) {
  // 4,096 impulses: the main grids' cells are a quarter to a half of their kernel radius, so the
  // vectorised evaluator takes a 64-sample tile row in several strips (gabor/simd.hpp
  // strip_width) and its cache slots wrap around within a strip.
  const Model model =
      analyze("gabor", grey_exemplar().view(), {{"impulses", 4096}, {"iterations", 10}}, 5);
  std::vector<Grid> grids;
  for (const double scale : {1.0, 0.5, 3.0}) grids.push_back({{-700.25, 33.5}, scale, 64, 40});
  expect_the_references_bytes([&] { return renders(model, grids); }, "gabor strips");
}

TEST_F(CpuTargets, GaborCellsBeyondACacheSlotGiveTheReferencesBytes) {
  // 65,536 impulses: cells of about 300 impulses, more than a slot of the vectorised evaluator's
  // cache holds (gabor/simd.hpp), drawn block by block at each use.
  const Model model =
      analyze("gabor", grey_exemplar().view(), {{"impulses", 65536}, {"iterations", 10}}, 5);
  expect_the_references_bytes(
      [&] {
        return renders(model, {{{-3.5, 2e5}, 2.0, 7, 5}});
      },
      "gabor large cells");
}

TEST_F(CpuTargets, GaborSurfaceNoiseGivesTheReferencesBytes) {
  // Surface Gabor noise (gabor/simd.hpp surface_impulse_sum) at scattered points of a sphere far
  // from the origin, each with its own frame: point samples, then footprints from a tenth of a
  // pixel to 40 pixels (thinning levels 0 to about 5), at two impulse densities.
  std::mt19937 engine(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> width(-3.0, 1.6);
  std::vector<SurfacePoint> points;
  for (int i = 0; i < 97; ++i) {
    Vec3d n{unit(engine), unit(engine), unit(engine)};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = {n.x / length, n.y / length, n.z / length};
    // The tangent: e_x or e_y projected on the tangent plane, whichever is further from n.
    const Vec3d axis = std::abs(n.x) < 0.7 ? Vec3d{1.0, 0.0, 0.0} : Vec3d{0.0, 1.0, 0.0};
    const double along = axis.x * n.x + axis.y * n.y;
    Vec3d t{axis.x - along * n.x, axis.y - along * n.y, -along * n.z};
    const double t_length = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    t = {t.x / t_length, t.y / t_length, t.z / t_length};
    const Vec3d b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
    const double w = std::pow(10.0, width(engine));
    points.push_back({{3e4 + 40.0 * n.x, -75.0 + 40.0 * n.y, 40.0 * n.z},
                      n,
                      t,
                      {w * t.x, w * t.y, w * t.z},
                      {0.5 * w * b.x, 0.5 * w * b.y, 0.5 * w * b.z}});
  }
  std::vector<SurfacePoint> samples = points;
  for (SurfacePoint& p : samples) p.dpdx = p.dpdy = {};
  for (const int impulses : {64, 1024}) {
    const Model model =
        analyze("gabor", colour_exemplar().view(), {{"impulses", impulses}, {"iterations", 20}}, 5);
    expect_the_references_bytes(
        [&] {
          std::vector<ImageF> images;
          for (const auto* batch : {&samples, &points}) {
            ImageF out(1, static_cast<int>(batch->size()), model.channels());
            evaluate_surface(model, *batch, {}, 11, out.view());
            images.push_back(std::move(out));
          }
          return images;
        },
        "gabor surface, " + std::to_string(impulses) + " impulses");
  }
}

}  // namespace
}  // namespace stochtex::cpu_target_test
