#include "stochtex/render.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/parallel.hpp"
#include "model/model_data.hpp"

namespace stochtex {
namespace {

// Finite and within the precise range (render.hpp): also false for NaN.
bool in_range(Vec2d v) {
  return std::abs(v.x) <= kPositionLimit && std::abs(v.y) <= kPositionLimit;
}

// "+-<limit> exemplar pixels, the precise range of docs/design.md §4", the end of every refusal.
std::string range_text() {
  return "+-" + std::to_string(static_cast<std::int64_t>(kPositionLimit)) +
         " exemplar pixels, the precise range of positions (docs/design.md §4)";
}

// One dispatch per batch; the method's loop over samples is concrete and inlined, then the values
// of srgb channels become linear light (model/model_colour.hpp). The arguments have been checked.
void evaluate_checked(const Model& model, std::span<const Vec2d> positions,
                      std::span<const Footprint> footprints, std::uint32_t seed,
                      ImageView<float> out) {
  std::visit([&](const auto& m) { m.evaluate(positions, footprints, seed, out); },
             model.data().model);
  decode_expectation(model.data().colour, positions.size(), footprints, out);
}

// evaluate()'s and evaluate_periodic()'s checks of their arguments.
void check_evaluation(const Model& model, std::span<const Vec2d> positions,
                      std::span<const Footprint> footprints, ImageView<float> out) {
  if (model.empty()) throw std::invalid_argument("evaluate: the model is empty");
  if (!footprints.empty() && footprints.size() != positions.size())
    throw std::invalid_argument("evaluate: footprints must be empty or one per position");
  if (out.channels != model.channels() ||
      static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) < positions.size())
    throw std::invalid_argument("evaluate: the output view must hold one pixel of " +
                                std::to_string(model.channels()) + " channels per position");
  if (!std::all_of(positions.begin(), positions.end(), in_range))
    throw std::invalid_argument("evaluate: a position is not finite or beyond " + range_text());
  if (!std::all_of(footprints.begin(), footprints.end(),
                   [](const Footprint& f) { return in_range(f.dpdx) && in_range(f.dpdy); }))
    throw std::invalid_argument("evaluate: a footprint is not finite or beyond " + range_text());
}

// The periodic twin of evaluate_checked; the model has no periodic_refusal (so its method has
// evaluate_periodic).
void evaluate_periodic_checked(const Model& model, std::span<const Vec2d> positions,
                               std::span<const Footprint> footprints, std::uint32_t seed,
                               ImageView<float> out, Vec2d period) {
  std::visit(
      [&](const auto& m) {
        if constexpr (requires { m.evaluate_periodic(positions, footprints, seed, out, period); })
          m.evaluate_periodic(positions, footprints, seed, out, period);
      },
      model.data().model);
  decode_expectation(model.data().colour, positions.size(), footprints, out);
}

void check_period(const Model& model, Vec2d period, std::string_view what) {
  if (!(period.x > 0.0 && period.y > 0.0 && in_range(period)))
    throw std::invalid_argument(std::string(what) +
                                ": the period must be positive and finite, within " + range_text());
  const std::string refusal = periodic_refusal(model);
  if (!refusal.empty()) throw std::invalid_argument(std::string(what) + ": " + refusal);
}

}  // namespace

std::string periodic_refusal(const Model& model) {
  if (model.empty()) return "the model is empty";
  if (std::holds_alternative<texton_mix::TextonMixModel>(model.data().model))
    return "a texton mix cannot render periodic (its mixing field does not repeat)";
  if (const auto* lrp = std::get_if<lrp::LrpModel>(&model.data().model);
      lrp != nullptr && !lrp->data().structure.empty())
    return "an lrp model with a structure component cannot render periodic (its fixed cosines do "
           "not repeat with the output)";
  // A method whose model has no evaluate_periodic.
  const bool periodic = std::visit(
      [](const auto& m) {
        return requires {
          &std::remove_cvref_t<decltype(m)>::evaluate_periodic;
        };
      },
      model.data().model);
  if (!periodic) return "a " + std::string(model.method()) + " model cannot render periodic";
  return {};
}

void evaluate_periodic(const Model& model, std::span<const Vec2d> positions,
                       std::span<const Footprint> footprints, std::uint32_t seed,
                       ImageView<float> out, Vec2d period) {
  check_evaluation(model, positions, footprints, out);
  check_period(model, period, "evaluate_periodic");
  evaluate_periodic_checked(model, positions, footprints, seed, out, period);
}

void check_grid(const Grid& grid, std::string_view what) {
  // The pixel indices' extremes, in double (no integer overflow for any first_pixel value); the
  // samples lie between the corners origin + scale * index.
  const auto reach = [&](std::int64_t first, int count) {
    const auto low = static_cast<double>(first);
    return std::max(std::abs(low), std::abs(low + static_cast<double>(count)));
  };
  const double x =
      std::abs(grid.origin.x) + std::abs(grid.scale) * reach(grid.first_pixel_x, grid.width);
  const double y =
      std::abs(grid.origin.y) + std::abs(grid.scale) * reach(grid.first_pixel_y, grid.height);
  if (in_range({x, y})) return;
  std::ostringstream reached;
  reached.precision(12);
  reached << std::max(x, y);
  throw std::invalid_argument(std::string(what) +
                              (std::isfinite(x + y) ? " reaches " + reached.str() + ", beyond "
                                                    : " is not finite; positions must be within ") +
                              range_text());
}

void evaluate(const Model& model, std::span<const Vec2d> positions,
              std::span<const Footprint> footprints, std::uint32_t seed, ImageView<float> out) {
  check_evaluation(model, positions, footprints, out);
  evaluate_checked(model, positions, footprints, seed, out);
}

void render(const Model& model, const Grid& grid, std::uint32_t seed, ImageView<float> out,
            const RenderOptions& options) {
  if (model.empty()) throw std::invalid_argument("render: the model is empty");
  if (out.width != grid.width || out.height != grid.height || out.channels != model.channels())
    throw std::invalid_argument("render: the output view does not match the grid and model");
  if (options.tile_size < 1 || options.supersample < 1)
    throw std::invalid_argument("render: tile_size and supersample must be positive");
  check_grid(grid, "render: the grid");
  if (options.period) check_period(model, *options.period, "render");
  const int tile = options.tile_size;
  const int tiles_x = (grid.width + tile - 1) / tile;
  const int tiles_y = (grid.height + tile - 1) / tile;
  const std::size_t tile_count = static_cast<std::size_t>(tiles_x) * tiles_y;
  const int sub = options.supersample;
  const double sub_step = 1.0 / sub;
  const int channels = model.channels();
  // Point samples for the supersampled reference; otherwise one footprint per pixel (scale).
  const bool with_footprints = options.filter && sub == 1;
  const Footprint pixel_footprint{{grid.scale, 0.0}, {0.0, grid.scale}};

  auto render_tile = [&](std::size_t t) {
    const int x0 = static_cast<int>(t % static_cast<std::size_t>(tiles_x)) * tile;
    const int y0 = static_cast<int>(t / static_cast<std::size_t>(tiles_x)) * tile;
    const int w = std::min(tile, grid.width - x0);
    const int h = std::min(tile, grid.height - y0);
    const std::size_t samples = static_cast<std::size_t>(w) * h * sub * sub;
    std::vector<Vec2d> positions;
    positions.reserve(samples);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int sy = 0; sy < sub; ++sy)
          for (int sx = 0; sx < sub; ++sx) {
            // Pixel (i, j) samples origin + scale * (i + 1/2, j + 1/2); sub-samples stratify it.
            const double i =
                static_cast<double>(grid.first_pixel_x + x0 + x) + (sx + 0.5) * sub_step;
            const double j =
                static_cast<double>(grid.first_pixel_y + y0 + y) + (sy + 0.5) * sub_step;
            positions.push_back({grid.origin.x + grid.scale * i, grid.origin.y + grid.scale * j});
          }
    std::vector<Footprint> footprints;
    if (with_footprints) footprints.assign(samples, pixel_footprint);
    const auto evaluate_tile = [&](ImageView<float> view) {
      if (options.period)
        evaluate_periodic_checked(model, positions, footprints, seed, view, *options.period);
      else
        evaluate_checked(model, positions, footprints, seed, view);
    };
    if (sub == 1) {
      evaluate_tile(out.sub(x0, y0, w, h));
      return;
    }
    std::vector<float> values(samples * static_cast<std::size_t>(channels));
    evaluate_tile(ImageView<float>{values.data(), static_cast<int>(samples), 1, channels,
                                   static_cast<std::ptrdiff_t>(samples) * channels});
    const std::size_t per_pixel = static_cast<std::size_t>(sub) * sub;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c) {
          const std::size_t first = (static_cast<std::size_t>(y) * w + x) * per_pixel;
          double sum = 0.0;
          for (std::size_t s = 0; s < per_pixel; ++s) sum += values[(first + s) * channels + c];
          out.at(x0 + x, y0 + y, c) = static_cast<float>(sum / static_cast<double>(per_pixel));
        }
  };
  std::function<void(std::size_t)> on_done;
  if (options.progress)
    on_done = [&](std::size_t done) {
      options.progress(static_cast<double>(done) / static_cast<double>(tile_count));
    };
  parallel_for(tile_count, options.threads, render_tile, on_done);
}

}  // namespace stochtex
