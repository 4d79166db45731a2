#include "methods/lrp/structure_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "methods/lrp/analysis.hpp"
#include "spectral/fft.hpp"
#include "spectral/periodic.hpp"

namespace stochtex::lrp {
namespace {

// The model file's limit on the cosine table (structure_model.cpp); the subdivision stops before.
constexpr double kMaxTableValues = 1 << 24;

// One real cosine of an n x n real DFT: the bin (kx, ky) of the half-plane and its mirror -k
// together, or alone when k == -k (DC and the Nyquist bins).
struct HalfPlaneBin {
  int kx = 0;
  int ky = 0;
  bool self_paired = false;
};

// The distinct real cosines of an n x n DFT, DC included, in a fixed order.
std::vector<HalfPlaneBin> half_plane_bins(int n) {
  std::vector<HalfPlaneBin> bins;
  for (int ky = 0; ky < n; ++ky)
    for (int kx = 0; kx <= n / 2; ++kx) {
      // Columns 0 and n/2 hold each pair twice (ky and n - ky): keep ky <= n/2.
      if ((kx == 0 || kx == n / 2) && ky > n / 2) continue;
      const bool self_paired = (kx == 0 || kx == n / 2) && (ky == 0 || ky == n / 2);
      bins.push_back({kx, ky, self_paired});
    }
  return bins;
}

// The real amplitude of a bin's cosine: |F| / n^2, doubled when k and -k are distinct.
double cosine_amplitude(std::complex<float> value, const HalfPlaneBin& bin, int n) {
  return (bin.self_paired ? 1.0 : 2.0) * std::abs(std::complex<double>(value)) / (double(n) * n);
}

}  // namespace

FixedPhaseRegion fixed_phase_region(ImageView<const float> component, int size, double ratio) {
  if (!(ratio >= 0.0 && ratio <= 1.0))
    throw std::invalid_argument("lrp: the energy ratio r must be between 0 and 1");
  if (component.width < size || component.height < size || component.channels != 1)
    throw std::invalid_argument("lrp: the structure crop does not fit the component");
  ImageF crop(size, size, 1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) crop.at(x, y, 0) = component.at(x, y, 0);
  // The periodic component has no border cross in its spectrum, so R holds the texture's own
  // high-energy frequencies, and its T-periodic repetition has no seams.
  const ImageF periodic = periodic_component(crop.view());
  Fft2d fft(size, size);
  std::vector<std::complex<float>> spectrum(fft.spectrum_size());
  fft.forward(periodic.pixels(), spectrum);
  const auto half = static_cast<std::size_t>(fft.spectrum_width());
  const auto at = [half](int kx, int ky) { return static_cast<std::size_t>(ky) * half + kx; };

  // Section 5.1: "we iteratively add the highest-amplitude frequencies to R" until R holds the
  // fraction r of the energy (DC excluded: the mean is not structure). Ties keep the bin order.
  std::vector<HalfPlaneBin> bins = half_plane_bins(size);
  bins.erase(bins.begin());  // DC
  std::vector<double> energy(bins.size());
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const double a = cosine_amplitude(spectrum[at(bins[i].kx, bins[i].ky)], bins[i], size);
    energy[i] = bins[i].self_paired ? a * a : 0.5 * a * a;
  }
  std::vector<std::size_t> order(bins.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return energy[a] > energy[b]; });
  const double total = std::accumulate(energy.begin(), energy.end(), 0.0);

  FixedPhaseRegion region;
  region.size = size;
  std::vector<std::complex<float>> kept(spectrum.size(), {0.0f, 0.0f});
  double cumulated = 0.0;
  for (const std::size_t i : order) {
    if (energy[i] <= 0.0 || (ratio < 1.0 && cumulated >= ratio * total)) break;
    cumulated += energy[i];
    const HalfPlaneBin& bin = bins[i];
    kept[at(bin.kx, bin.ky)] = spectrum[at(bin.kx, bin.ky)];
    const int mirror_x = (size - bin.kx) % size;
    const int mirror_y = (size - bin.ky) % size;
    // Columns 0 and size/2 hold the mirror in the half-plane too; the inverse reads both.
    if (bin.kx == 0 || bin.kx == size / 2)
      kept[at(bin.kx, mirror_y)] = std::conj(spectrum[at(bin.kx, bin.ky)]);
    region.bins.push_back(bin.ky * size + bin.kx);
    if (!bin.self_paired) region.bins.push_back(mirror_y * size + mirror_x);
  }
  region.energy_fraction = total > 0.0 ? cumulated / total : 0.0;
  region.structure_image.resize(fft.image_size());
  fft.inverse(kept, region.structure_image);
  return region;
}

void remove_region(std::vector<double>& power, const FixedPhaseRegion& region) {
  if (power.size() != static_cast<std::size_t>(region.size) * region.size)
    throw std::invalid_argument("lrp: the power spectrum and the region differ in size");
  for (const int bin : region.bins) power[static_cast<std::size_t>(bin)] = 0.0;
}

int structure_cosines(double ratio, int cosines) {
  if (!(ratio > 0.0)) return 0;
  return std::clamp(static_cast<int>(std::lround(ratio * cosines)), 1, cosines);
}

StructureData reduce_structure(std::span<const FixedPhaseRegion> regions, int cosines_per_block,
                               std::span<const float> colour_basis,
                               std::vector<SubdivisionLevel>* levels) {
  if (regions.empty() || cosines_per_block < 1)
    throw std::invalid_argument("lrp: a structure needs regions and at least one cosine");
  const int channels = static_cast<int>(regions.size());
  const int size = regions.front().size;
  if (colour_basis.size() != static_cast<std::size_t>(channels) * channels)
    throw std::invalid_argument("lrp: the colour basis does not match the channels");
  const std::array<float, kWindowTerms> window = window_coefficients();

  StructureData best;
  // B = 2 is skipped: its blocks' regions (2 x T / 2) are the whole period, the cosines of B = 1.
  for (int blocks = 1; size / blocks >= 2; blocks = blocks == 1 ? 4 : 2 * blocks) {
    if (4.0 * channels * blocks * double(blocks) * cosines_per_block > kMaxTableValues) break;
    const int side = size / blocks;
    // Each block's cosines reproduce the block and half a block around it (n = 2 x side), the
    // whole support of its window (radius one block): our reading of section 5.3's "Delta_R is
    // set to the block size so as to handle transitions" that lets the blocks form a partition
    // of unity, so that keeping every cosine gives back the structure image exactly.
    const int n = 2 * side;
    Fft2d fft(n, n);
    const std::vector<HalfPlaneBin> bins = half_plane_bins(n);
    const auto half = static_cast<std::size_t>(fft.spectrum_width());
    const auto kept = static_cast<std::size_t>(
        std::min<std::size_t>(bins.size(), static_cast<std::size_t>(cosines_per_block)));
    StructureData level;
    level.period = size;
    level.blocks = blocks;
    level.cosines = cosines_per_block;
    level.cosine_table.assign(
        4 * static_cast<std::size_t>(channels) * blocks * blocks * cosines_per_block, 0.0f);
    std::vector<float> region(fft.image_size());
    std::vector<std::complex<float>> spectrum(fft.spectrum_size());
    std::vector<double> energy(bins.size());
    std::vector<std::size_t> order(bins.size());
    for (int c = 0; c < channels; ++c) {
      const std::vector<float>& image = regions[static_cast<std::size_t>(c)].structure_image;
      for (int block_y = 0; block_y < blocks; ++block_y)
        for (int block_x = 0; block_x < blocks; ++block_x) {
          // Pixel m of the region is pixel (block * side - side / 2 + m) mod T of the image.
          const int start_x = block_x * side - side / 2;
          const int start_y = block_y * side - side / 2;
          for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
              region[static_cast<std::size_t>(y) * n + x] =
                  image[static_cast<std::size_t>(((start_y + y) % size + size) % size) * size +
                        static_cast<std::size_t>(((start_x + x) % size + size) % size)];
          fft.forward(region, spectrum);
          // "The J_R highest-amplitude frequencies are selected for each block", ranked by the
          // energy of their real cosine (DC included: a small block is mostly its mean).
          for (std::size_t i = 0; i < bins.size(); ++i) {
            const double a = cosine_amplitude(
                spectrum[static_cast<std::size_t>(bins[i].ky) * half + bins[i].kx], bins[i], n);
            energy[i] = bins[i].self_paired ? a * a : 0.5 * a * a;
          }
          std::iota(order.begin(), order.end(), std::size_t{0});
          std::stable_sort(order.begin(), order.end(),
                           [&](std::size_t a, std::size_t b) { return energy[a] > energy[b]; });
          float* out = &level.cosine_table[4 * ((static_cast<std::size_t>(c) * blocks * blocks +
                                                 static_cast<std::size_t>(block_y) * blocks +
                                                 static_cast<std::size_t>(block_x)) *
                                                cosines_per_block)];
          // Fewer distinct frequencies than J_R (tiny blocks): the rest stay silent (amplitude 0).
          for (std::size_t j = 0; j < kept; ++j, out += 4) {
            const HalfPlaneBin& bin = bins[order[j]];
            const std::complex<float> value =
                spectrum[static_cast<std::size_t>(bin.ky) * half + bin.kx];
            const double fx = double(bin.kx) / n;
            const double fy = double(bin.ky > n / 2 ? bin.ky - n : bin.ky) / n;
            // Sample m sits at x = start + m + 1/2 and the node at the block centre, start + side:
            // the cosine's argument at x is f.(x - node) + f.(side - 1/2) + arg F / 2 pi turns.
            double phase = std::arg(std::complex<double>(value)) / (2.0 * std::numbers::pi) +
                           (fx + fy) * (side - 0.5);
            phase -= std::floor(phase);
            auto phase_float = static_cast<float>(phase);
            if (phase_float >= 1.0f) phase_float = 0.0f;
            out[0] = static_cast<float>(fx);
            out[1] = static_cast<float>(fy);
            out[2] = static_cast<float>(cosine_amplitude(value, bin, n));
            out[3] = phase_float;
          }
        }
    }
    // Section 5.3: n_R evaluated at the pixels of the structure image, mean colour deviation.
    double deviation = 0.0;
    std::vector<float> noise(static_cast<std::size_t>(channels));
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        std::fill(noise.begin(), noise.end(), 0.0f);
        add_fixed_phase(level, window, {x + 0.5, y + 0.5}, nullptr, 1.0f, channels, noise.data());
        const std::size_t pixel = static_cast<std::size_t>(y) * size + x;
        for (int c = 0; c < channels; ++c) {
          double difference = 0.0;
          for (int k = 0; k < channels; ++k)
            difference += colour_basis[static_cast<std::size_t>(c * channels + k)] *
                          (double(noise[static_cast<std::size_t>(k)]) -
                           regions[static_cast<std::size_t>(k)].structure_image[pixel]);
          deviation += std::abs(difference);
        }
      }
    deviation /= double(size) * size * channels;
    if (levels != nullptr) levels->push_back({blocks, deviation});
    best = std::move(level);
    if (deviation < kStructureTolerance) break;
  }
  return best;
}

void plan_turbulence(std::span<const double> power, int size, double turbulence, std::uint32_t key,
                     StructureData& structure) {
  structure.turbulence = static_cast<float>(turbulence);
  if (!(turbulence > 0.0)) return;
  const double variance = std::accumulate(power.begin(), power.end(), 0.0);
  const double scale = variance > 0.0 ? 1.0 / std::sqrt(variance) : 0.0;
  // Constant amplitudes per stratum (shaped = false): n_T only needs the exemplar's spectral
  // scale, and its tables carry no per-frequency weights.
  for (const StratumPlan& plan :
       plan_strata(power, size, kTurbulenceStrata, kTurbulenceCosines, false, {}, key)) {
    structure.turbulence_strata.push_back({plan.sampling.cosines, plan.sampling.spacing,
                                           static_cast<float>(plan.sampling.amplitude * scale)});
    for (const auto& substratum : plan.substrata) {
      structure.turbulence_first.push_back(
          static_cast<std::uint32_t>(structure.turbulence_frequencies.size() / 2));
      structure.turbulence_count.push_back(static_cast<std::uint32_t>(substratum.size()));
      for (const auto& bin : substratum) {
        structure.turbulence_frequencies.push_back(static_cast<float>(bin[0]) /
                                                   static_cast<float>(size));
        structure.turbulence_frequencies.push_back(static_cast<float>(bin[1]) /
                                                   static_cast<float>(size));
      }
    }
  }
}

}  // namespace stochtex::lrp
