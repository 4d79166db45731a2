// Materials on meshes (render_mesh with a material model, docs/materials.md "On a mesh"): the
// surface-gradient arithmetic of bump mapping, a plane under constant slopes lit as the perturbed
// normal computed by hand, a plane seen head-on lit as render_maps' normal map says, derived and
// synthesised normal maps of the same relief, and the refusals.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "model/model_data.hpp"
#include "registry.hpp"
#include "render/mesh_shading.hpp"
#include "stochtex/material.hpp"
#include "stochtex/mesh_render.hpp"
#include "stochtex/stochtex.hpp"
#include "test_support.hpp"

namespace stochtex::mesh_material_test {
namespace {

using test_support::kMeshes;
using test_support::kRock;

void expect_near(const Vec3d& a, const Vec3d& b, double tolerance, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tolerance) << what;
  EXPECT_NEAR(a.y, b.y, tolerance) << what;
  EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

MapInfo map_info(const std::string& name, MapKind kind, int channels) {
  MapInfo map;
  map.name = name;
  map.kind = kind;
  map.channels = channels;
  return map;
}

// The same model data read through other maps (the channels and their values do not change).
Model with_maps(const Model& model, std::vector<MapInfo> maps) {
  ModelData data = model.data();
  data.maps = std::move(maps);
  return Model(std::make_shared<const ModelData>(std::move(data)));
}

// The rock material's maps `names`, analysed by `method`.
Model rock(const std::string& method, const std::vector<std::string>& names,
           const ParamValues& params = {}, const MaterialOptions& options = {}) {
  std::vector<ImageF> images;
  for (const std::string& name : names) images.push_back(read_image(kRock + name + ".png"));
  std::vector<MaterialMap> maps;
  for (std::size_t i = 0; i < names.size(); ++i)
    maps.push_back({names[i], {}, images[i].view(), names[i] + ".png"});
  return analyze_material(method, maps, params, 0, options);
}

// The square |x|, |y| <= 1 of the plane z = 0, uv = (x, -y) (so that texture rows run down the
// picture of a camera on +z with +y up), and a camera on +z whose picture it fills.
Mesh plane() {
  Mesh mesh;
  for (const auto& [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
    mesh.positions.push_back({x, y, 0.0});
    mesh.uvs.push_back({x, -y});
  }
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  prepare_mesh(mesh, "plane");
  return mesh;
}
constexpr double kDistance = 2.0;  // the camera's, from the plane: the picture spans |x| < 0.73
Camera head_on() {
  Camera camera;
  camera.eye = {0.0, 0.0, kDistance};
  return camera;
}

// Every route to a surface gradient gives the tangent part of a linear height's gradient.
TEST(MeshBump, SurfaceGradientsOfALinearHeight) {
  const Vec3d n = normalized({1.0, 2.0, 3.0});
  const Vec3d t = normalized(cross(n, {1.0, 0.0, 0.0}));
  const Vec3d b = cross(n, t);
  const Vec3d a{0.3, -0.2, 0.5};  // h(q) = a . q
  const Vec3d tangent_part = a - n * dot(n, a);
  expect_near(surface_gradient(n, a), tangent_part, 1e-15, "volume gradient");
  const Vec3d dpdx = t * 2.0 + b * 0.5;
  const Vec3d dpdy = t * -0.3 + b * 1.5;
  expect_near(surface_gradient_from_steps(n, dpdx, dpdy, dot(a, dpdx), dot(a, dpdy)), tangent_part,
              1e-14, "steps");
  // Steps off the tangent plane count by their projections on it.
  expect_near(
      surface_gradient_from_steps(n, dpdx + n * 0.7, dpdy - n * 0.2, dot(a, dpdx), dot(a, dpdy)),
      tangent_part, 1e-14, "steps off the plane");
  expect_near(surface_gradient_from_steps(n, dpdx, dpdx * 2.0, 1.0, 2.0), {}, 0.0, "parallel");

  // Texture coordinates that keep angles: the unit square of uv spans L = 3 units turned by 0.4
  // radians, 64 exemplar pixels per uv unit. One exemplar pixel measures L / 64 on the surface, the
  // height is in those units: the texture gradient g bumps by g_x u + g_y v, u and v the unit
  // tangents along which p_x and p_y grow.
  const double turn = 0.4;
  const Vec3d u = t * std::cos(turn) + b * std::sin(turn);
  const Vec3d v = t * -std::sin(turn) + b * std::cos(turn);
  Mesh triangle;
  const Vec3d q0{0.5, -1.0, 2.0};
  triangle.positions = {q0, q0 + u * 3.0 + v * 0.5, q0 + v * 3.0 - u};
  triangle.uvs = {{0.0, 0.0}, {1.0, 0.5 / 3.0}, {-1.0 / 3.0, 1.0}};
  triangle.triangles = {{0, 1, 2}};
  const TextureGradients texture = texture_gradients(triangle, 0, 64.0);
  expect_near(texture.x, u * (64.0 / 3.0), 1e-12, "p_x's gradient");
  expect_near(texture.y, v * (64.0 / 3.0), 1e-12, "p_y's gradient");
  const Vec2d g{0.4, -0.7};
  expect_near(texture_surface_gradient(n, texture, g), u * g.x + v * g.y, 1e-14, "uv");
  expect_near(texture_surface_gradient(n, {u, u * 2.0}, g), {}, 0.0, "degenerate uv");

  // The texture gradient back from its changes along a footprint's steps.
  const Footprint footprint{{2.0, 0.5}, {-0.3, 1.5}};
  const Vec2d back =
      texture_gradient_from_steps(footprint, g.x * 2.0 + g.y * 0.5, g.x * -0.3 + g.y * 1.5);
  EXPECT_NEAR(back.x, g.x, 1e-15);
  EXPECT_NEAR(back.y, g.y, 1e-15);
  const Vec2d none = texture_gradient_from_steps({{1.0, 2.0}, {-2.0, -4.0}}, 1.0, 1.0);
  EXPECT_EQ(none.x, 0.0);
  EXPECT_EQ(none.y, 0.0);

  // Slopes s = (-n_x / n_z, -n_y / n_z) on the plane z = 0 with x and y its tangents: the
  // normal map's own normal.
  const Vec3d bumped = bumped_normal({0.0, 0.0, 1.0}, {0.6, -0.4, 0.0});
  expect_near(bumped, normalized({-0.6, 0.4, 1.0}), 1e-15, "bumped");
}

// A tiling model of an exemplar whose albedo is white noise, whose normal map's slopes are s up to
// 1e-6 and whose last channel is 0.4 up to 1e-6 (tiling renders every value within the
// exemplar's range), read as a material of albedo, normal map and ambient occlusion, and read
// without a normal map and with the last channel a scalar map of another name (render-mesh uses
// neither).
struct ConstantSlopes {
  Model bumped;
  Model flat;
};
constexpr double kOcclusion = 0.4;
ConstantSlopes constant_slopes(double sx, double sy) {
  std::mt19937 engine(4);
  std::normal_distribution<float> noise(0.5f, 0.1f);
  std::uniform_real_distribution<double> tiny(0.0, 1e-6);
  ImageF exemplar(32, 32, 6);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      for (int c = 0; c < 3; ++c) exemplar.at(x, y, c) = noise(engine);
      exemplar.at(x, y, 3) = static_cast<float>(sx + tiny(engine));
      exemplar.at(x, y, 4) = static_cast<float>(sy + tiny(engine));
      exemplar.at(x, y, 5) = static_cast<float>(kOcclusion + tiny(engine));
    }
  const Model bumped = analyze_exemplar(
      "tiling", exemplar.view(), {}, 3, "constant slopes", {},
      {map_info("albedo", MapKind::colour, 3), map_info("normal", MapKind::normal, 2),
       map_info("ao", MapKind::scalar, 1)});
  return {bumped, with_maps(bumped, {map_info("albedo", MapKind::colour, 3),
                                     map_info("slope_x", MapKind::colour, 1),
                                     map_info("slope_y", MapKind::colour, 1),
                                     map_info("roughness", MapKind::scalar, 1)})};
}

// A plane under a normal map of constant slopes s and an ambient occlusion a is lit as computed by
// hand: 0.3 a + 0.7 max(0, n.l) with n = normalize(-s_x, -s_y, 1) through the uvs (x right, y up
// the picture, as the normal map's), normalize(-s_x, s_y, 1) through the triplanar projection on
// (x, y), whose texture y runs up the picture (world y) where the image's runs down. The same
// albedo without normal map or ambient occlusion (0.3 + 0.7 n.l) gives each pixel's albedo.
TEST(MeshBump, ConstantSlopesLightAPlaneAsTheirNormal) {
  const double sx = 0.6, sy = -0.4;
  const ConstantSlopes models = constant_slopes(sx, sy);
  const Mesh mesh = plane();
  constexpr int kSide = 40;
  const Vec3d light = light_direction(pixel_rays(head_on(), kSide, kSide));
  for (const bool uv : {true, false}) {
    MeshRenderOptions options;
    if (uv) options.mapping = std::nullopt;
    options.texture_scale = 40.0;
    ImageF bumped(kSide, kSide, 3), flat(kSide, kSide, 3);
    render_mesh(models.bumped, mesh, head_on(), options, 2, bumped.view());
    render_mesh(models.flat, mesh, head_on(), options, 2, flat.view());
    const Vec3d n = normalized({-sx, uv ? -sy : sy, 1.0});
    const double expected = 0.3 * kOcclusion + 0.7 * std::max(0.0, dot(n, light));
    const double unbumped = 0.3 + 0.7 * light.z;
    double largest = 0.0;
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x)
        for (int c = 0; c < 3; ++c) {
          const double albedo = flat.at(x, y, c) / unbumped;
          largest = std::max(largest, std::abs(bumped.at(x, y, c) - albedo * expected));
        }
    // The maps' 1e-6 spread and float rounding (measured: 1.8e-7 uv, 5.7e-7 triplanar-linear).
    EXPECT_LT(largest, 2e-6) << (uv ? "uv" : "triplanar-linear");
    // The bump shows: n.l against the unbumped normal's (measured: 0.35 and -0.12 apart).
    EXPECT_GT(std::abs(dot(n, light) - light.z), 0.1) << (uv ? "uv" : "triplanar-linear");
  }
}

// A plane seen head-on samples a regular grid of the texture: through the uvs, every pixel is lit
// as render_maps' maps of that grid say (the albedo times the Lambert of its normal map), for a
// derived normal map (texton: the height's central differences one footprint apart, as
// render_maps takes them one grid step apart) and a synthesised one (tiling: two slopes).
TEST(MeshBump, HeadOnPlaneIsLitAsRenderMapsSays) {
  const Mesh mesh = plane();
  constexpr int kSide = 48;
  const PixelRays rays = pixel_rays(head_on(), kSide, kSide);
  const Vec3d light = light_direction(rays);
  const double pixel = kDistance * length(rays.step_x);  // one pixel on the plane
  MeshRenderOptions options;
  options.mapping = std::nullopt;
  options.texture_scale = 1.5 / pixel;  // 1.5 exemplar pixels a pixel
  const Grid grid{{-0.75 * kSide, -0.75 * kSide}, 1.5, kSide, kSide};
  for (const auto& [method, derived] : {std::pair{"texton", true}, {"tiling", false}}) {
    const Model model = rock(method, {"albedo", "normal", "height"},
                             derived ? ParamValues{{"iterations", 3}} : ParamValues{});
    ASSERT_EQ(model.maps()[1].derived_from.empty(), !derived) << method;
    ImageF picture(kSide, kSide, 3);
    render_mesh(model, mesh, head_on(), options, 5, picture.view());
    const std::vector<NamedImage> maps = render_maps(
        model, grid, [&](const Grid& part, ImageView<float> out) { render(model, part, 5, out); });
    double largest = 0.0;
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const ImageF& normal = maps[1].image;
        const Vec3d n = normalized({2.0 * normal.at(x, y, 0) - 1.0, 2.0 * normal.at(x, y, 1) - 1.0,
                                    2.0 * normal.at(x, y, 2) - 1.0});
        const double lit = 0.3 + 0.7 * std::max(0.0, dot(n, light));
        for (int c = 0; c < 3; ++c)
          largest =
              std::max(largest, std::abs(picture.at(x, y, c) - maps[0].image.at(x, y, c) * lit));
      }
    // The mesh's positions come from ray casts in double (within 1e-12 of the grid's), and the
    // normal map's 0.5 + 0.5 n is rounded to float (measured: 6.5e-8 texton, 7.6e-8 tiling).
    EXPECT_LT(largest, 1e-6) << method;
  }
}

// The correlation, over the pixels both cover, of the light that bumps add to two renders of the
// same colour map: a / a_flat against b / b_flat (channel 0).
double bump_correlation(const ImageF& a, const ImageF& b, const ImageF& flat) {
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int y = 0; y < flat.height(); ++y)
    for (int x = 0; x < flat.width(); ++x) {
      if (flat.at(x, y, 0) == 0.2f || !(flat.at(x, y, 0) > 0.0f)) continue;  // background
      const double ra = a.at(x, y, 0) / flat.at(x, y, 0);
      const double rb = b.at(x, y, 0) / flat.at(x, y, 0);
      n += 1, sa += ra, sb += rb, saa += ra * ra, sbb += rb * rb, sab += ra * rb;
    }
  const double cov = sab / n - sa / n * sb / n;
  return cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

// One model read three ways: with its synthesised normal map (two slopes), with a normal map
// derived from its own height instead, and without a normal map. Its slopes follow its height as
// the exemplar's do (tiling copies both from the same patches, texton noise is linear in its
// texton), so on every mapping the two bumps light the mesh alike, through the frames that each
// mapping gives the stored slopes and the footprint steps the derived ones.
TEST(MeshBump, DerivedAndSynthesisedNormalsAgree) {
  const Model derived = rock("texton", {"albedo", "normal", "height"}, {{"iterations", 3}});
  const double k = derived.maps()[1].slope_scale;
  const Mesh sphere = read_mesh(kMeshes + "sphere.obj");
  const Mesh scan = read_mesh(kMeshes + "scan.obj");
  struct Case {
    std::string name;
    std::string method;
    const Mesh* mesh;
    std::optional<SurfaceMapping> mapping;
  };
  for (const Case& c : {Case{"uv", "tiling", &sphere, std::nullopt},
                        Case{"triplanar-linear", "tiling", &scan, SurfaceMapping::triplanar_linear},
                        Case{"triplanar", "tiling", &scan, SurfaceMapping::triplanar},
                        Case{"surface", "texton", &scan, SurfaceMapping::surface}}) {
    const Model stored = rock(c.method, {"albedo", "normal", "height"},
                              c.method == "texton" ? ParamValues{{"iterations", 3}} : ParamValues{},
                              {.derive_normals = false});
    MapInfo from_height = map_info("normal", MapKind::normal, 0);
    from_height.derived_from = "height";
    from_height.slope_scale = k;
    const Model own = with_maps(
        stored, {map_info("albedo", MapKind::colour, 3), map_info("slope_x", MapKind::colour, 1),
                 map_info("slope_y", MapKind::colour, 1), map_info("height", MapKind::height, 1),
                 from_height});
    const Model flat = with_maps(
        stored, {map_info("albedo", MapKind::colour, 3), map_info("slope_x", MapKind::colour, 1),
                 map_info("slope_y", MapKind::colour, 1), map_info("height", MapKind::height, 1)});
    MeshRenderOptions options;
    options.mapping = c.mapping;
    options.texture_scale = c.mapping ? default_texture_scale(*c.mesh) / 4.0 : 256.0;
    const Camera camera = orbit_camera(*c.mesh, 30.0, 20.0, 1.0, 96, 96);
    ImageF a(96, 96, 3), b(96, 96, 3), f(96, 96, 3);
    render_mesh(stored, *c.mesh, camera, options, 1, a.view());
    render_mesh(own, *c.mesh, camera, options, 1, b.view());
    render_mesh(flat, *c.mesh, camera, options, 1, f.view());
    // Measured: 0.95 uv, 0.91 triplanar-linear, 0.92 triplanar, 0.85 surface; with the stored
    // slopes' x turned the other way 0.86, 0.51, 0.55, 0.54, and their y -0.40, -0.12, -0.14,
    // -0.13 (the frames are right, and each mapping's frame is tested).
    EXPECT_GT(bump_correlation(a, b, f), c.mapping ? 0.75 : 0.92) << c.method << " on " << c.name;
    // And the bump shows: it changes most covered pixels by more than float rounding (measured:
    // over 90 %; the others lie where both normals face away from the light).
    int covered = 0, changed = 0;
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x)
        if (f.at(x, y, 0) != 0.2f) {
          ++covered;
          changed += std::abs(a.at(x, y, 0) - f.at(x, y, 0)) > 1e-3f;
        }
    EXPECT_GT(changed, covered * 4 / 5) << c.method << " on " << c.name;
  }
}

// A material's picture is the same bytes whatever the thread count (derived and stored normals).
TEST(MeshBump, SameBytesWhateverTheThreadCount) {
  const Mesh sphere = read_mesh(kMeshes + "sphere.obj");
  const Camera camera = orbit_camera(sphere, 30.0, 20.0, 1.0, 80, 64);
  for (const Model& model :
       {rock("texton", {"albedo", "normal", "height", "ao"}, {{"iterations", 3}}),
        rock("tiling", {"albedo", "normal"})}) {
    for (const std::optional<SurfaceMapping> mapping :
         {std::optional<SurfaceMapping>(), std::optional(SurfaceMapping::triplanar_linear)}) {
      MeshRenderOptions options;
      options.mapping = mapping;
      options.texture_scale = 256.0;
      ImageF reference(80, 64, 3);
      options.threads = 1;
      render_mesh(model, sphere, camera, options, 4, reference.view());
      ImageF image(80, 64, 3);
      options.threads = 3;
      render_mesh(model, sphere, camera, options, 4, image.view());
      EXPECT_TRUE(test_support::same_bytes(reference, image)) << model.method();
    }
  }
}

// A material without a colour map is refused with a sentence before any work; the picture of a
// material has its colour map's channels.
TEST(MeshBump, AMaterialWithoutColourIsRefused) {
  const Model relief = rock("tiling", {"normal", "height"});
  const Mesh sphere = read_mesh(kMeshes + "sphere.obj");
  const Camera camera = orbit_camera(sphere, 0.0, 0.0, 1.0, 8, 8);
  ImageF image(8, 8, 3);
  image.view().at(0, 0, 0) = 42.0f;
  try {
    render_mesh(relief, sphere, camera, {}, 0, image.view());
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::invalid_input);
    EXPECT_NE(std::string(error.what()).find("has none (its maps: normal, height)"),
              std::string::npos)
        << error.what();
  }
  EXPECT_EQ(image.view().at(0, 0, 0), 42.0f);
  EXPECT_THROW(mesh_output_channels(relief), Error);
  const Model rough = rock("tiling", {"roughness", "albedo"});
  EXPECT_EQ(mesh_output_channels(rough), 3);
  ImageF four(8, 8, 4);  // the model's channels are not the picture's
  EXPECT_THROW(render_mesh(rough, sphere, camera, {}, 0, four.view()), std::invalid_argument);
  EXPECT_EQ(mesh_output_channels(test_support::white_noise_model("lrp")), 3);
}

}  // namespace
}  // namespace stochtex::mesh_material_test
