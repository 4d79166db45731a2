// The `stochtex` command (DESIGN.md section 6). Exit codes: 0 ok, 1 runtime failure (bad file,
// numerical failure), 2 usage error. Messages go to stderr; --json output is one document on
// stdout.

#include <fmt/core.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>

#include "edit_command.hpp"
#include "io/image_io.hpp"
#include "io/text_file.hpp"
#include "metrics/metrics.hpp"
#include "number_pair.hpp"
#include "report_command.hpp"
#include "stochtex/stochtex.hpp"
#include "target_option.hpp"
#ifdef STOCHTEX_WITH_GL
#include "stochtex/gpu.hpp"
#endif

namespace {

using namespace stochtex;

constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;
constexpr int kMaxSide = 32768;
// 64 Mpixel (an 8192 x 8192 image, 1 GiB of RGBA floats): larger renders are refused up front
// rather than attempted as multi-gigabyte allocations.
constexpr std::int64_t kMaxOutputPixels = std::int64_t{1} << 26;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Size {
  int width = 0;
  int height = 0;
};

Size parse_size(const std::string& text) {
  static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw UsageError("--size must be WIDTHxHEIGHT, e.g. 512x512, not '" + text + "'");
  const Size size{std::stoi(match[1]), std::stoi(match[2])};
  if (size.width < 1 || size.height < 1 || size.width > kMaxSide || size.height > kMaxSide ||
      static_cast<std::int64_t>(size.width) * size.height > kMaxOutputPixels)
    throw UsageError(
        fmt::format("--size {} is out of range: each side must be 1 to {} and the "
                    "image at most {} pixels",
                    text, kMaxSide, kMaxOutputPixels));
  return size;
}

Vec2d parse_origin(const std::string& text) {
  if (const std::optional<Vec2d> origin = cli::parse_number_pair(text)) return *origin;
  throw UsageError("--origin must be X,Y in exemplar pixels, e.g. 1000,-250.5, not '" + text + "'");
}

std::map<std::string, std::string, std::less<>> parse_params(
    const std::vector<std::string>& items) {
  std::map<std::string, std::string, std::less<>> params;
  for (const auto& item : items) {
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0)
      throw UsageError("-p expects key=value, e.g. -p mni=30, not '" + item + "'");
    params[item.substr(0, equals)] = item.substr(equals + 1);
  }
  return params;
}

// A progress bar on stderr, shown only when stdout is a terminal (never in pipes, CI or --json).
class Progress {
 public:
  explicit Progress(std::string label)
      : label_(std::move(label)), enabled_(isatty(STDOUT_FILENO) && isatty(STDERR_FILENO)) {}
  ~Progress() {
    if (enabled_ && drawn_) std::fputc('\n', stderr);
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void operator()(double fraction) {
    if (!enabled_) return;
    const int percent = static_cast<int>(fraction * 100.0);
    if (percent == last_percent_) return;
    last_percent_ = percent;
    drawn_ = true;
    const int filled = percent * 30 / 100;
    fmt::print(stderr, "\r{} [{}{}] {:3d}%", label_,
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(30 - filled), ' '), percent);
    std::fflush(stderr);
  }
  void message(const std::string& text) const {
    if (enabled_) fmt::print(stderr, "{}\n", text);
  }

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  int last_percent_ = -1;
};

struct AnalyzeOptions {
  std::string input;
  std::string target;
  std::string method;
  std::vector<std::string> params;
  std::uint32_t seed = 0;
};

struct RenderSettings {
  std::string size = "512x512";
  std::string origin = "0,0";
  double scale = 1.0;
  std::uint32_t seed = 0;
  int threads = 0;
  int supersample = 1;
  int tile = 64;
  bool no_filter = false;
  int bit_depth = 8;
  std::string backend = "cpu";
  std::string gl_filter = "exact";
};

void add_render_options(CLI::App* command, RenderSettings& settings, bool size_required) {
  auto* size = command->add_option("--size", settings.size, "output size WIDTHxHEIGHT in pixels");
  if (size_required) size->required();
  command
      ->add_option("--origin", settings.origin, "model-space position X,Y of the top-left corner")
      ->capture_default_str();
  command->add_option("--scale", settings.scale, "exemplar pixels per output pixel (zoom out > 1)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e6));
  command->add_option("--seed", settings.seed, "32-bit seed of the random pattern")
      ->capture_default_str();
  command->add_option("--threads", settings.threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  command
      ->add_option("--supersample", settings.supersample,
                   "average KxK point samples per pixel (filtering reference)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  command->add_option("--tile", settings.tile, "tile side in pixels (speed only, never the output)")
      ->capture_default_str()
      ->check(CLI::Range(1, 4096));
  command->add_flag("--no-filter", settings.no_filter,
                    "point-sample even when zoomed out (aliases)");
  command->add_option("--bit-depth", settings.bit_depth, "PNG output bits per channel")
      ->capture_default_str()
      ->check(CLI::IsMember({8, 16}));
  command
      ->add_option("--backend", settings.backend,
                   "cpu (the reference) or gl (OpenGL 4.5 compute, headless; every method)")
      ->capture_default_str()
      ->check(CLI::IsMember({"cpu", "gl"}));
  command
      ->add_option(
          "--gl-filter", settings.gl_filter,
          "with --backend gl: exact (the CPU's filter, to float rounding) or hardware "
          "(texton order 1, tiling: mip-mapped textures, trilinear + anisotropic; equal to the "
          "CPU in distribution)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "hardware"}));
}

void add_analyze_options(CLI::App* command, AnalyzeOptions& options) {
  auto* input = command->add_option("INPUT", options.input, "exemplar image (PNG, EXR or PFM)");
  command->add_option("--target", options.target, std::string(cli::kTargetHelp))->excludes(input);
  command->add_option("--method,-m", options.method, "texture method (see `stochtex methods`)")
      ->required();
  command->add_option("-p,--param", options.params,
                      "method parameter key=value (repeatable; listed below)");
  command->footer("\nmethods and parameters (-p name=default):\n" + methods_text());
  command
      ->add_option("--analysis-seed", options.seed, "seed of the analysis' random initialisation")
      ->capture_default_str();
}

ImageF load_exemplar(const std::string& path) {
  ImageF image = read_image(path);
  validate_exemplar(image.view(), path);
  return image;
}

Model run_analyze(const AnalyzeOptions& options) {
  // Check the method and parameters before reading anything: usage errors come first.
  const ParamValues params = resolve_params(options.method, parse_params(options.params));
  if (!options.target.empty())
    return cli::target_model(options.target, options.method, params, options.seed);
  if (options.input.empty())
    throw UsageError("give an exemplar INPUT or, for lrp, a --target spectrum");
  const ImageF exemplar = load_exemplar(options.input);
  Progress progress("analyse");
  progress.message(fmt::format("analysing {} with {}...", options.input, options.method));
  return analyze(options.method, exemplar.view(), params, options.seed, options.input);
}

void run_render(const Model& model, const RenderSettings& settings, const std::string& output) {
  const Size size = parse_size(settings.size);
  const Grid grid{parse_origin(settings.origin), settings.scale, size.width, size.height, 0, 0};
  ImageF image(size.width, size.height, model.channels());
  RenderOptions options;
  options.threads = settings.threads;
  options.tile_size = settings.tile;
  options.supersample = settings.supersample;
  options.filter = !settings.no_filter;
  if (settings.backend == "gl") {
#ifdef STOCHTEX_WITH_GL
    GpuRenderOptions gpu_options;
    gpu_options.filter = options.filter;
    gpu_options.texture_filter =
        settings.gl_filter == "hardware" ? GlFilter::hardware : GlFilter::exact;
    if (options.supersample != 1)
      throw UsageError("--supersample is a CPU reference: use it with --backend cpu");
    render_gl(model, grid, settings.seed, image.view(), gpu_options);
#else
    throw Error(ErrorCode::io,
                "this stochtex was built without the OpenGL backend "
                "(STOCHTEX_BUILD_GL=OFF); use --backend cpu");
#endif
  } else {
    Progress progress("render ");
    options.progress = [&](double fraction) { progress(fraction); };
    render(model, grid, settings.seed, image.view(), options);
  }
  write_image(output, image.view(), settings.bit_depth);
}

void export_model_images(const Model& model, const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder))
    throw Error(ErrorCode::io, fmt::format("cannot export into '{}': the folder does not exist; "
                                           "create it first",
                                           folder.string()));
  for (auto& [name, image] : model_images(model)) {
    write_image(folder / (name + ".exr"), image.view());
    float peak = 0.0f;
    for (const float value : image.pixels()) peak = std::max(peak, std::abs(value));
    for (float& value : image.pixels()) value = 0.5f + 0.5f * value / std::max(peak, 1e-30f);
    write_image(folder / (name + ".png"), image.view());
  }
}

int run(int argc, char** argv) {
  CLI::App app{"stochtex: infinite, seedable, filterable textures from a small exemplar photo"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stochtex 0.1.0");

  AnalyzeOptions analyze_options;
  std::string output;
  RenderSettings settings;
  std::string model_path;
  bool json = false;

  auto* analyze_cmd = app.add_subcommand("analyze", "exemplar -> model file (.stx)");
  add_analyze_options(analyze_cmd, analyze_options);
  analyze_cmd->add_option("-o,--output", output, "model file to write (.stx)")->required();

  auto* render_cmd = app.add_subcommand("render", "model file -> image");
  render_cmd->add_option("MODEL", model_path, "model file (.stx)")->required();
  render_cmd->add_option("-o,--output", output, "image to write (.png, .exr or .pfm)")->required();
  add_render_options(render_cmd, settings, true);

  auto* synth_cmd = app.add_subcommand("synth", "analyze + render in one step");
  add_analyze_options(synth_cmd, analyze_options);
  synth_cmd->add_option("-o,--output", output, "image to write (.png, .exr or .pfm)")->required();
  add_render_options(synth_cmd, settings, true);

  auto* gaussian_cmd = app.add_subcommand("gaussian", "the exemplar's Gaussian version (ADSN)");
  std::string gaussian_input;
  gaussian_cmd->add_option("INPUT", gaussian_input, "exemplar image")->required();
  gaussian_cmd->add_option("-o,--output", output, "image to write")->required();
  gaussian_cmd->add_option("--size", settings.size, "output size WIDTHxHEIGHT")->required();
  gaussian_cmd->add_option("--seed", settings.seed, "32-bit seed")->capture_default_str();
  gaussian_cmd->add_option("--bit-depth", settings.bit_depth, "PNG output bits per channel")
      ->capture_default_str()
      ->check(CLI::IsMember({8, 16}));

  auto* compare_cmd = app.add_subcommand("compare", "quality of IMAGE against EXEMPLAR");
  std::string compare_exemplar;
  std::string compare_image;
  compare_cmd->add_option("EXEMPLAR", compare_exemplar, "the exemplar")->required();
  compare_cmd->add_option("IMAGE", compare_image, "the synthesised image")->required();
  compare_cmd->add_flag("--json", json, "print one JSON document");

  auto* info_cmd = app.add_subcommand("info", "describe a model file");
  info_cmd->add_option("MODEL", model_path, "model file (.stx)")->required();
  info_cmd->add_flag("--json", json, "print one JSON document");
  std::string export_folder;
  info_cmd->add_option("--export", export_folder,
                       "write the model's image arrays (e.g. the texton) into this folder as "
                       "NAME.exr (values) and NAME.png (preview: 0.5 + 0.5 v / max|v|)");

  auto* export_cmd = app.add_subcommand(
      "export-shader", "model file -> self-contained GLSL + data images for engines");
  export_cmd->add_option("MODEL", model_path, "model file (.stx)")->required();
  export_cmd->add_option("-o,--output", output, "folder to write (created if missing)")->required();

  cli::EditOptions edit_options;
  cli::add_edit_command(app, edit_options);
  cli::ReportOptions report_options;
  auto* report_cmd = cli::add_report_command(app, report_options);

  auto* methods_cmd = app.add_subcommand("methods", "list the methods and their parameters");
  methods_cmd->add_flag("--json", json, "print one JSON document");

  // CLI11's own usage errors follow the one-sentence rule too.
  app.failure_message([](const CLI::App*, const CLI::Error& error) {
    return fmt::format("stochtex: error: {}; see --help\n", error.what());
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  }

  try {
    if (*analyze_cmd) {
      check_output_path(output, false);
      const Model model = run_analyze(analyze_options);
      save_model(model, output);
      fmt::print(stderr, "wrote {}\n", output);
    } else if (*render_cmd) {
      parse_size(settings.size);
      parse_origin(settings.origin);
      check_output_path(output, true);
      run_render(load_model(model_path), settings, output);
      fmt::print(stderr, "wrote {}\n", output);
    } else if (*synth_cmd) {
      parse_size(settings.size);
      parse_origin(settings.origin);
      check_output_path(output, true);
      run_render(run_analyze(analyze_options), settings, output);
      fmt::print(stderr, "wrote {}\n", output);
    } else if (*gaussian_cmd) {
      const Size size = parse_size(settings.size);
      check_output_path(output, true);
      const ImageF exemplar = load_exemplar(gaussian_input);
      const ImageF result =
          gaussian_version(exemplar.view(), size.width, size.height, settings.seed);
      write_image(output, result.view(), settings.bit_depth);
      fmt::print(stderr, "wrote {}\n", output);
    } else if (*compare_cmd) {
      const ImageF exemplar = load_exemplar(compare_exemplar);
      const ImageF image = read_image(compare_image);
      if (image.channels() != exemplar.channels())
        throw Error(
            ErrorCode::invalid_input,
            fmt::format("'{}' has {} channels but the exemplar '{}' has {}; compare images "
                        "of the same kind",
                        compare_image, image.channels(), compare_exemplar, exemplar.channels()));
      const ComparisonReport r = compare_images(exemplar.view(), image.view());
      if (json) {
        nlohmann::ordered_json doc{{"exemplar", compare_exemplar},
                                   {"image", compare_image},
                                   {"welch_crop", r.crop},
                                   {"spectral_error", r.spectral_error},
                                   {"spectral_error_adsn", r.spectral_error_adsn},
                                   {"histogram_error", r.histogram_error},
                                   {"histogram_error_adsn", r.histogram_error_adsn},
                                   {"histogram_error_floor", r.histogram_error_floor},
                                   {"mean_error", r.mean_error},
                                   {"covariance_error", r.covariance_error}};
        fmt::print("{}\n", doc.dump(2));
      } else {
        fmt::print("{:<28}{:>12}{:>12}{:>12}\n", "measure", "image", "ADSN", "floor");
        fmt::print("{:<28}{:>12.4f}{:>12.4f}{:>12}\n", "spectral error (rel. L1)", r.spectral_error,
                   r.spectral_error_adsn, "");
        fmt::print("{:<28}{:>12.4f}{:>12.4f}{:>12.4f}\n", "colour histogram (SW2)",
                   r.histogram_error, r.histogram_error_adsn, r.histogram_error_floor);
        fmt::print("{:<28}{:>12.4f}\n", "mean error", r.mean_error);
        fmt::print("{:<28}{:>12.4f}\n", "covariance error (rel.)", r.covariance_error);
      }
    } else if (*info_cmd) {
      const Model model = load_model(model_path);
      if (!export_folder.empty()) export_model_images(model, export_folder);
      const std::string description = describe_model(model);
      if (json) {
        fmt::print("{}\n", description);
      } else {
        const auto doc = nlohmann::json::parse(description);
        fmt::print("model     {}\nmethod    {}\nchannels  {}\n", model_path, model.method(),
                   model.channels());
        for (const auto& [name, value] : doc["params"].items())
          fmt::print("  {} = {}\n", name, format_param(model.method(), name, value.get<double>()));
        for (const auto& array : doc["arrays"])
          fmt::print("array     {} {}\n", array["name"].get<std::string>(), array["shape"].dump());
        fmt::print("data      {} bytes\n", doc["array_bytes"].get<std::size_t>());
      }
    } else if (*export_cmd) {
#ifdef STOCHTEX_WITH_GL
      const ShaderExport files = export_shader(load_model(model_path));
      const std::filesystem::path folder(output);
      std::error_code error;
      std::filesystem::create_directories(folder, error);
      if (error)
        throw Error(ErrorCode::io,
                    fmt::format("cannot create the folder '{}': {}", output, error.message()));
      write_text_file(folder / files.glsl_file_name, files.glsl);
      for (const auto& [name, image] : files.images)
        write_image(folder / (name + ".exr"), image.view());
      write_text_file(folder / "README.md", files.readme);
      fmt::print(stderr, "wrote {} ({}, {} image(s), README.md)\n", output, files.glsl_file_name,
                 files.images.size());
#else
      throw Error(ErrorCode::io,
                  "this stochtex was built without the OpenGL backend "
                  "(STOCHTEX_BUILD_GL=OFF), which export-shader needs");
#endif
    } else if (*edit_options.command) {
      cli::run_edit_command(edit_options);
    } else if (*report_cmd) {
      return cli::run_report(report_options);
    } else if (*methods_cmd) {
      fmt::print("{}", json ? methods_json() + "\n" : methods_text());
    }
  } catch (const UsageError& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return kExitUsage;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return kExitUsage;
  } catch (const Error& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return kExitRuntime;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "stochtex: error: out of memory; use a smaller --size or exemplar\n");
    return kExitRuntime;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stochtex: error: {}\n", e.what());
    return kExitRuntime;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return run(argc, argv);
}
