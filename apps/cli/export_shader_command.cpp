// `stochtex export-shader MODEL -o DIR`: a self-contained GLSL file, the model's data images and a
// README for engines (include/stochtex/gpu.hpp).

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <system_error>

#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "io/image_io.hpp"
#include "stochtex/stochtex.hpp"
#ifdef STOCHTEX_WITH_GL
#include "stochtex/gpu.hpp"
#endif

namespace stochtex::cli {
namespace {

void export_shader_files([[maybe_unused]] const std::string& model_path,
                         [[maybe_unused]] const std::string& output) {
#ifdef STOCHTEX_WITH_GL
  const ShaderExport files = export_shader(load_model(model_path));
  const std::filesystem::path folder(output);
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error)
    throw Error(ErrorCode::io,
                fmt::format("cannot create the folder '{}': {}", output, error.message()));
  write_file_atomically(folder / files.glsl_file_name, files.glsl);
  for (const auto& [name, image] : files.images)
    write_image(folder / (name + ".exr"), image.view());
  write_file_atomically(folder / "README.md", files.readme);
  fmt::print(stderr, "wrote {} ({}, {} image(s), README.md)\n", output, files.glsl_file_name,
             files.images.size());
#else
  throw Error(ErrorCode::io,
              "this stochtex was built without the OpenGL backend "
              "(STOCHTEX_BUILD_GL=OFF), which export-shader needs");
#endif
}

}  // namespace

Command add_export_shader_command(CLI::App& app) {
  struct Options {
    std::string model;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("export-shader",
                                     "model file -> self-contained GLSL + data images for engines");
  command->add_option("MODEL", options->model, "model file (.stx)")->required();
  command->add_option("-o,--output", options->output, "folder to write (created if missing)")
      ->required();
  return {command, [options] {
            export_shader_files(options->model, options->output);
            return 0;
          }};
}

}  // namespace stochtex::cli
