// The report's HTML: plain pages with relative links and inline style, so that DIR opens offline
// from any copy.

#include <fmt/core.h>
#include <fmt/format.h>

#include <array>
#include <string_view>
#include <utility>

#include "report/measures.hpp"
#include "report_output.hpp"

namespace stochtex::cli {
namespace {

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

std::string format_value(const Measure& measure, double value) {
  return fmt::format(fmt::runtime(measure.format), value);
}

std::string format_value(const Measure& measure, const Outcome& outcome) {
  if (outcome.error) return "failed";
  if (measure.method_only && outcome.name == "gaussian") return "&mdash;";
  return format_value(measure, outcome.quality.*measure.value);
}

const std::string_view kStyle =
    "<style>body{font-family:sans-serif;margin:1.5em;max-width:110em}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}"
    "td,th{border:1px solid #ccc;padding:3px 6px;text-align:right;vertical-align:top}"
    "th{background:#f4f4f4}td.name,th.name{text-align:left}"
    "td.pictures{text-align:center}img.spectrum{image-rendering:pixelated}"
    "p.help{color:#555;font-size:90%;max-width:60em}</style>";

}  // namespace

std::string exemplar_page(const ExemplarResults& exemplar, const ReportSettings& settings) {
  std::string page = fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>stochtex report: {0}</title>"
      "{1}</head><body>\n<p><a href=\"index.html\">&larr; all exemplars</a></p>\n"
      "<h1>{0}</h1>\n<p>{2} ({3}&times;{4}, {5} channel(s)); every synthesis is "
      "{6}&times;{7} pixels, seed {8}, default parameters.</p>\n<p><b>--method auto</b> chose "
      "{9}</p>\n<table>\n<tr><th></th>",
      html_escape(exemplar.name), kStyle, html_escape(exemplar.path), exemplar.image.width(),
      exemplar.image.height(), exemplar.image.channels(), settings.width, settings.height,
      settings.seed, html_escape(exemplar.choice.reason));
  std::vector<std::string> kinds{"exemplar"};
  for (const Outcome& outcome : exemplar.outcomes) kinds.push_back(outcome.name);
  for (const auto& kind : kinds)
    page += fmt::format("<th>{}</th>", kind == "gaussian" ? "Gaussian (ADSN)" : kind);
  page += "</tr>\n";
  const auto failed = [&](std::size_t k) {
    return k > 0 && exemplar.outcomes[k - 1].error.has_value();
  };
  const std::string averaged =
      fmt::format("power spectrum averaged over {} seeds (log)", settings.averaged_seeds);
  const std::array<std::pair<std::string_view, std::string_view>, 4> rows{
      {{"image", ""},
       {"power spectrum (log)", "_spectrum"},
       {averaged, "_spectrum_averaged"},
       {"colour histogram", "_histogram"}}};
  for (const auto& [title, suffix] : rows) {
    page += fmt::format("<tr><th class=\"name\">{}</th>", title);
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      if (failed(k)) {
        page += fmt::format("<td class=\"pictures\">failed: {}</td>",
                            html_escape(*exemplar.outcomes[k - 1].error));
        continue;
      }
      const bool spectrum = suffix.starts_with("_spectrum");
      page += fmt::format(
          "<td class=\"pictures\"><img src=\"{}/{}{}.png\" alt=\"{} {}\"{}></td>", exemplar.name,
          kinds[k], suffix, kinds[k], title,
          spectrum ? fmt::format(" class=\"spectrum\" width=\"{}\"", 2 * exemplar.crop) : "");
    }
    page += "</tr>\n";
  }
  page += "</table>\n<p class=\"help\">Spectra: Welch estimates on " +
          fmt::format("{0}&times;{0}", exemplar.crop) +
          " crops, DC at the centre, log scale from the exemplar's 1% quantile (black) to its "
          "maximum (white), the same for every picture. The averaged spectra are the mean of " +
          fmt::format("{}", settings.averaged_seeds) + " renders (seeds " +
          fmt::format("{}&ndash;{}", settings.seed, settings.seed + settings.averaged_seeds - 1) +
          "): what differs from the exemplar's there is the synthesis's bias, not its shot "
          "noise. Histograms: the exemplar's per-channel "
          "histogram as pale areas, the synthesis's as lines, on the same axes.</p>\n"
          "<table>\n<tr><th class=\"name\"></th>";
  for (const Measure& measure : measures()) page += fmt::format("<th>{}</th>", measure.title);
  page += "</tr>\n";
  for (const Outcome& outcome : exemplar.outcomes) {
    page += fmt::format("<tr><td class=\"name\">{}</td>",
                        outcome.name == "gaussian" ? "Gaussian (ADSN)" : outcome.name);
    for (const Measure& measure : measures())
      page += fmt::format("<td>{}</td>", format_value(measure, outcome));
    page += "</tr>\n";
  }
  page += "<tr><td class=\"name\">floor (exemplar halves)</td>";
  for (const Measure& measure : measures())
    page += measure.floor_key.empty()
                ? std::string("<td></td>")
                : fmt::format("<td>{}</td>", format_value(measure, exemplar.histogram_error_floor));
  page += "</tr>\n</table>\n<dl>\n";
  for (const Measure& measure : measures())
    page += fmt::format("<dt>{}</dt><dd>{}</dd>\n", measure.title, measure.help);
  page += "</dl>\n</body></html>\n";
  return page;
}

std::string index_page(const ReportRun& run) {
  const ReportSettings& settings = run.settings;
  std::string page = fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>stochtex report</title>{}"
      "</head><body>\n<h1>stochtex report</h1>\n<p>{} exemplar(s), methods {}, each with its "
      "default parameters, rendered at {}&times;{} with seed {} beside the exemplar's Gaussian "
      "version (ADSN). One run on one machine: {} thread(s), {:.1f} s wall, {:.1f} s CPU. "
      "Analysis and per-sample times are the CPU time of one thread, so work running beside "
      "them changes them little.</p>\n<p class=\"help\">No number below ranks the methods: "
      "a lower spectral or colour error can go with a picture that has lost the exemplar's "
      "structure (a Gaussian method's blur of bricks). The structure error measures that loss; "
      "the gallery's last column is what <code>--method auto</code> chooses from the exemplar's "
      "own measures, and why (docs/comparison.md).</p>\n",
      kStyle, run.exemplars.size(), fmt::join(run.methods, ", "), settings.width, settings.height,
      settings.seed, run.threads, run.wall_seconds, run.cpu_seconds);
  page +=
      "<h2>Gallery</h2>\n<table>\n<tr><th class=\"name\">name</th><th>exemplar</th>"
      "<th>Gaussian (ADSN)</th>";
  for (const auto& method : run.methods) page += fmt::format("<th>{}</th>", method);
  page += "<th class=\"name\">--method auto</th></tr>\n";
  for (const ExemplarResults& exemplar : run.exemplars) {
    page += fmt::format(
        "<tr><td class=\"name\"><a href=\"{0}.html\">{0}</a></td>"
        "<td class=\"pictures\"><a href=\"{0}.html\"><img src=\"{0}/exemplar.png\" width=\"128\" "
        "alt=\"exemplar\"></a></td>",
        exemplar.name);
    for (const Outcome& outcome : exemplar.outcomes)
      page += outcome.error ? std::string("<td>failed</td>")
                            : fmt::format(
                                  "<td class=\"pictures\"><img src=\"{}/{}.png\" "
                                  "width=\"128\" alt=\"{}\"></td>",
                                  exemplar.name, outcome.name, outcome.name);
    page += fmt::format("<td class=\"name\">{}</td></tr>\n", html_escape(exemplar.choice.reason));
  }
  page += "</table>\n";
  for (const Measure& measure : measures()) {
    page += fmt::format(
        "<h2>{}</h2>\n<p class=\"help\">{}.</p>\n<table>\n<tr>"
        "<th class=\"name\">exemplar</th>",
        measure.title, measure.help);
    if (!measure.method_only) page += "<th>Gaussian (ADSN)</th>";
    for (const auto& method : run.methods) page += fmt::format("<th>{}</th>", method);
    page += "</tr>\n";
    for (const ExemplarResults& exemplar : run.exemplars) {
      page +=
          fmt::format("<tr><td class=\"name\"><a href=\"{0}.html\">{0}</a></td>", exemplar.name);
      // No value is marked best: the lowest spectral error can be a blur (see the page's top).
      for (const Outcome& outcome : exemplar.outcomes) {
        if (measure.method_only && outcome.name == "gaussian") continue;
        page += fmt::format("<td>{}</td>", format_value(measure, outcome));
      }
      page += "</tr>\n";
    }
    page += "</table>\n";
  }
  page += "</body></html>\n";
  return page;
}

}  // namespace stochtex::cli
