// `stochtex export-web MODEL.stx... -o DIR [--variant exact|fast|both] [--force]`: the WebGL2
// viewer as static files for a set of models (docs/studio.md, "export-web"): DIR/index.html with
// its export/ files, DIR/viewer/ (viewer.js, group.js), DIR/models.json and each model's web
// export in DIR/models/<file stem>/<variant>/ (src/web/web_export.hpp).

#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "stochtex/error.hpp"
#ifdef STOCHTEX_WITH_GL
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "stochtex/model.hpp"
#include "web/assets.hpp"
#include "web/web_export.hpp"
#endif

namespace stochtex::cli {
namespace {

#ifdef STOCHTEX_WITH_GL
namespace fs = std::filesystem;

// One model's files, under models/<name>/<variant>/.
struct ExportedModel {
  std::string name;  // the model file's stem
  std::string file;  // the model file's name
  Model model;
  std::vector<std::pair<ShaderVariant, std::vector<web::WebFile>>> variants;
};

// The output folder may be new or empty; an existing non-empty one only with --force, which
// overwrites the files export-web writes and leaves every other file as it is.
void check_output_folder(const fs::path& folder, bool force) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(folder, error);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw std::invalid_argument(fmt::format(
        "'{}' exists and is not a folder; choose a new folder for -o", folder.string()));
  if (!force && !fs::is_empty(folder, error))
    throw std::invalid_argument(
        fmt::format("the folder '{}' exists and is not empty; choose a new or empty folder, or "
                    "pass --force to overwrite the files export-web writes in it",
                    folder.string()));
}

// The page's list of models: each one's name, file, method, channels and exported variants.
std::string models_json(const std::vector<ExportedModel>& models) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ExportedModel& exported : models) {
    nlohmann::ordered_json variants = nlohmann::ordered_json::array();
    for (const auto& [variant, files] : exported.variants)
      variants.push_back(web::variant_name(variant));
    list.push_back({{"name", exported.name},
                    {"file", exported.file},
                    {"method", exported.model.method()},
                    {"channels", exported.model.channels()},
                    {"variants", variants}});
  }
  return nlohmann::ordered_json{{"models", list}}.dump(1) + "\n";
}

#endif

void export_web_files([[maybe_unused]] const std::vector<std::string>& model_paths,
                      [[maybe_unused]] const std::string& output,
                      [[maybe_unused]] const std::string& variant, [[maybe_unused]] bool force) {
#ifdef STOCHTEX_WITH_GL
  std::vector<ShaderVariant> variants;
  if (variant != "fast") variants.push_back(ShaderVariant::exact);
  if (variant != "exact") variants.push_back(ShaderVariant::fast);
  const fs::path folder(output);
  check_output_folder(folder, force);

  std::vector<ExportedModel> models;
  std::set<std::string> names;
  for (const std::string& path : model_paths) {
    const fs::path file(path);
    const std::string name = file.stem().string();
    if (name.empty() || name.front() == '.')
      throw std::invalid_argument(fmt::format(
          "'{}': export-web names a model's folder after its file name, which must not be empty "
          "or start with '.'; rename the file",
          path));
    if (!names.insert(name).second)
      throw std::invalid_argument(fmt::format(
          "two models are named '{}' (the file name without its extension), and each needs a "
          "folder of its own; rename one of the files",
          name));
    models.push_back({name, file.filename().string(), load_model(file), {}});
  }
  for (ExportedModel& exported : models)
    for (const ShaderVariant v : variants) {
      try {
        exported.variants.emplace_back(v, web::web_export(exported.model, v));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format("{}: {}", exported.file, e.what()));
      } catch (const Error& e) {
        throw Error(e.code(), fmt::format("{}: {}", exported.file, e.what()));
      }
    }

  // Every file and its place, checked before the first is written.
  std::vector<std::pair<fs::path, std::string_view>> files;
  for (const EmbeddedFile& page : web::embedded_files()) {
    const std::string_view name = page.name;
    if (name == "export/index.html")
      files.emplace_back(folder / "index.html", page.text);
    else if (name.starts_with("export/") || name.starts_with("viewer/"))
      files.emplace_back(folder / fs::path(name), page.text);
  }
  const std::string list = models_json(models);
  files.emplace_back(folder / "models.json", list);
  for (const ExportedModel& exported : models)
    for (const auto& [v, web_files] : exported.variants)
      for (const web::WebFile& web_file : web_files)
        files.emplace_back(
            folder / "models" / exported.name / std::string(web::variant_name(v)) / web_file.name,
            web_file.bytes);
  AtomicFileSet written;  // all the files or none
  for (const auto& [target, bytes] : files) {
    written.create_folder(target.parent_path());
    check_output_target(target);
  }
  for (const auto& [target, bytes] : files) written.write(target, bytes);
  written.commit();
  fmt::print(stderr,
             "wrote {} ({} model(s), {} variant(s) each); serve it over HTTP to view it, e.g. "
             "python3 -m http.server -d {}\n",
             output, models.size(), variants.size(), output);
#else
  throw Error(ErrorCode::io,
              "this stochtex was built without the OpenGL backend "
              "(STOCHTEX_BUILD_GL=OFF), which export-web needs");
#endif
}

}  // namespace

Command add_export_web_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> models;
    std::string output;
    std::string variant = "both";
    bool force = false;
  };
  auto options = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "export-web", "model files -> a static web page drawing them live in WebGL2");
  command->add_option("MODEL", options->models, "model files (.stx), named by their file names")
      ->required();
  command
      ->add_option("-o,--output", options->output,
                   "folder to write (created if missing; an existing one must be empty)")
      ->required();
  command
      ->add_option("--variant", options->variant,
                   "exact (the CPU render to float rounding), fast (hardware-filtered textures) "
                   "or both (the page switches between them)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "fast", "both"}));
  command->add_flag("--force", options->force,
                    "write into an existing non-empty folder, replacing the files export-web "
                    "writes and keeping the others");
  return {command, [options] {
            export_web_files(options->models, options->output, options->variant, options->force);
            return 0;
          }};
}

}  // namespace stochtex::cli
