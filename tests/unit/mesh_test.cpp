// Meshes (stochtex/mesh.hpp) and their pictures (stochtex/mesh_render.hpp): the OBJ reader and the
// checks of prepare_mesh on each kind of bad mesh, computed normals, the rasteriser's independence
// of the thread count, ray differentials of a plane seen head-on, and the refusals before work.

#include "stochtex/mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/srgb.hpp"
#include "render/mesh_shading.hpp"
#include "stochtex/material.hpp"
#include "stochtex/mesh_render.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::mesh_test {
namespace {

using MeshTest = test_support::FolderTest;

using test_support::kMeshes;

using test_support::white_noise_model;

const Model& tiling_model() {
  static const Model model = white_noise_model("tiling");
  return model;
}

// read_mesh must refuse the OBJ text with a stochtex::Error naming the file and saying `problem`.
void expect_refused(const std::filesystem::path& path, const std::string& text,
                    const std::string& problem) {
  std::ofstream(path) << text;
  try {
    read_mesh(path);
    ADD_FAILURE() << problem << ": accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  }
}

TEST_F(MeshTest, ReadsTheShippedMeshes) {
  const Mesh sphere = read_mesh(kMeshes + "sphere.obj");
  EXPECT_EQ(sphere.triangles.size(), 2208u);
  EXPECT_EQ(sphere.uvs.size(), sphere.positions.size());
  EXPECT_EQ(sphere.normals.size(), sphere.positions.size());
  EXPECT_TRUE(sphere.uv_wrap_seam);  // its meridian at u = 0 and u = 1
  const Mesh scan = read_mesh(kMeshes + "scan.obj");
  EXPECT_TRUE(scan.uvs.empty());
  EXPECT_FALSE(scan.uv_wrap_seam);
  ASSERT_EQ(scan.normals.size(), scan.positions.size());
  for (const Vec3d& n : scan.normals) EXPECT_NEAR(length(n), 1.0, 1e-12);
}

TEST_F(MeshTest, ComputesAreaWeightedNormals) {
  // A unit square in the z = 0 plane split in two, and a wide triangle folded up at x = 1: the
  // shared vertices' normals lean towards the larger face.
  std::ofstream(file("fold.obj")) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 1\n"
                                     "f 1 2 3\nf 1 3 4\nf 2 3 5\n";
  const Mesh mesh = read_mesh(file("fold.obj"));
  EXPECT_NEAR(mesh.normals[0].z, 1.0, 1e-12);
  EXPECT_NEAR(mesh.normals[3].z, 1.0, 1e-12);
  // Vertex 2 (index 1): the z = 0 face (area 1/2, normal +z) and the x = 1 face (area 1/2,
  // normal +x): equal weights.
  EXPECT_NEAR(mesh.normals[1].x, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(mesh.normals[1].z, std::sqrt(0.5), 1e-12);
}

// A UV sphere's pole: its top row of quads, split in two, gives triangles whose two corners are
// the pole repeated. They are skipped and counted; the rest is the mesh.
TEST_F(MeshTest, SkipsAndCountsDegenerateTriangles) {
  std::ofstream(file("pole.obj")) << "v 0 0 1\nv 0 0 1\nv 1 0 0\nv 0 1 0\nv -1 0 0\n"
                                     "f 1 3 4\nf 1 2 4\nf 2 4 5\nf 1 1 3\nf 3 4 4\n";
  const Mesh mesh = read_mesh(file("pole.obj"));
  EXPECT_EQ(mesh.skipped_triangles, 3u);
  EXPECT_EQ(mesh.triangles.size(), 2u);
}

TEST_F(MeshTest, RefusesBadMeshes) {
  expect_refused(file("empty.obj"), "# nothing\n", "has no triangle");
  expect_refused(file("points.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "has no triangle");
  expect_refused(file("nan.obj"), "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n",
                 "line 3 has 'nan', which is not a finite number");
  expect_refused(file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "out of range");
  expect_refused(file("degenerate.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
                 "every one of its 2 triangles is degenerate");
  // Three triangles on the edge (1, 2): a fin.
  expect_refused(file("fin.obj"),
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 2 5\n",
                 "not manifold");
  // The same fin with the shared edge's vertices duplicated (as a uv seam would): still one edge.
  expect_refused(file("fin_split.obj"),
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 0\nv 1 0 0\n"
                 "f 1 2 3\nf 1 2 4\nf 6 7 5\n",
                 "not manifold");
}

TEST(MeshChecks, RefusesValuesAndSizes) {
  const Mesh good{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {{0, 1, 2}}};
  const auto refused = [](Mesh mesh, const std::string& problem) {
    try {
      prepare_mesh(mesh, "'m.obj'");
      ADD_FAILURE() << problem << ": accepted";
    } catch (const Error& error) {
      EXPECT_EQ(error.code(), ErrorCode::invalid_input);
      EXPECT_NE(std::string(error.what()).find("'m.obj': "), std::string::npos);
      EXPECT_NE(std::string(error.what()).find(problem), std::string::npos) << error.what();
    }
  };
  Mesh nan = good;
  nan.positions[1].y = std::numeric_limits<double>::quiet_NaN();
  refused(nan, "not finite");
  Mesh inf = good;
  inf.positions[2].z = std::numeric_limits<double>::infinity();
  refused(inf, "not finite");
  Mesh zero_normal = good;
  zero_normal.normals = {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}};
  refused(zero_normal, "normal");
  Mesh bad_uv = good;
  bad_uv.uvs = {{0, 0}, {1, std::nan("")}, {0, 1}};
  refused(bad_uv, "texture coordinate");
  Mesh range = good;
  range.triangles[0][2] = 3;
  refused(range, "vertex 3 of only 3");
  Mesh huge = good;
  huge.triangles.resize(kMaxMeshTriangles + 1, {0, 1, 2});
  refused(huge, "more than the limits");
  Mesh fine = good;
  prepare_mesh(fine, "'m.obj'");
  EXPECT_NEAR(std::abs(fine.normals[0].z), 1.0, 1e-12);
}

// A flat strip in the plane z = 0, x from 0 to 2 and y from 0 to 1, v = y. Wrapped, u runs from 0
// to 1 on each half (u = x, then x - 1): the position x = 1 carries u = 1 and u = 0, the wrap
// seam of a UV sphere's meridian, flattened; otherwise u = x / 2, no seam.
Mesh uv_strip(bool wrapped) {
  Mesh mesh;
  for (std::uint32_t half = 0; half < 2; ++half) {
    for (int corner = 0; corner < 4; ++corner) {
      const double x = half + corner % 2;
      const double y = corner / 2;
      mesh.positions.push_back({x, y, 0.0});
      mesh.uvs.push_back({wrapped ? x - half : x / 2.0, y});
    }
    const std::uint32_t first = 4 * half;
    mesh.triangles.push_back({first, first + 1, first + 3});
    mesh.triangles.push_back({first, first + 3, first + 2});
  }
  prepare_mesh(mesh, "strip");
  return mesh;
}

// A uv wrap seam: one position whose uvs differ by a whole number in u or v (within 2^-16, as
// text rounds 0.1 and 1.1), not a position whose uvs differ otherwise (islands of an atlas).
TEST(MeshChecks, FindsUvWrapSeams) {
  EXPECT_TRUE(uv_strip(true).uv_wrap_seam);
  EXPECT_FALSE(uv_strip(false).uv_wrap_seam);
  const Mesh triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}},
                      {},
                      {{0.1f, 0.25}, {0.5, 0.25}, {0.1, 0.75}, {0, 0}},
                      {{0, 1, 2}}};
  const auto seam = [&](Vec2d last) {
    Mesh mesh = triangle;
    mesh.uvs.back() = last;
    prepare_mesh(mesh, "triangle");
    return mesh.uv_wrap_seam;
  };
  EXPECT_TRUE(seam({1.1f, 0.25}));
  EXPECT_TRUE(seam({0.1f, -1.75}));
  EXPECT_TRUE(seam({-2.9, 3.25}));
  EXPECT_FALSE(seam({0.1f, 0.25}));  // the same uv: no seam
  EXPECT_FALSE(seam({0.6, 0.25}));
  EXPECT_FALSE(seam({1.1, 0.5}));
}

// The derivatives of a plane seen head-on are one pixel's size at its distance, at every pixel.
TEST(MeshRender, HeadOnPlaneDerivativesArePixelSize) {
  Camera camera;
  camera.eye = {0.25, -0.5, 5.0};
  camera.target = {0.25, -0.5, 0.0};
  const PixelRays rays = pixel_rays(camera, 64, 48);
  const double pixel = 5.0 * 2.0 * std::tan(20.0 * std::acos(-1.0) / 180.0) / 48.0;
  for (const auto& [x, y] : {std::pair{0, 0}, {31, 23}, {63, 47}, {10, 40}}) {
    const Vec3d d = rays.direction(x, y);
    const double t = 5.0 / -d.z;  // the plane z = 0
    const PlaneHit hit = plane_differentials(rays, d, t, {0.0, 0.0, 1.0});
    EXPECT_NEAR(hit.dpdx.x, pixel, 1e-12);
    EXPECT_NEAR(hit.dpdx.y, 0.0, 1e-12);
    EXPECT_NEAR(hit.dpdx.z, 0.0, 1e-12);
    EXPECT_NEAR(hit.dpdy.x, 0.0, 1e-12);
    EXPECT_NEAR(hit.dpdy.y, -pixel, 1e-12);  // picture y runs down, world y up
    EXPECT_NEAR(hit.dpdy.z, 0.0, 1e-12);
  }
  // Tilted by 60 degrees about x, the plane stretches dp/dy by 1 / cos(60) at the centre line.
  const Vec3d n{0.0, std::sin(std::acos(-1.0) / 3.0), std::cos(std::acos(-1.0) / 3.0)};
  const Vec3d d = rays.direction(32, 24) - (rays.step_x + rays.step_y) * 0.5;  // the centre
  const PlaneHit tilted = plane_differentials(rays, d, 5.0, n);
  EXPECT_NEAR(length(tilted.dpdy), pixel / std::cos(std::acos(-1.0) / 3.0), 1e-9);
}

TEST(MeshRender, TangentFieldIsOrthonormalEverywhere) {
  for (const Vec3d n : {Vec3d{0, 1, 0}, Vec3d{0, -1, 0}, Vec3d{1, 0, 0}, Vec3d{0, 0, 1},
                        normalized(Vec3d{1, 2, 3}), normalized(Vec3d{1e-9, 1, 0})}) {
    const Vec3d t = surface_tangent(n);
    EXPECT_NEAR(length(t), 1.0, 1e-12);
    EXPECT_NEAR(dot(t, n), 0.0, 1e-12);
  }
}

TEST(MeshRender, SameBytesWhateverTheThreadCount) {
  for (const char* name : {"sphere.obj", "scan.obj"}) {
    const Mesh mesh = read_mesh(kMeshes + name);
    const Camera camera = orbit_camera(mesh, 30.0, 20.0, 1.0, 96, 80);
    MeshRenderOptions options;
    options.texture_scale = default_texture_scale(mesh) / 8.0;
    ImageF reference(96, 80, 3);
    options.threads = 1;
    render_mesh(tiling_model(), mesh, camera, options, 5, reference.view());
    int covered = 0;
    for (int y = 0; y < 80; ++y)
      for (int x = 0; x < 96; ++x) covered += reference.view().at(x, y, 0) != 0.2f;
    EXPECT_GT(covered, 96 * 80 / 4) << name;  // the framed mesh fills much of the picture
    EXPECT_LT(covered, 96 * 80) << name;      // and the background shows around it
    for (const int threads : {2, 3, 8}) {
      ImageF image(96, 80, 3);
      options.threads = threads;
      render_mesh(tiling_model(), mesh, camera, options, 5, image.view());
      EXPECT_TRUE(test_support::same_bytes(reference, image)) << name << ", " << threads;
    }
  }
}

// The background is the value an output file shows: as it is for data, decoded from sRGB for a
// model of colour, whose render is linear light encoded into its PNG (before, such a render's
// background showed 124 of 255 where a data model's showed 51).
TEST(MeshRender, TheBackgroundLooksTheSameForEveryColourSpace) {
  const Mesh mesh = read_mesh(kMeshes + "sphere.obj");
  const Camera camera = orbit_camera(mesh, 30.0, 20.0, 1.0, 32, 24);
  MeshRenderOptions options;
  for (const ColourSpace space : {ColourSpace::data, ColourSpace::srgb}) {
    const Model model = with_colour_space(tiling_model(), space);
    ImageF image(32, 24, 3);
    render_mesh(model, mesh, camera, options, 5, image.view());
    const float expected = space == ColourSpace::srgb ? srgb_decode(0.2f) : 0.2f;
    EXPECT_EQ(mesh_background(model, options), expected);
    EXPECT_EQ(image.at(0, 0, 0), expected) << "the corner shows the background";
  }
}

// The uv strip seen head-on from in front of its seam, a picture 128 x 64 pixels and 0.25 mesh
// units wide, its seam between columns 63 and 64. The texture scale is no whole number (a
// period's pixels need not be): 0.29 exemplar pixels a picture pixel. Zoomed in, neighbouring
// pixels are close and a seam stands out.
constexpr int kStripWidth = 128;
constexpr int kStripHeight = 64;
constexpr double kStripScale = 150.5;

ImageF render_strip(const Model& model, const Mesh& mesh, bool periodic, std::uint32_t seed) {
  const PixelRays unit = pixel_rays({{0, 0, 1}, {0, 0, 0}}, kStripWidth, kStripHeight);
  Camera camera;
  camera.eye = {1.0, 0.5, 0.25 / (kStripWidth * length(unit.step_x))};
  camera.target = {1.0, 0.5, 0.0};
  MeshRenderOptions options;
  options.mapping = std::nullopt;  // the uv mapping
  options.texture_scale = kStripScale;
  options.periodic = periodic;
  ImageF image(kStripWidth, kStripHeight, mesh_output_channels(model));
  render_mesh(model, mesh, camera, options, seed, image.view());
  return image;
}

// The step across the strip's seam (columns 63 to 64) over the mean step between the other
// neighbouring columns, each the sum of absolute differences over rows and channels.
double seam_step(const ImageF& image) {
  std::vector<double> steps;
  for (int x = 0; x + 1 < image.width(); ++x) {
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
      for (int c = 0; c < image.channels(); ++c)
        sum += std::abs(image.at(x + 1, y, c) - image.at(x, y, c));
    steps.push_back(sum);
  }
  const double seam = steps[kStripWidth / 2 - 1];
  const double interior = (std::accumulate(steps.begin(), steps.end(), 0.0) - seam) /
                          static_cast<double>(steps.size() - 1);
  return seam / interior;
}

// The models of the seam test: each method's of grass_lawn_128 (quick settings, as in
// periodic_test.cpp) and the rock material (albedo, its normal map derived from its height, so
// that the bump samples the height around each fragment too).
std::vector<std::pair<std::string, Model>> seam_models() {
  std::vector<std::pair<std::string, Model>> models;
  const ImageF grass = read_image(STOCHTEX_TEXTURE_DIR "/grass_lawn_128.png");
  for (const auto& [method, params] : std::initializer_list<std::pair<const char*, ParamValues>>{
           {"texton", {{"support", 32}, {"iterations", 10}}},
           {"tiling", {}},
           {"lrp", {{"cosines", 4}, {"strata", 2}}},
           {"gabor", {{"impulses", 128}, {"iterations", 5}}}})
    models.emplace_back(method, analyze(method, grass.view(), params, 1));
  const std::vector<std::string> names = {"albedo", "normal", "height"};
  std::vector<ImageF> images;
  for (const std::string& name : names)
    images.push_back(read_image(test_support::kRock + name + ".png"));
  std::vector<MaterialMap> maps;
  for (std::size_t i = 0; i < names.size(); ++i)
    maps.push_back({names[i], {}, images[i].view(), names[i] + ".png"});
  models.emplace_back("rock material",
                      analyze_material("texton", maps, {{"iterations", 3}, {"support", 32}}, 0));
  return models;
}

// The uv mapping evaluates the model at uv * texture scale, so where u jumps from 1 to 0 the
// texture does too: the default render steps at the seam. With `periodic` the texture repeats
// every uv unit and the seam steps as the interior does. Measured over seeds 1 to 8, the seam
// step over the interior's mean: default 2.13 to 7.86 (per model at least: texton 2.54, tiling
// 3.67, lrp 2.25, gabor 2.13, the material 2.99), periodic 0.50 to 1.41 (at most: texton 1.40,
// tiling 0.78, lrp 1.22, gabor 1.27, the material 1.41). The bound 1.75 lies between, about 0.35
// from either; seeds 1 to 4 are tested.
TEST(MeshRender, PeriodicUvHidesTheWrapSeam) {
  const Mesh strip = uv_strip(true);
  for (const auto& [name, model] : seam_models()) {
    for (std::uint32_t seed = 1; seed <= 4; ++seed) {
      const double plain = seam_step(render_strip(model, strip, false, seed));
      const double periodic = seam_step(render_strip(model, strip, true, seed));
      EXPECT_GT(plain, 1.75) << name << ", seed " << seed;
      EXPECT_LT(periodic, 1.75) << name << ", seed " << seed;
    }
  }
}

TEST(MeshRender, RefusesBeforeWork) {
  const Mesh scan = read_mesh(kMeshes + "scan.obj");
  const Camera camera = orbit_camera(scan, 0.0, 0.0, 1.0, 8, 8);
  ImageF image(8, 8, 3);
  image.view().at(0, 0, 0) = 42.0f;
  MeshRenderOptions options;
  options.mapping = SurfaceMapping::surface;
  EXPECT_THROW(render_mesh(white_noise_model("lrp"), scan, camera, options, 0, image.view()),
               std::invalid_argument);
  options.mapping = std::nullopt;  // uv, and the scan has none
  EXPECT_THROW(render_mesh(tiling_model(), scan, camera, options, 0, image.view()),
               std::invalid_argument);
  options.mapping = SurfaceMapping::triplanar_linear;
  options.texture_scale = 1e10;  // beyond 2^32 exemplar pixels
  EXPECT_THROW(render_mesh(tiling_model(), scan, camera, options, 0, image.view()),
               std::invalid_argument);
  // --periodic: the uv mapping only, and models evaluate_periodic takes.
  const Mesh sphere = read_mesh(kMeshes + "sphere.obj");
  options.texture_scale = 64.0;
  options.periodic = true;
  EXPECT_THROW(render_mesh(tiling_model(), sphere, camera, options, 0, image.view()),
               std::invalid_argument);
  EXPECT_NE(mesh_periodic_refusal(tiling_model(), options).find("uv mapping"), std::string::npos);
  options.mapping = std::nullopt;
  EXPECT_EQ(mesh_periodic_refusal(tiling_model(), options), "");
  EXPECT_EQ(image.view().at(0, 0, 0), 42.0f);
  EXPECT_THROW(orbit_camera(scan, 0.0, 90.0, 1.0, 8, 8), std::invalid_argument);
  Camera degenerate;
  EXPECT_THROW(pixel_rays(degenerate, 8, 8), std::invalid_argument);
}

}  // namespace
}  // namespace stochtex::mesh_test
