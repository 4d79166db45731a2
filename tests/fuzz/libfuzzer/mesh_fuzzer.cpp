// Coverage-guided fuzzing (libFuzzer) of the OBJ reader and of rendering after it (docs/meshes.md,
// docs/design.md §9): every input must be refused with stochtex::Error, or read as a mesh that
// renders finite values with linear triplanar mapping and, when it has texture coordinates, with
// them. Seeds: tests/fuzz/corpus/mesh. Built by scripts/sanitize.sh.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "input_file.hpp"
#include "stochtex/mesh_render.hpp"
#include "stochtex/stochtex.hpp"

namespace {

const stochtex::Model& model() {
  static const stochtex::Model tiling = [] {
    stochtex::ImageF exemplar(16, 16, 3);
    for (std::size_t i = 0; i < exemplar.pixels().size(); ++i)
      exemplar.pixels()[i] = static_cast<float>((i * 37) % 101) / 100.0f;
    return stochtex::analyze("tiling", exemplar.view(), {}, 0);
  }();
  return tiling;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& input_path = write_input_file("mesh", ".obj", data, size);
  try {
    const stochtex::Mesh mesh = stochtex::read_mesh(input_path);
    stochtex::ImageF image(5, 4, 3);
    stochtex::MeshRenderOptions options;
    options.threads = 1;
    options.texture_scale = 3.0;
    for (const bool uv : {false, true}) {
      if (uv && mesh.uvs.empty()) continue;
      options.mapping =
          uv ? std::nullopt : std::optional(stochtex::SurfaceMapping::triplanar_linear);
      try {
        stochtex::render_mesh(model(), mesh, stochtex::orbit_camera(mesh, 30.0, 20.0, 1.0, 5, 4),
                              options, 1, image.view());
      } catch (const std::invalid_argument&) {
        continue;  // a mesh the texture scale puts beyond the precise range: refused before work
      }
      for (const float value : image.pixels())
        if (!std::isfinite(value)) std::abort();
    }
  } catch (const stochtex::Error&) {
  }
  return 0;
}
