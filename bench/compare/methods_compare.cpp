// The four methods side by side (docs/design.md §10): analysis time and evaluation cost per
// sample of every registered method on the same exemplar, in one process, at 1 thread and at all
// hardware threads, with the ratio of each to the fastest and the ratios the papers claim on GPUs
// beside the measured ones (docs/performance.md explains the differences), and each method's
// one-thread cost on the scalar reference evaluator against the machine's best CPU target (the
// SIMD speed-up, render.hpp's CpuTarget).
// Usage: stochtex_methods_compare [EXEMPLAR.png] (default: the corpus's moss_ground_512.png).

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "io/image_io.hpp"
#include "stochtex/stochtex.hpp"

namespace {

using namespace stochtex;
using Clock = std::chrono::steady_clock;

constexpr int kSide = 256;
constexpr double kMinimumSeconds = 0.5;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Wall-clock nanoseconds per sample of kSide x kSide renders on `target`, repeated for at least
// kMinimumSeconds.
double ns_per_sample(const Model& model, int threads, CpuTarget target) {
  set_cpu_target(target);
  ImageF out(kSide, kSide, model.channels());
  RenderOptions options;
  options.threads = threads;
  const Grid grid{{0.0, 0.0}, 1.0, kSide, kSide};
  render(model, grid, 0, out.view(), options);  // warm-up: caches, thread start
  int renders = 0;
  const auto start = Clock::now();
  do {
    render(model, grid, static_cast<std::uint32_t>(++renders), out.view(), options);
  } while (seconds_since(start) < kMinimumSeconds);
  return seconds_since(start) * 1e9 / (static_cast<double>(renders) * kSide * kSide);
}

// The reference's and the best target's one-thread costs and the best target's at `threads`.
struct Costs {
  double reference = 0.0;
  double single = 0.0;
  double all = 0.0;
};
Costs measure(const Model& model, int threads) {
  const CpuTarget best = available_cpu_targets().back();
  Costs costs;
  costs.reference = ns_per_sample(model, 1, CpuTarget::reference);
  costs.single = ns_per_sample(model, 1, best);
  costs.all = ns_per_sample(model, threads, best);
  return costs;
}

struct Row {
  std::string method;
  double analysis_ms = 0.0;
  Costs ns;
};

// The papers' per-sample cost ratios on GPUs: slower method, faster method, claimed factor.
struct Claim {
  const char* slower;
  const char* faster;
  const char* factor;
  const char* source;
};
constexpr Claim kClaims[] = {
    {"texton", "tiling-b1", "~20", "Heitz & Neyret 2018 sec. 6.1 (Gaussian fast path)"},
    {"texton", "tiling", "~20", "the same claim against the full histogram-preserving path"},
    {"lrp", "texton", "~10", "Galerne et al. 2017 sec. 5 (Quadro K5000)"},
    {"gabor", "lrp", "> 1", "Gilet et al. 2014 sec. 6 (fewer special functions)"},
};

const Row* find_row(const std::vector<Row>& rows, std::string_view method) {
  const auto found =
      std::find_if(rows.begin(), rows.end(), [&](const Row& row) { return row.method == method; });
  return found == rows.end() ? nullptr : &*found;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string path =
        argc > 1 ? argv[1] : std::string(STOCHTEX_TEXTURE_DIR) + "/moss_ground_512.png";
    const ImageF exemplar = read_image(path);
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<Row> rows;
    for (const auto& method : methods()) {
      Row row{std::string(method.name), 0.0, {}};
      const auto start = Clock::now();
      const Model model = analyze(method.name, exemplar.view(), {}, 0, path);
      row.analysis_ms = seconds_since(start) * 1e3;
      row.ns = measure(model, threads);
      rows.push_back(row);
      fmt::print(stderr, "measured {}\n", row.method);
    }
    // Tiling's Gaussian-input fast path (-p blend=1: no T, no T^-1), the case behind the tiling
    // paper's "20x faster than texton noise".
    {
      Row row{"tiling-b1", 0.0, {}};
      const auto start = Clock::now();
      const Model model = analyze("tiling", exemplar.view(), {{"blend", 1.0}}, 0, path);
      row.analysis_ms = seconds_since(start) * 1e3;
      row.ns = measure(model, threads);
      rows.push_back(row);
    }
    const double fastest =
        std::min_element(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
          return a.ns.single < b.ns.single;
        })->ns.single;
    fmt::print(
        "{} ({}x{} {}-channel), {}x{} renders, default parameters, {} hardware threads, CPU "
        "target {}\n",
        path, exemplar.width(), exemplar.height(), exemplar.channels(), kSide, kSide, threads,
        cpu_target_name(available_cpu_targets().back()));
    fmt::print("{:<10} {:>12} {:>14} {:>16} {:>10} {:>16} {:>10} {:>10}\n", "method", "analysis ms",
               "reference 1 thr", "ns/sample 1 thr", "x SIMD",
               fmt::format("ns/sample {} thr", threads), fmt::format("x {} thr", threads),
               "x fastest");
    for (const Row& row : rows)
      fmt::print("{:<10} {:>12.1f} {:>14.1f} {:>16.1f} {:>10.2f} {:>16.1f} {:>10.2f} {:>10.1f}\n",
                 row.method, row.analysis_ms, row.ns.reference, row.ns.single,
                 row.ns.reference / row.ns.single, row.ns.all, row.ns.single / row.ns.all,
                 row.ns.single / fastest);
    fmt::print("\n{:<20} {:>12} {:>18}  {}\n", "ns/sample ratio", "paper (GPU)", "measured (1 thr)",
               "claim");
    for (const Claim& claim : kClaims) {
      const Row* slower = find_row(rows, claim.slower);
      const Row* faster = find_row(rows, claim.faster);
      if (slower == nullptr || faster == nullptr) continue;
      fmt::print("{:<20} {:>12} {:>18.1f}  {}\n",
                 fmt::format("{} / {}", claim.slower, claim.faster), claim.factor,
                 slower->ns.single / faster->ns.single, claim.source);
    }
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stochtex_methods_compare: error: {}\n", e.what());
    return 1;
  }
}
