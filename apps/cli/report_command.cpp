// `stochtex report EXEMPLAR... -o DIR`: every method on every exemplar, side by side, as an HTML
// page that opens offline (DIR/index.html, one page per exemplar, PNG pictures) and, with --json,
// one JSON summary on stdout (also written to DIR/report.json). Exits 1 when some method failed
// on some exemplar: the report is still written and shows which. Usage errors, unreadable
// exemplars and unwritable outputs are found before any long work.

#include <fmt/core.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>

#include "arguments.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "io/image_io.hpp"
#include "report/measure_all.hpp"
#include "report_output.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMinSide = 16;
constexpr int kMaxSide = 4096;
constexpr int kMaxThumbnail = 1024;

struct ReportOptions {
  std::vector<std::string> exemplars;
  std::string output;
  std::string size = "256x256";
  std::uint32_t seed = 1;
  std::vector<std::string> methods;  // empty: all
  int threads = 0;
  int thumbnail = 0;  // largest side of DIR/thumbnails/*.png; 0: none
  bool json = false;
};

Size report_size(const std::string& text) {
  if (const std::optional<Size> size = parse_size(text);
      size && size->width >= kMinSide && size->height >= kMinSide && size->width <= kMaxSide &&
      size->height <= kMaxSide)
    return *size;
  throw std::invalid_argument(
      fmt::format("--size must be WIDTHxHEIGHT with sides from {} to {}, e.g. 256x256, not '{}'",
                  kMinSide, kMaxSide, text));
}

std::vector<std::string> resolve_methods(const std::vector<std::string>& requested) {
  std::vector<std::string> names;
  if (requested.empty()) {
    for (const auto& method : methods()) names.emplace_back(method.name);
    return names;
  }
  for (const auto& name : requested) {
    method_info(name);  // throws std::invalid_argument naming the known methods
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

// The exemplar's file stem with every character other than letters, digits, '.', '-' and '_'
// replaced, made unique with a suffix: used in file names and relative links, so no escaping.
std::string unique_name(const std::string& path, std::set<std::string>& taken) {
  std::string stem = fs::path(path).stem().string();
  for (char& c : stem)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
  if (stem.empty() || stem == "thumbnails" || stem == "index" || stem == "report") stem += "_";
  std::string name = stem;
  for (int suffix = 2; !taken.insert(name).second; ++suffix)
    name = fmt::format("{}_{}", stem, suffix);
  return name;
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Writes a synthesis's picture files: DIR/NAME/KIND.png, KIND_spectrum.png,
// KIND_spectrum_averaged.png, KIND_histogram.png and, when asked, DIR/thumbnails/NAME_KIND.png.
void write_pictures(AtomicFileSet& files, const fs::path& folder, const std::string& name,
                    const Pictures& pictures, int thumbnail) {
  const fs::path own = folder / name;
  const std::string kind(pictures.kind);
  write_image(files, own / (kind + ".png"), pictures.image);
  write_image(files, own / (kind + "_spectrum.png"), pictures.spectrum.view());
  write_image(files, own / (kind + "_spectrum_averaged.png"), pictures.averaged_spectrum.view());
  write_image(files, own / (kind + "_histogram.png"), pictures.histogram.view());
  if (thumbnail > 0)
    write_image(files, folder / "thumbnails" / (name + "_" + kind + ".png"),
                downscale(pictures.image, thumbnail).view());
}

int run_report(const ReportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  // Usage errors first, then unreadable exemplars, then unwritable outputs: all before long work.
  ReportSettings settings;
  const Size size = report_size(options.size);
  settings.width = size.width;
  settings.height = size.height;
  settings.seed = options.seed;
  const std::vector<std::string> method_names = resolve_methods(options.methods);
  const int threads = resolve_thread_count(options.threads);

  std::vector<ExemplarResults> exemplars;
  std::set<std::string> taken;
  HeldImages held;
  for (const auto& path : options.exemplars) {
    ImageF image = load_exemplar(path, held.check(path));
    ExemplarResults& exemplar = exemplars.emplace_back();
    exemplar.path = path;
    exemplar.name = unique_name(path, taken);
    exemplar.image = std::move(image);
  }
  const fs::path folder(options.output);
  AtomicFileSet files;  // the whole report or nothing
  files.create_folder(folder);
  for (const ExemplarResults& exemplar : exemplars) files.create_folder(folder / exemplar.name);
  if (options.thumbnail > 0) files.create_folder(folder / "thumbnails");

  std::mutex print_mutex;
  std::size_t finished = 0;
  const std::size_t total = exemplars.size() * (1 + method_names.size());
  MeasureCallbacks callbacks;
  callbacks.pictures = [&](const ExemplarResults& exemplar, const Pictures& pictures) {
    write_pictures(files, folder, exemplar.name, pictures, options.thumbnail);
  };
  callbacks.finished = [&](const ExemplarResults& exemplar, const Outcome& outcome) {
    const std::lock_guard lock(print_mutex);
    ++finished;
    if (outcome.error)
      fmt::print(stderr, "report: [{}/{}] {} {}: failed: {}\n", finished, total, exemplar.name,
                 outcome.name, *outcome.error);
    else if (outcome.name == "gaussian")
      fmt::print(stderr, "report: [{}/{}] {} Gaussian version\n", finished, total, exemplar.name);
    else
      fmt::print(stderr, "report: [{}/{}] {} {}: analysis {:.2f} s, {:.0f} ns/sample\n", finished,
                 total, exemplar.name, outcome.name, outcome.quality.analysis_seconds,
                 outcome.quality.ns_per_sample);
  };
  const int failures = measure_all(exemplars, method_names, settings, threads, callbacks);

  const ReportRun run{
      exemplars,
      method_names,
      settings,
      threads,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
      process_cpu_seconds() - cpu_start,
      failures};
  for (const ExemplarResults& exemplar : exemplars)
    files.write(folder / (exemplar.name + ".html"), exemplar_page(exemplar, settings));
  files.write(folder / "index.html", index_page(run));
  const std::string json = summary_json(run);
  files.write(folder / "report.json", json + "\n");
  files.commit();
  if (options.json) fmt::print("{}\n", json);
  fmt::print(stderr, "wrote {} ({} exemplar(s), {:.1f} s wall, {:.1f} s CPU)\n",
             (folder / "index.html").string(), exemplars.size(), run.wall_seconds, run.cpu_seconds);
  if (failures > 0) {
    fmt::print(stderr, "stochtex: error: {} of {} method runs failed; {} shows which\n", failures,
               exemplars.size() * method_names.size(), (folder / "index.html").string());
    return kExitRuntime;
  }
  return 0;
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto options = std::make_shared<ReportOptions>();
  auto* command = app.add_subcommand(
      "report", "every method on every exemplar: an HTML page of pictures and measured numbers");
  command->add_option("EXEMPLAR", options->exemplars, "exemplar images")->required();
  command->add_option("-o,--output", options->output, "folder to write (created if missing)")
      ->required();
  command->add_option("--size", options->size, "size WIDTHxHEIGHT of every synthesis")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "32-bit seed of every render")
      ->capture_default_str();
  command
      ->add_option("--methods", options->methods,
                   "comma-separated methods to run (default: all, see `stochtex methods`)")
      ->delimiter(',');
  command->add_option("--threads", options->threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  command
      ->add_option("--thumbnail", options->thumbnail,
                   "also write DIR/thumbnails/NAME_KIND.png with this largest side (0 = none)")
      ->capture_default_str()
      ->check(CLI::Range(0, kMaxThumbnail));
  command->add_flag("--json", options->json,
                    "print the summary as one JSON document on stdout (also DIR/report.json)");
  return {command, [options] { return run_report(*options); }};
}

}  // namespace stochtex::cli
