// `stochtex export-shader MODEL -o DIR [--variant exact|fast]`: a self-contained GLSL file, the
// model's data images and a README for engines (include/stochtex/gpu.hpp).

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
                         [[maybe_unused]] const std::string& output,
                         [[maybe_unused]] const std::string& variant) {
#ifdef STOCHTEX_WITH_GL
  ShaderExportOptions options;
  options.variant = variant == "fast" ? ShaderVariant::fast : ShaderVariant::exact;
  const ShaderExport files = export_shader(load_model(model_path), options);
  const std::filesystem::path folder(output);
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error)
    throw Error(ErrorCode::io,
                fmt::format("cannot create the folder '{}': {}", output, error.message()));
  write_file_atomically(folder / files.glsl_file_name, files.glsl);
  for (const ShaderTexture& texture : files.textures)
    write_image(folder / texture.file_name(), texture.image.view(),
                texture.encoding == TextureEncoding::png16 ? 16 : 8);
  write_file_atomically(folder / "README.md", files.readme);
  fmt::print(stderr, "wrote {} ({}, {} image(s), README.md)\n", output, files.glsl_file_name,
             files.textures.size());
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
    std::string variant = "exact";
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand("export-shader",
                                     "model file -> self-contained GLSL + data images for engines");
  command->add_option("MODEL", options->model, "model file (.stx)")->required();
  command->add_option("-o,--output", options->output, "folder to write (created if missing)")
      ->required();
  command
      ->add_option("--variant", options->variant,
                   "exact (the CPU's filter in the shader, to float rounding) or fast (the "
                   "--gl-filter hardware GLSL: PNG data, mip-mapped hardware filtering; equal to "
                   "the CPU in distribution)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "fast"}));
  return {command, [options] {
            export_shader_files(options->model, options->output, options->variant);
            return 0;
          }};
}

}  // namespace stochtex::cli
