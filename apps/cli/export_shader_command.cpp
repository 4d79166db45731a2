// `stochtex export-shader MODEL -o DIR [--variant exact|fast] [--language NAME]`: a
// self-contained shader library, its wrappers, the model's data images and a README for engines
// (include/stochtex/gpu.hpp), in a language of the table src/gl/languages.hpp.

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "gl/languages.hpp"
#include "io/image_io.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

// --language's help, from the table: each name with its title and targets.
std::string language_help() {
  std::string text;
  for (std::size_t i = 0; i < gl::kLanguageRows.size(); ++i) {
    const gl::LanguageRow& row = gl::kLanguageRows[i];
    text += fmt::format("{}{} ({} for {})",
                        i == 0 ? "" : (i + 1 == gl::kLanguageRows.size() ? " or " : ", "), row.name,
                        row.title, row.targets);
  }
  return text + "; both variants (`stochtex languages` lists them)";
}

// --language's choices: the table's names.
std::vector<std::string> language_choices() {
  std::vector<std::string> names;
  for (const gl::LanguageRow& row : gl::kLanguageRows) names.emplace_back(row.name);
  return names;
}

void export_shader_files([[maybe_unused]] const std::string& model_path,
                         [[maybe_unused]] const std::string& output,
                         [[maybe_unused]] const std::string& variant,
                         [[maybe_unused]] const std::string& language) {
#ifdef STOCHTEX_WITH_GL
  ShaderExportOptions options;
  options.variant = variant == "fast" ? ShaderVariant::fast : ShaderVariant::exact;
  options.language = gl::find_language(language)->language;
  ShaderExport files;
  try {
    files = export_shader(load_model(model_path), options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("{}: {}", model_path, e.what()));
  }
  // Every file's place is checked before the first is written, and the files are committed
  // together (docs/design.md section 6): all of them or none.
  const std::filesystem::path folder(output);
  AtomicFileSet written;
  written.create_folder(folder);
  std::vector<std::filesystem::path> targets = {folder / files.shader.name, folder / "README.md",
                                                folder / "manifest.json"};
  for (const TextFile& wrapper : files.wrappers) targets.push_back(folder / wrapper.name);
  for (const ShaderTexture& texture : files.textures)
    targets.push_back(folder / texture.file_name());
  for (const std::filesystem::path& target : targets) check_output_target(target);
  written.write(folder / files.shader.name, files.shader.text);
  for (const TextFile& wrapper : files.wrappers) written.write(folder / wrapper.name, wrapper.text);
  for (const ShaderTexture& texture : files.textures)
    write_image(written, folder / texture.file_name(), texture.image.view(),
                texture.encoding == TextureEncoding::png16 ? 16 : 8);
  written.write(folder / "README.md", files.readme);
  written.write(folder / "manifest.json", files.manifest);
  written.commit();
  fmt::print(stderr, "wrote {} ({}, {} image(s), README.md, manifest.json)\n", output,
             files.shader.name, files.textures.size());
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
    std::string language{gl::language_row(ShaderExportOptions{}.language).name};
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
  command->add_option("--language", options->language, language_help())
      ->capture_default_str()
      ->check(CLI::IsMember(language_choices()));
  return {command, [options] {
            export_shader_files(options->model, options->output, options->variant,
                                options->language);
            return 0;
          }};
}

}  // namespace stochtex::cli
