#include "report_command.hpp"

#include <fmt/core.h>
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <stdexcept>
#include <string_view>
#include <tuple>

#include "core/parallel.hpp"
#include "io/image_io.hpp"
#include "io/text_file.hpp"
#include "report/comparison.hpp"
#include "stochtex/stochtex.hpp"

namespace stochtex::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMinSide = 16;
constexpr int kMaxSide = 4096;
constexpr int kMaxThumbnail = 1024;

// One synthesis's numbers (its images are written as soon as they are made, not kept).
struct Outcome {
  std::string name;
  std::optional<std::string> error;  // set when the method failed on this exemplar
  Quality quality;
  double analysis_seconds = 0.0;
  double ns_per_sample = 0.0;
};

struct ExemplarEntry {
  std::string path;
  std::string name;  // file stem made safe for file names and links, unique in the report
  ImageF image;
  int crop = 0;
  double histogram_error_floor = 0.0;
  std::vector<Outcome> outcomes;  // the Gaussian version first, then the methods in order
};

struct Measure {
  std::string_view title;
  std::string_view help;
  double (*value)(const Outcome&);
  bool method_only;  // no value for the Gaussian version
  std::string_view format;
};

const std::array kMeasures = {
    Measure{"spectral error",
            "relative L1 distance of the Welch power spectra (Hann-windowed crops) of the "
            "synthesis and the exemplar; the Gaussian version's value is the level of the ideal "
            "Gaussian texture, which texton, lrp and gabor noise approximate",
            [](const Outcome& o) { return o.quality.spectral_error; }, false, "{:.3f}"},
    Measure{"colour error (SW2)",
            "sliced Wasserstein-2 distance between the pixel colours of the synthesis and of the "
            "exemplar (64 fixed directions); the floor is the exemplar's top half against its "
            "bottom half",
            [](const Outcome& o) { return o.quality.histogram_error; }, false, "{:.4f}"},
    Measure{"mean error", "Euclidean distance of the mean colours",
            [](const Outcome& o) { return o.quality.mean_error; }, false, "{:.4f}"},
    Measure{"covariance error", "relative Frobenius distance of the colour covariance matrices",
            [](const Outcome& o) { return o.quality.covariance_error; }, false, "{:.3f}"},
    Measure{"non-stationarity",
            "coefficient of variation, over 4x4-sample blocks, of the per-sample variance across "
            "8 seeds of a 64x64 grid of point samples 2 exemplar pixels apart; the Gaussian "
            "version is exactly stationary, so its value is the estimator's noise",
            [](const Outcome& o) { return o.quality.nonstationarity; }, false, "{:.3f}"},
    Measure{"analysis (s)",
            "CPU seconds of one thread analysing the exemplar with the default parameters",
            [](const Outcome& o) { return o.analysis_seconds; }, true, "{:.2f}"},
    Measure{"ns/sample",
            "CPU nanoseconds per sample of one thread rendering the report's image (scale 1, "
            "filtered)",
            [](const Outcome& o) { return o.ns_per_sample; }, true, "{:.0f}"},
};

std::pair<int, int> parse_report_size(const std::string& text) {
  static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
  std::smatch match;
  if (std::regex_match(text, match, pattern)) {
    const int width = std::stoi(match[1]);
    const int height = std::stoi(match[2]);
    if (width >= kMinSide && height >= kMinSide && width <= kMaxSide && height <= kMaxSide)
      return {width, height};
  }
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

std::string html_escape(std::string_view text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

void create_folder(const fs::path& folder) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder))
    throw Error(ErrorCode::io,
                fmt::format("cannot create the report folder '{}': {}", folder.string(),
                            error ? error.message() : "a file of that name exists"));
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Writes a synthesis's picture files: DIR/NAME/KIND.png, KIND_spectrum.png, KIND_histogram.png
// and, when asked, DIR/thumbnails/NAME_KIND.png.
void write_pictures(const fs::path& folder, const std::string& name, const std::string& kind,
                    ImageView<const float> image, const ImageF& spectrum, const ImageF& histogram,
                    int thumbnail) {
  const fs::path own = folder / name;
  write_image(own / (kind + ".png"), image);
  write_image(own / (kind + "_spectrum.png"), spectrum.view());
  write_image(own / (kind + "_histogram.png"), histogram.view());
  if (thumbnail > 0)
    write_image(folder / "thumbnails" / (name + "_" + kind + ".png"),
                downscale(image, thumbnail).view());
}

std::string format_value(const Measure& measure, const Outcome& outcome) {
  if (outcome.error) return "failed";
  if (measure.method_only && outcome.name == "gaussian") return "&mdash;";
  return fmt::format(fmt::runtime(measure.format), measure.value(outcome));
}

const std::string_view kStyle =
    "<style>body{font-family:sans-serif;margin:1.5em;max-width:110em}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}"
    "td,th{border:1px solid #ccc;padding:3px 6px;text-align:right;vertical-align:top}"
    "th{background:#f4f4f4}td.name,th.name{text-align:left}"
    "td.pictures{text-align:center}img.spectrum{image-rendering:pixelated}"
    "p.help{color:#555;font-size:90%;max-width:60em}</style>";

std::string exemplar_page(const ExemplarEntry& entry, const ReportSettings& settings) {
  std::string page = fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>stochtex report: {0}</title>"
      "{1}</head><body>\n<p><a href=\"index.html\">&larr; all exemplars</a></p>\n"
      "<h1>{0}</h1>\n<p>{2} ({3}&times;{4}, {5} channel(s)); every synthesis is "
      "{6}&times;{7} pixels, seed {8}, default parameters.</p>\n<table>\n<tr><th></th>",
      html_escape(entry.name), kStyle, html_escape(entry.path), entry.image.width(),
      entry.image.height(), entry.image.channels(), settings.width, settings.height, settings.seed);
  std::vector<std::string> kinds{"exemplar"};
  for (const Outcome& outcome : entry.outcomes) kinds.push_back(outcome.name);
  for (const auto& kind : kinds)
    page += fmt::format("<th>{}</th>", kind == "gaussian" ? "Gaussian (ADSN)" : kind);
  page += "</tr>\n";
  const auto failed = [&](std::size_t k) {
    return k > 0 && entry.outcomes[k - 1].error.has_value();
  };
  const std::array<std::pair<std::string_view, std::string_view>, 3> rows{
      {{"image", ""}, {"power spectrum (log)", "_spectrum"}, {"colour histogram", "_histogram"}}};
  for (const auto& [title, suffix] : rows) {
    page += fmt::format("<tr><th class=\"name\">{}</th>", title);
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      if (failed(k)) {
        page += fmt::format("<td class=\"pictures\">failed: {}</td>",
                            html_escape(*entry.outcomes[k - 1].error));
        continue;
      }
      const bool spectrum = suffix == "_spectrum";
      page += fmt::format(
          "<td class=\"pictures\"><img src=\"{}/{}{}.png\" alt=\"{} {}\"{}></td>", entry.name,
          kinds[k], suffix, kinds[k], title,
          spectrum ? fmt::format(" class=\"spectrum\" width=\"{}\"", 2 * entry.crop) : "");
    }
    page += "</tr>\n";
  }
  page += "</table>\n<p class=\"help\">Spectra: Welch estimates on " +
          fmt::format("{0}&times;{0}", entry.crop) +
          " crops, DC at the centre, log scale from the exemplar's 1% quantile (black) to its "
          "maximum (white), the same for every picture. Histograms: the exemplar's per-channel "
          "histogram as pale areas, the synthesis's as lines, on the same axes.</p>\n"
          "<table>\n<tr><th class=\"name\"></th>";
  for (const Measure& measure : kMeasures) page += fmt::format("<th>{}</th>", measure.title);
  page += "</tr>\n";
  for (const Outcome& outcome : entry.outcomes) {
    page += fmt::format("<tr><td class=\"name\">{}</td>",
                        outcome.name == "gaussian" ? "Gaussian (ADSN)" : outcome.name);
    for (const Measure& measure : kMeasures)
      page += fmt::format("<td>{}</td>", format_value(measure, outcome));
    page += "</tr>\n";
  }
  page += fmt::format("<tr><td class=\"name\">floor (exemplar halves)</td><td></td><td>{:.4f}</td>",
                      entry.histogram_error_floor);
  for (std::size_t m = 2; m < kMeasures.size(); ++m) page += "<td></td>";
  page += "</tr>\n</table>\n<dl>\n";
  for (const Measure& measure : kMeasures)
    page += fmt::format("<dt>{}</dt><dd>{}</dd>\n", measure.title, measure.help);
  page += "</dl>\n</body></html>\n";
  return page;
}

std::string index_page(const std::vector<ExemplarEntry>& entries,
                       const std::vector<std::string>& method_names, const ReportSettings& settings,
                       int threads, double wall_seconds, double cpu_seconds) {
  std::string page = fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>stochtex report</title>{}"
      "</head><body>\n<h1>stochtex report</h1>\n<p>{} exemplar(s), methods {}, each with its "
      "default parameters, rendered at {}&times;{} with seed {} beside the exemplar's Gaussian "
      "version (ADSN). One run on one machine: {} thread(s), {:.1f} s wall, {:.1f} s CPU. "
      "Analysis and per-sample times are the CPU time of one thread, so work running beside "
      "them changes them little.</p>\n",
      kStyle, entries.size(), fmt::join(method_names, ", "), settings.width, settings.height,
      settings.seed, threads, wall_seconds, cpu_seconds);
  page +=
      "<h2>Gallery</h2>\n<table>\n<tr><th class=\"name\">name</th><th>exemplar</th>"
      "<th>Gaussian (ADSN)</th>";
  for (const auto& method : method_names) page += fmt::format("<th>{}</th>", method);
  page += "</tr>\n";
  for (const ExemplarEntry& entry : entries) {
    page += fmt::format(
        "<tr><td class=\"name\"><a href=\"{0}.html\">{0}</a></td>"
        "<td class=\"pictures\"><a href=\"{0}.html\"><img src=\"{0}/exemplar.png\" width=\"128\" "
        "alt=\"exemplar\"></a></td>",
        entry.name);
    for (const Outcome& outcome : entry.outcomes)
      page += outcome.error ? std::string("<td>failed</td>")
                            : fmt::format(
                                  "<td class=\"pictures\"><img src=\"{}/{}.png\" "
                                  "width=\"128\" alt=\"{}\"></td>",
                                  entry.name, outcome.name, outcome.name);
    page += "</tr>\n";
  }
  page += "</table>\n";
  for (const Measure& measure : kMeasures) {
    page += fmt::format(
        "<h2>{}</h2>\n<p class=\"help\">{}.</p>\n<table>\n<tr>"
        "<th class=\"name\">exemplar</th>",
        measure.title, measure.help);
    if (!measure.method_only) page += "<th>Gaussian (ADSN)</th>";
    for (const auto& method : method_names) page += fmt::format("<th>{}</th>", method);
    page += "</tr>\n";
    for (const ExemplarEntry& entry : entries) {
      page += fmt::format("<tr><td class=\"name\"><a href=\"{0}.html\">{0}</a></td>", entry.name);
      // The best (lowest) value among the methods in bold.
      std::optional<double> best;
      for (const Outcome& outcome : entry.outcomes)
        if (outcome.name != "gaussian" && !outcome.error)
          best = std::min(best.value_or(measure.value(outcome)), measure.value(outcome));
      for (const Outcome& outcome : entry.outcomes) {
        if (measure.method_only && outcome.name == "gaussian") continue;
        const std::string text = format_value(measure, outcome);
        const bool bold =
            outcome.name != "gaussian" && !outcome.error && best && measure.value(outcome) == *best;
        page += bold ? fmt::format("<td><b>{}</b></td>", text) : fmt::format("<td>{}</td>", text);
      }
      page += "</tr>\n";
    }
    page += "</table>\n";
  }
  page += "</body></html>\n";
  return page;
}

nlohmann::ordered_json summary_json(const std::vector<ExemplarEntry>& entries,
                                    const std::vector<std::string>& method_names,
                                    const ReportSettings& settings, int threads,
                                    double wall_seconds, double cpu_seconds, int failures) {
  auto exemplars = nlohmann::ordered_json::array();
  for (const ExemplarEntry& entry : entries) {
    auto syntheses = nlohmann::ordered_json::array();
    for (const Outcome& outcome : entry.outcomes) {
      nlohmann::ordered_json item{{"name", outcome.name}};
      if (outcome.error) {
        item["error"] = *outcome.error;
      } else {
        item["spectral_error"] = outcome.quality.spectral_error;
        item["histogram_error"] = outcome.quality.histogram_error;
        item["mean_error"] = outcome.quality.mean_error;
        item["covariance_error"] = outcome.quality.covariance_error;
        item["nonstationarity"] = outcome.quality.nonstationarity;
        if (outcome.name != "gaussian") {
          item["analysis_seconds"] = outcome.analysis_seconds;
          item["ns_per_sample"] = outcome.ns_per_sample;
        }
      }
      syntheses.push_back(item);
    }
    exemplars.push_back({{"name", entry.name},
                         {"file", entry.path},
                         {"width", entry.image.width()},
                         {"height", entry.image.height()},
                         {"channels", entry.image.channels()},
                         {"welch_crop", entry.crop},
                         {"histogram_error_floor", entry.histogram_error_floor},
                         {"page", entry.name + ".html"},
                         {"syntheses", syntheses}});
  }
  return {{"settings",
           {{"width", settings.width},
            {"height", settings.height},
            {"seed", settings.seed},
            {"methods", method_names},
            {"threads", threads},
            {"stationarity_side", settings.stationarity_side},
            {"stationarity_step", settings.stationarity_step},
            {"stationarity_seeds", settings.stationarity_seeds},
            {"stationarity_block", settings.stationarity_block}}},
          {"wall_seconds", wall_seconds},
          {"cpu_seconds", cpu_seconds},
          {"failures", failures},
          {"exemplars", exemplars}};
}

}  // namespace

CLI::App* add_report_command(CLI::App& app, ReportOptions& options) {
  auto* command = app.add_subcommand(
      "report", "every method on every exemplar: an HTML page of pictures and measured numbers");
  command->add_option("EXEMPLAR", options.exemplars, "exemplar images")->required();
  command->add_option("-o,--output", options.output, "folder to write (created if missing)")
      ->required();
  command->add_option("--size", options.size, "size WIDTHxHEIGHT of every synthesis")
      ->capture_default_str();
  command->add_option("--seed", options.seed, "32-bit seed of every render")->capture_default_str();
  command
      ->add_option("--methods", options.methods,
                   "comma-separated methods to run (default: all, see `stochtex methods`)")
      ->delimiter(',');
  command->add_option("--threads", options.threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  command
      ->add_option("--thumbnail", options.thumbnail,
                   "also write DIR/thumbnails/NAME_KIND.png with this largest side (0 = none)")
      ->capture_default_str()
      ->check(CLI::Range(0, kMaxThumbnail));
  command->add_flag("--json", options.json,
                    "print the summary as one JSON document on stdout (also DIR/report.json)");
  return command;
}

int run_report(const ReportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  // Usage errors first, then unreadable exemplars, then unwritable outputs: all before long work.
  ReportSettings settings;
  std::tie(settings.width, settings.height) = parse_report_size(options.size);
  settings.seed = options.seed;
  const std::vector<std::string> method_names = resolve_methods(options.methods);
  const int threads = resolve_thread_count(options.threads);

  std::vector<ExemplarEntry> entries;
  std::set<std::string> taken;
  for (const auto& path : options.exemplars) {
    ImageF image = read_image(path);
    validate_exemplar(image.view(), path);
    ExemplarEntry& entry = entries.emplace_back();
    entry.path = path;
    entry.name = unique_name(path, taken);
    entry.image = std::move(image);
  }
  const fs::path folder(options.output);
  create_folder(folder);
  for (const ExemplarEntry& entry : entries) create_folder(folder / entry.name);
  if (options.thumbnail > 0) create_folder(folder / "thumbnails");

  std::mutex print_mutex;
  std::size_t finished = 0;
  const std::size_t total = entries.size() * (1 + method_names.size());
  const auto report_progress = [&](const ExemplarEntry& entry, const Outcome& outcome) {
    const std::lock_guard lock(print_mutex);
    ++finished;
    if (outcome.error)
      fmt::print(stderr, "report: [{}/{}] {} {}: failed: {}\n", finished, total, entry.name,
                 outcome.name, *outcome.error);
    else if (outcome.name == "gaussian")
      fmt::print(stderr, "report: [{}/{}] {} Gaussian version\n", finished, total, entry.name);
    else
      fmt::print(stderr, "report: [{}/{}] {} {}: analysis {:.2f} s, {:.0f} ns/sample\n", finished,
                 total, entry.name, outcome.name, outcome.analysis_seconds, outcome.ns_per_sample);
  };

  // Per exemplar: what every synthesis is measured against, and the Gaussian version.
  std::vector<ExemplarReference> references(entries.size());
  parallel_for(entries.size(), threads, [&](std::size_t i) {
    ExemplarEntry& entry = entries[i];
    references[i] = make_reference(entry.image.view(), settings);
    const ExemplarReference& reference = references[i];
    entry.crop = reference.crop;
    entry.histogram_error_floor = reference.histogram_error_floor;
    write_pictures(folder, entry.name, "exemplar", entry.image.view(), reference.spectrum_picture,
                   reference.histogram_picture, options.thumbnail);
    const Synthesis gaussian = measure_gaussian(entry.image.view(), reference, settings);
    write_pictures(folder, entry.name, gaussian.name, gaussian.image.view(),
                   gaussian.spectrum_picture, gaussian.histogram_picture, options.thumbnail);
    entry.outcomes.resize(1 + method_names.size());
    entry.outcomes[0].name = gaussian.name;
    entry.outcomes[0].quality = gaussian.quality;
    report_progress(entry, entry.outcomes[0]);
  });

  // Every (exemplar, method) pair, the most expensive first so that the last tasks to start are
  // short ones: gabor's analysis dominates and grows with the pixel and channel counts.
  struct Task {
    std::size_t exemplar;
    std::size_t method;
    double cost;
  };
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double size =
        static_cast<double>(entries[i].image.pixel_count()) * entries[i].image.channels();
    for (std::size_t m = 0; m < method_names.size(); ++m)
      tasks.push_back({i, m, method_names[m] == "gabor" ? 100.0 * size : size});
  }
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const Task& a, const Task& b) { return a.cost > b.cost; });
  std::atomic<int> failures{0};
  std::vector<std::atomic<std::size_t>> remaining(entries.size());
  for (auto& count : remaining) count = method_names.size();
  parallel_for(tasks.size(), threads, [&](std::size_t t) {
    ExemplarEntry& entry = entries[tasks[t].exemplar];
    const std::string& method = method_names[tasks[t].method];
    Outcome& outcome = entry.outcomes[1 + tasks[t].method];
    outcome.name = method;
    try {
      const Synthesis synthesis =
          measure_method(method, entry.image.view(), references[tasks[t].exemplar], settings);
      write_pictures(folder, entry.name, method, synthesis.image.view(), synthesis.spectrum_picture,
                     synthesis.histogram_picture, options.thumbnail);
      outcome.quality = synthesis.quality;
      outcome.analysis_seconds = synthesis.analysis_seconds;
      outcome.ns_per_sample = synthesis.ns_per_sample;
    } catch (const std::exception& e) {
      outcome.error = e.what();
      ++failures;
    }
    if (--remaining[tasks[t].exemplar] == 0) references[tasks[t].exemplar].colours.reset();
    report_progress(entry, outcome);
  });

  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu_seconds = process_cpu_seconds() - cpu_start;
  for (const ExemplarEntry& entry : entries)
    write_text_file(folder / (entry.name + ".html"), exemplar_page(entry, settings));
  write_text_file(folder / "index.html",
                  index_page(entries, method_names, settings, threads, wall_seconds, cpu_seconds));
  const std::string json =
      summary_json(entries, method_names, settings, threads, wall_seconds, cpu_seconds, failures)
          .dump(2);
  write_text_file(folder / "report.json", json + "\n");
  if (options.json) fmt::print("{}\n", json);
  fmt::print(stderr, "wrote {} ({} exemplar(s), {:.1f} s wall, {:.1f} s CPU)\n",
             (folder / "index.html").string(), entries.size(), wall_seconds, cpu_seconds);
  if (failures > 0) {
    fmt::print(stderr, "stochtex: error: {} of {} method runs failed; {} shows which\n",
               failures.load(), tasks.size(), (folder / "index.html").string());
    return 1;
  }
  return 0;
}

}  // namespace stochtex::cli
