// `stochtex render-mesh MESH -o IMAGE --model MODEL`: a picture of an OBJ mesh textured by a model
// (docs/meshes.md), on the CPU reference or the OpenGL backend.

#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "io/image_io.hpp"
#include "progress.hpp"
#include "renderer/backends.hpp"
#include "stochtex/mesh_render.hpp"

namespace stochtex::cli {
namespace {

struct Options {
  std::string mesh;
  std::string model;
  std::string output;
  std::string mapping = "triplanar-linear";
  std::string camera = "30,20";
  std::string size = "512x512";
  std::string backend = "cpu";
  std::uint32_t seed = 0;
  double texture_scale = 0.0;
  SurfaceOptions surface;
  int threads = 0;
  bool periodic = false;
};

// --camera: AZIMUTH,ELEVATION[,DISTANCE] (degrees, degrees, framings) or EX,EY,EZ,TX,TY,TZ (eye
// and target in mesh units); `mesh` is needed for the orbit only, so it is read by then.
std::vector<double> camera_numbers(const std::string& text) {
  static const std::regex number(R"(\s*([-+0-9.eE]+)\s*)");
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    std::smatch match;
    std::size_t used = 0;
    double value = 0.0;
    try {
      if (!std::regex_match(part, match, number)) return {};
      value = std::stod(match[1], &used);
    } catch (const std::exception&) {
      return {};
    }
    if (used != match[1].str().size() || !std::isfinite(value)) return {};
    values.push_back(value);
    start = comma + 1;
  }
  if (values.size() != 2 && values.size() != 3 && values.size() != 6) return {};
  return values;
}

Camera make_camera(const std::vector<double>& numbers, const Mesh& mesh, const Size& size) {
  if (numbers.size() == 6) {
    Camera camera;
    camera.eye = {numbers[0], numbers[1], numbers[2]};
    camera.target = {numbers[3], numbers[4], numbers[5]};
    if (camera.eye.x == camera.target.x && camera.eye.z == camera.target.z)
      camera.up = {0.0, 0.0, -1.0};  // looking straight down or up: -z is the picture's top
    return camera;
  }
  return orbit_camera(mesh, numbers[0], numbers[1], numbers.size() == 3 ? numbers[2] : 1.0,
                      size.width, size.height);
}

int run(const Options& o) {
  const Size size = output_size(o.size);
  const std::vector<double> camera = camera_numbers(o.camera);
  if (camera.empty())
    throw std::invalid_argument(
        "--camera must be AZIMUTH,ELEVATION[,DISTANCE] (degrees, degrees, framings) or "
        "EX,EY,EZ,TX,TY,TZ (eye and target in mesh units), not '" +
        o.camera + "'");
  std::optional<SurfaceMapping> mapping;
  if (o.mapping != "uv") mapping = mapping_from_name(o.mapping);
  const renderer::Backend backend =
      o.backend == "gl" ? renderer::Backend::gl : renderer::Backend::cpu;
  renderer::check_backend_built(backend);
  const int threads = resolve_thread_count(o.threads);
  check_memory_budget(render_peak_bytes(size.width, size.height, 32, 1, threads),
                      fmt::format("rendering {} pixels on {} threads", o.size, threads),
                      "use fewer --threads or a smaller --size");
  check_output_path(o.output, true, {o.mesh, o.model});

  const Model model = load_model(o.model);
  int channels = 0;
  try {
    channels = mesh_output_channels(model);
  } catch (const Error& error) {
    throw Error(error.code(), o.model + ": " + error.what());
  }
  check_output_channels(o.output, channels);
  if (mapping && !supports_mapping(model, *mapping))
    throw std::invalid_argument(fmt::format(
        "{}: {} models have no {} mapping; use --mapping triplanar-linear or uv, which every "
        "method has",
        o.model, model.method(), o.mapping));
  // (a material is refused by render_mesh_gl with its own sentence)
  if (backend == renderer::Backend::gl && mapping && model.maps().empty() &&
      !renderer::backend_supports_mapping(backend, model, *mapping))
    throw std::invalid_argument(fmt::format(
        "{}: the gl backend has no GLSL {} mapping for {} models; use --backend cpu, or "
        "--mapping uv, which every method has on the gl backend",
        o.model, o.mapping, model.method()));
  MeshRenderOptions options;
  options.mapping = mapping;
  options.surface = o.surface;
  options.periodic = o.periodic;
  options.threads = threads;
  if (o.periodic) {
    renderer::check_periodic_backend(backend);
    if (const std::string refusal = mesh_periodic_refusal(model, options); !refusal.empty())
      throw std::invalid_argument("--periodic: " + refusal);
  }
  const Mesh mesh = read_mesh(o.mesh);
  if (mesh.skipped_triangles > 0)
    fmt::print(stderr,
               "stochtex render-mesh: warning: '{}': skipped {} degenerate triangle(s) of zero "
               "area, which cover no pixel\n",
               o.mesh, mesh.skipped_triangles);
  if (!mapping && mesh.uvs.empty())
    throw std::invalid_argument(
        "'" + o.mesh +
        "' has no texture coordinates (vt on every face corner), which --mapping uv needs; use "
        "--mapping triplanar-linear");
  if (!mapping && !o.periodic && mesh.uv_wrap_seam)
    fmt::print(stderr,
               "stochtex render-mesh: note: '{}' has a uv wrap seam (a position whose uvs differ "
               "by a whole number), where the texture steps; --periodic repeats it every uv unit "
               "and hides the seam\n",
               o.mesh);

  options.texture_scale =
      o.texture_scale > 0.0 ? o.texture_scale : (mapping ? default_texture_scale(mesh) : 1024.0);
  ImageF image(size.width, size.height, channels);
  const Camera view = make_camera(camera, mesh, size);
  {
    Progress progress("render-mesh ");
    options.progress = [&](double fraction) { progress(fraction); };
    renderer::render_mesh_on(backend, model, mesh, view, options, o.seed, image.view());
  }
  write_image(o.output, image.view(), 8, mesh_output_space(model));
  fmt::print(stderr, "wrote {}\n", o.output);
  return 0;
}

}  // namespace

Command add_render_mesh_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "render-mesh", "OBJ mesh + model file -> image of the textured mesh (docs/meshes.md)");
  command->add_option("MESH", options->mesh, "mesh file (.obj)")->required();
  command->add_option("-o,--output", options->output, "image to write (.png, .exr or .pfm)")
      ->required();
  command
      ->add_option("--model", options->model,
                   "model file (.stx); a material's colour map is shaded, bumped by its normal "
                   "map, its ambient light times its ao map (docs/materials.md)")
      ->required();
  command
      ->add_option("--mapping", options->mapping,
                   "surface (surface noise), triplanar (histogram-preserving, tiling), "
                   "triplanar-linear (every method) or uv (the mesh's texture coordinates, every "
                   "method)")
      ->capture_default_str()
      ->check(CLI::IsMember({"surface", "triplanar", "triplanar-linear", "uv"}));
  command
      ->add_option("--camera", options->camera,
                   "AZIMUTH,ELEVATION[,DISTANCE]: degrees about +y (0 = from +z) and above the "
                   "horizon, distance in framings (1 = the bounding sphere fits); or "
                   "EX,EY,EZ,TX,TY,TZ: eye and target in mesh units")
      ->capture_default_str();
  command->add_option("--size", options->size, "output size WIDTHxHEIGHT in pixels")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "32-bit seed of the random pattern")
      ->capture_default_str();
  command
      ->add_option("--texture-scale", options->texture_scale,
                   "exemplar pixels per mesh unit (per uv unit with --mapping uv); default: "
                   "1024 / the bounding box's largest side (1024 with uv)")
      ->check(finite_range(1e-9, 1e9));
  command
      ->add_option("--surface-mni", options->surface.surface_mni,
                   "surface noise: mean number of impulses per texton-sized cube, lambda r^3 "
                   "(texton paper section 6)")
      ->capture_default_str()
      ->check(finite_range(kMinSurfaceMni, kMaxSurfaceMni));
  command
      ->add_option("--sharpness", options->surface.triplanar_sharpness,
                   "triplanar mappings: the weight of axis k is |n_k|^sharpness, normalised")
      ->capture_default_str()
      ->check(finite_range(kMinTriplanarSharpness, kMaxTriplanarSharpness));
  command->add_flag(
      "--periodic", options->periodic,
      "--mapping uv: the texture repeats every uv unit (its period the texture scale), as an "
      "engine's repeat wrap, so that a seam where u or v jumps by a whole number (a UV sphere's) "
      "does not show; CPU backend only, each method's scalar evaluator (docs/meshes.md)");
  command->add_option("--threads", options->threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, kMaxThreads));
  command
      ->add_option("--backend", options->backend,
                   "cpu (the reference) or gl (OpenGL 4.5, headless: the mesh rasterised, each "
                   "fragment calling the method's GLSL; --mapping uv with every method, triplanar "
                   "with tiling; no materials)")
      ->capture_default_str()
      ->check(CLI::IsMember({"cpu", "gl"}));
  return {command, [options] { return run(*options); }};
}

}  // namespace stochtex::cli
