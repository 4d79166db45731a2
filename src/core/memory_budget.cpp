#include "core/memory_budget.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace stochtex {

std::uint64_t render_peak_bytes(int width, int height, int tile, int supersample, int threads,
                                int channels) {
  const auto pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  const auto tile_width = static_cast<std::uint64_t>(std::min(tile, width));
  const auto tile_height = static_cast<std::uint64_t>(std::min(tile, height));
  const std::uint64_t tiles = ((static_cast<std::uint64_t>(width) + tile - 1) / tile) *
                              ((static_cast<std::uint64_t>(height) + tile - 1) / tile);
  const std::uint64_t workers = std::min<std::uint64_t>(static_cast<std::uint64_t>(threads), tiles);
  const auto samples_per_pixel = static_cast<std::uint64_t>(supersample) * supersample;
  const std::uint64_t bytes_per_sample = supersample == 1 ? 48 : 32;
  const auto image_bytes = 6 * static_cast<std::uint64_t>(std::max(channels, 4));
  return image_bytes * pixels +
         workers * tile_width * tile_height * samples_per_pixel * bytes_per_sample;
}

std::uint64_t gaussian_peak_bytes(int width, int height, int exemplar_width, int exemplar_height,
                                  int channels) {
  // A 7-smooth size is at most a few percent above its minimum beyond a hundred.
  const auto domain_side = [](int output, int exemplar) {
    return static_cast<std::uint64_t>(output + exemplar) * 21 / 20 + 8;
  };
  const auto pixels = [](int w, int h) {
    return static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  };
  const std::uint64_t domain =
      exemplar_width > 0 ? domain_side(width, exemplar_width) * domain_side(height, exemplar_height)
                         : pixels(width, height);
  return 24 * domain + 24 * pixels(width, height) +
         (24 + 8 * static_cast<std::uint64_t>(channels)) * pixels(exemplar_width, exemplar_height);
}

std::uint64_t evaluate_peak_bytes(std::uint64_t points, int channels) {
  return kFixedPeakBytes +
         points * (2 * 48 + 4 * static_cast<std::uint64_t>(std::max(channels, 0)));
}

std::uint64_t compare_peak_bytes(std::uint64_t exemplar_pixels, std::uint64_t image_pixels,
                                 int channels) {
  return kFixedPeakBytes +
         (exemplar_pixels + image_pixels) * (56 + 12 * static_cast<std::uint64_t>(channels));
}

std::uint64_t mix_peak_bytes(int width, int height, int channels, int steps, int support) {
  const auto count = [](int n) { return static_cast<std::uint64_t>(std::max(n, 0)); };
  const std::uint64_t side = count(std::min({support, width, height}));
  return kFixedPeakBytes + count(width) * count(height) * (24 + 46 * count(channels)) +
         28 * count(steps) * side * side * count(channels);
}

void check_memory_budget(std::uint64_t bytes, const std::string& request,
                         const std::string& remedy) {
  if (bytes <= kMemoryBudgetBytes) return;
  char needed[32];
  std::snprintf(needed, sizeof needed, "%.1f", static_cast<double>(bytes) / 1e9);
  throw std::invalid_argument(request + " needs about " + needed +
                              " GB of memory, more than the budget of " +
                              std::to_string(kMemoryBudgetBytes >> 30) + " GiB; " + remedy);
}

void HeldImages::add(int width, int height, int channels, const std::string& name) {
  bytes_ += std::uint64_t{4} * static_cast<std::uint64_t>(width) *
            static_cast<std::uint64_t>(height) * static_cast<std::uint64_t>(channels);
  check_memory_budget(kFixedPeakBytes + bytes_,
                      "holding '" + name + "' (" + std::to_string(width) + "x" +
                          std::to_string(height) + ") beside the other images",
                      "crop or downscale the images");
}

std::function<void(int width, int height, int channels)> HeldImages::check(
    const std::string& name) {
  return [this, name](int width, int height, int channels) { add(width, height, channels, name); };
}

}  // namespace stochtex
