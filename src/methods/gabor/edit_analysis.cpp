#include "methods/gabor/edit_analysis.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <span>
#include <stdexcept>

#include "model/model_data.hpp"

namespace stochtex::gabor {

bool GaussianGroup::contains(const GaussianComponent& g) const {
  const double frequency = std::hypot(g.frequency_x, g.frequency_y);
  return (channel < 0 || g.channel == channel) && g.band >= first_band && g.band <= last_band &&
         frequency >= min_frequency && frequency <= max_frequency;
}

GaborModel edit_gaussians(const GaborModel& model, const GaussianGroup& group,
                          const SpectrumEdit& edit) {
  std::vector<bool> selected;
  selected.reserve(model.gaussians().size());
  for (const GaussianComponent& g : model.gaussians()) selected.push_back(group.contains(g));
  return edit_gaussians(model, selected, edit);
}

GaborModel edit_gaussians(const GaborModel& model, const std::vector<bool>& selected,
                          const SpectrumEdit& edit) {
  if (!std::isfinite(edit.rotation) || !std::isfinite(edit.scale) ||
      !std::isfinite(edit.translation_x) || !std::isfinite(edit.translation_y) ||
      !(edit.magnitude >= 0.0) || !std::isfinite(edit.magnitude))
    throw std::invalid_argument("gabor edit: every transform value must be finite, magnitude >= 0");
  if (selected.size() != model.gaussians().size())
    throw std::invalid_argument("gabor edit: the selection does not match the model's Gaussians");
  const double c = std::cos(edit.rotation);
  const double s = std::sin(edit.rotation);
  std::vector<GaussianComponent> edited;
  edited.reserve(model.gaussians().size());
  for (std::size_t i = 0; i < selected.size(); ++i) {
    GaussianComponent g = model.gaussians()[i];
    if (selected[i]) {
      const double x = edit.scale * (c * g.frequency_x - s * g.frequency_y) + edit.translation_x;
      const double y = edit.scale * (s * g.frequency_x + c * g.frequency_y) + edit.translation_y;
      if (!(std::abs(x) <= 0.5) || !(std::abs(y) <= 0.5)) continue;
      g.frequency_x = static_cast<float>(x);
      g.frequency_y = static_cast<float>(y);
      g.variance = static_cast<float>(g.variance * edit.magnitude * edit.magnitude);
      g.band = std::clamp(g.band + edit.bandwidth_shift, 0, kMaxBands - 1);
      if (!(g.variance > 0.0f) || !std::isfinite(g.variance)) continue;
    }
    edited.push_back(g);
  }
  // A model file cannot hold an empty Gaussian table, and a noise without Gaussians is constant.
  if (edited.empty() && !model.gaussians().empty())
    throw std::invalid_argument(
        "gabor edit: the edit leaves no Gaussian (all moved beyond Nyquist or to zero magnitude)");
  return GaborModel(model.channels(), model.impulses(), model.colour_space(), std::move(edited),
                    std::vector<float>(model.mixing().begin(), model.mixing().end()),
                    std::vector<float>(model.mean().begin(), model.mean().end()), model.report());
}

std::string_view component_name(WoldComponent component) {
  switch (component) {
    case WoldComponent::periodic:
      return "periodic";
    case WoldComponent::anisotropic:
      return "anisotropic";
    case WoldComponent::stochastic:
      break;
  }
  return "stochastic";
}

namespace {

// Standard deviation of band b's spectral Gaussians, a_b / (2 sqrt(pi)) (eq. 3), and their full
// width at half maximum, 2^-b cycles per pixel (section 4.3).
double spectral_deviation(int band) {
  return bandwidth(band) / (2.0 * std::sqrt(kPi));
}
double full_width(int band) {
  return std::ldexp(1.0, -band);
}

// The power spectral density of eq. (6) of the given Gaussians at (x, y), periodic with period 1
// (the pixel grid aliases frequencies beyond Nyquist). Terms beyond 6 standard deviations
// (e^-18) are skipped; the wide bands 0-2 also sum the periods their tails reach.
double spectral_density(std::span<const GaussianComponent* const> gaussians, double x, double y) {
  double sum = 0.0;
  for (const GaussianComponent* g : gaussians) {
    const double deviation = spectral_deviation(g->band);
    const double reach_squared = 36.0 * deviation * deviation;
    const int periods = static_cast<int>(std::floor(6.0 * deviation + 0.5));
    double value = 0.0;
    for (const double sign : {1.0, -1.0}) {
      double dx = x - sign * g->frequency_x;
      double dy = y - sign * g->frequency_y;
      dx -= std::round(dx);
      dy -= std::round(dy);
      for (int py = -periods; py <= periods; ++py)
        for (int px = -periods; px <= periods; ++px) {
          const double ex = dx + px;
          const double ey = dy + py;
          const double distance_squared = ex * ex + ey * ey;
          if (distance_squared < reach_squared)
            value += std::exp(-distance_squared / (2.0 * deviation * deviation));
        }
    }
    // Each lobe of the pair holds half the variance (eq. 3): sigma^2 / 2 N(xi; +-omega, s).
    sum += 0.5 * g->variance * value / (2.0 * kPi * deviation * deviation);
  }
  return sum;
}

// Section 8, harmonic part: isolated, strong, narrow peaks (see edit_analysis.hpp).
void mark_periodic(std::span<const GaussianComponent* const> channel,
                   std::span<WoldComponent* const> labels) {
  constexpr int kRingPoints = 16;
  double channel_variance = 0.0;
  for (const GaussianComponent* g : channel) channel_variance += g->variance;
  // Candidates hold at least a quarter of a peak's least variance (a peak between bins is fitted
  // by up to 4 neighbouring Gaussians): a fit that also covers the diffuse spectrum with narrow
  // Gaussians (the weighted fit's defaults) would otherwise chain every peak to its neighbours.
  std::vector<std::size_t> narrow;
  for (std::size_t i = 0; i < channel.size(); ++i) {
    const GaussianComponent& g = *channel[i];
    if (full_width(g.band) <= kPeriodicMaxFwhm &&
        std::hypot(g.frequency_x, g.frequency_y) >= 3.0 * full_width(g.band) &&
        g.variance >= 0.25 * kPeakMinShare * channel_variance)
      narrow.push_back(i);
  }
  // Clusters: narrow Gaussians within 2 FWHM of each other (a peak between frequency bins is
  // fitted by neighbouring Gaussians), omega and -omega being the same pair.
  const auto distance = [&](std::size_t a, std::size_t b) {
    const GaussianComponent& ga = *channel[a];
    const GaussianComponent& gb = *channel[b];
    return std::min(std::hypot(ga.frequency_x - gb.frequency_x, ga.frequency_y - gb.frequency_y),
                    std::hypot(ga.frequency_x + gb.frequency_x, ga.frequency_y + gb.frequency_y));
  };
  std::vector<std::size_t> parent(narrow.size());
  for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = k;
  const auto root = [&](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  // Neighbours are found through a grid of cells of side 2 kPeriodicMaxFwhm (the largest link
  // distance), each Gaussian entered at omega and -omega: a 3 x 3 block of cells holds all the
  // candidates within reach, so the clustering costs O(n) for spread-out spectra.
  constexpr int kCells = static_cast<int>(0.5 / kPeriodicMaxFwhm);
  const auto cell = [](double f) {
    return std::clamp(static_cast<int>(std::floor((f + 0.5) * kCells)), 0, kCells - 1);
  };
  std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(kCells) * kCells);
  for (std::size_t k = 0; k < narrow.size(); ++k)
    for (const double sign : {1.0, -1.0}) {
      const GaussianComponent& g = *channel[narrow[k]];
      std::vector<std::size_t>& bucket =
          cells[static_cast<std::size_t>(cell(sign * g.frequency_y)) * kCells +
                static_cast<std::size_t>(cell(sign * g.frequency_x))];
      if (bucket.empty() || bucket.back() != k) bucket.push_back(k);
    }
  for (std::size_t a = 0; a < narrow.size(); ++a) {
    const GaussianComponent& g = *channel[narrow[a]];
    const int cx = cell(g.frequency_x);
    const int cy = cell(g.frequency_y);
    for (int y = std::max(0, cy - 1); y <= std::min(kCells - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(kCells - 1, cx + 1); ++x)
        for (const std::size_t b : cells[static_cast<std::size_t>(y) * kCells + x]) {
          if (b <= a) continue;
          const double width =
              std::max(full_width(channel[narrow[a]]->band), full_width(channel[narrow[b]]->band));
          if (distance(narrow[a], narrow[b]) <= 2.0 * width) parent[root(a)] = root(b);
        }
  }
  // Members of each cluster, listed once.
  std::vector<std::vector<std::size_t>> clusters(narrow.size());
  for (std::size_t m = 0; m < narrow.size(); ++m) clusters[root(m)].push_back(narrow[m]);
  for (const std::vector<std::size_t>& members : clusters) {
    if (members.empty()) continue;
    // Centre: variance-weighted, each member taken on the side of the pair nearest the first.
    const GaussianComponent& first = *channel[members.front()];
    double cx = 0.0, cy = 0.0, variance = 0.0, width = 1.0;
    for (const std::size_t i : members) {
      const GaussianComponent& g = *channel[i];
      const double same =
          std::hypot(g.frequency_x - first.frequency_x, g.frequency_y - first.frequency_y);
      const double mirrored =
          std::hypot(g.frequency_x + first.frequency_x, g.frequency_y + first.frequency_y);
      const double sign = same <= mirrored ? 1.0 : -1.0;
      cx += g.variance * sign * g.frequency_x;
      cy += g.variance * sign * g.frequency_y;
      variance += g.variance;
      width = std::min(width, full_width(g.band));
    }
    cx /= variance;
    cy /= variance;
    double radius = 0.0;
    for (const std::size_t i : members) {
      const GaussianComponent& g = *channel[i];
      radius = std::max(radius, std::min(std::hypot(g.frequency_x - cx, g.frequency_y - cy),
                                         std::hypot(g.frequency_x + cx, g.frequency_y + cy)));
    }
    // A spectral line: compact (spread over at most 2 FWHM), strong and isolated.
    if (radius > 2.0 * width || variance < kPeakMinShare * channel_variance) continue;
    double peak = 0.0;
    for (const std::size_t i : members)
      peak = std::max(peak,
                      spectral_density(channel, channel[i]->frequency_x, channel[i]->frequency_y));
    double ring = 0.0;
    const double ring_radius = radius + 3.0 * width;
    for (int r = 0; r < kRingPoints; ++r) {
      const double angle = 2.0 * kPi * r / kRingPoints;
      ring += spectral_density(channel, cx + ring_radius * std::cos(angle),
                               cy + ring_radius * std::sin(angle)) /
              kRingPoints;
    }
    if (peak >= kPeakProminence * ring)
      for (const std::size_t i : members) *labels[i] = WoldComponent::periodic;
  }
}

// Section 8, evanescent part: lines of Gaussians through the origin (see edit_analysis.hpp).
void mark_anisotropic(std::span<const GaussianComponent* const> channel,
                      std::span<WoldComponent* const> labels) {
  constexpr int kBins = kOrientationBins;
  std::vector<double> histogram(kBins, 0.0);
  std::vector<int> bin_of(channel.size(), -1);
  double total = 0.0;
  for (std::size_t i = 0; i < channel.size(); ++i) {
    const GaussianComponent& g = *channel[i];
    if (*labels[i] != WoldComponent::stochastic ||
        std::hypot(g.frequency_x, g.frequency_y) < 2.0 * spectral_deviation(g.band))
      continue;
    double angle = std::atan2(g.frequency_y, g.frequency_x);
    if (angle < 0.0) angle += kPi;
    bin_of[i] = std::min(kBins - 1, static_cast<int>(angle / kPi * kBins));
    histogram[static_cast<std::size_t>(bin_of[i])] += g.variance;
    total += g.variance;
  }
  if (!(total > 0.0)) return;
  const auto wrap = [](int bin) { return static_cast<std::size_t>((bin + kBins) % kBins); };
  std::vector<bool> flagged(kBins);
  for (int k = 0; k < kBins; ++k)
    flagged[wrap(k)] = histogram[wrap(k - 1)] + histogram[wrap(k)] + histogram[wrap(k + 1)] >=
                       kOrientationExcess * 3.0 * total / kBins;
  // Runs of flagged bins, taken circularly (orientation is mod pi): start after an unflagged bin.
  int start = 0;
  while (start < kBins && flagged[wrap(start)]) ++start;
  if (start == kBins) return;  // every direction is in excess: an isotropic spectrum
  for (int offset = 1; offset <= kBins;) {
    const int first = start + offset;
    if (!flagged[wrap(first)]) {
      ++offset;
      continue;
    }
    int last = first;
    while (flagged[wrap(last + 1)]) ++last;
    offset += last - first + 1;
    std::vector<bool> in_run(kBins, false);
    for (int k = first; k <= last; ++k) in_run[wrap(k)] = true;
    // The run's direction: the principal axis of its Gaussians' frequencies (sign-free).
    double sxx = 0.0, sxy = 0.0, syy = 0.0, weight = 0.0;
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < channel.size(); ++i) {
      if (bin_of[i] < 0 || !in_run[static_cast<std::size_t>(bin_of[i])]) continue;
      const GaussianComponent& g = *channel[i];
      members.push_back(i);
      sxx += g.variance * g.frequency_x * g.frequency_x;
      sxy += g.variance * g.frequency_x * g.frequency_y;
      syy += g.variance * g.frequency_y * g.frequency_y;
      weight += g.variance;
    }
    if (members.size() < 3) continue;
    const double direction = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    const double ux = std::cos(direction), uy = std::sin(direction);
    // Radial positions (folded: omega and -omega are one pair) and tangential offsets.
    double radial_mean = 0.0, radial_square = 0.0, tangential_square = 0.0, spread = 0.0;
    for (const std::size_t i : members) {
      const GaussianComponent& g = *channel[i];
      const double w = g.variance / weight;
      const double radial = std::abs(ux * g.frequency_x + uy * g.frequency_y);
      const double tangential = -uy * g.frequency_x + ux * g.frequency_y;
      const double deviation = spectral_deviation(g.band);
      radial_mean += w * radial;
      radial_square += w * radial * radial;
      tangential_square += w * tangential * tangential;
      spread += w * deviation * deviation;
    }
    const double along = radial_square - radial_mean * radial_mean + spread;
    const double across = tangential_square + spread;
    if (along >= kElongation * kElongation * across)
      for (const std::size_t i : members) *labels[i] = WoldComponent::anisotropic;
  }
}

}  // namespace

std::vector<WoldComponent> wold_components(const GaborModel& model) {
  const std::vector<GaussianComponent>& gaussians = model.gaussians();
  std::vector<WoldComponent> labels(gaussians.size(), WoldComponent::stochastic);
  for (int c = 0; c < model.channels(); ++c) {
    std::vector<const GaussianComponent*> channel;
    std::vector<WoldComponent*> channel_labels;
    for (std::size_t i = 0; i < gaussians.size(); ++i)
      if (gaussians[i].channel == c) {
        channel.push_back(&gaussians[i]);
        channel_labels.push_back(&labels[i]);
      }
    if (channel.empty()) continue;
    mark_periodic(channel, channel_labels);
    mark_anisotropic(channel, channel_labels);
  }
  return labels;
}

}  // namespace stochtex::gabor

namespace stochtex::gabor {

namespace {

constexpr std::array<WoldComponent, 3> kComponents = {
    WoldComponent::periodic, WoldComponent::anisotropic, WoldComponent::stochastic};

// The shortest text that reads back as `value`, as fmt's "{}".
std::string number(double value) {
  std::array<char, 32> text;
  const auto end = std::to_chars(text.data(), text.data() + text.size(), value).ptr;
  return {text.data(), end};
}

}  // namespace

std::array<GroupShare, 3> group_shares(const GaborModel& model,
                                       const std::vector<WoldComponent>& labels) {
  std::array<GroupShare, 3> shares;
  std::array<double, 3> variances{};
  double total = 0.0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const auto slot = static_cast<std::size_t>(labels[i]);
    ++shares[slot].gaussians;
    variances[slot] += model.gaussians()[i].variance;
    total += model.gaussians()[i].variance;
  }
  std::array<GroupShare, 3> ordered;
  for (std::size_t k = 0; k < kComponents.size(); ++k) {
    const auto slot = static_cast<std::size_t>(kComponents[k]);
    ordered[k] = {kComponents[k], shares[slot].gaussians,
                  total > 0.0 ? variances[slot] / total : 0.0};
  }
  return ordered;
}

nlohmann::ordered_json groups_json(const GaborModel& model,
                                   const std::vector<WoldComponent>& labels) {
  nlohmann::ordered_json doc{{"gaussians", labels.size()}};
  for (const GroupShare& share : group_shares(model, labels))
    doc["groups"][std::string(component_name(share.component))] = {
        {"gaussians", share.gaussians}, {"variance_share", share.variance_share}};
  return doc;
}

std::vector<bool> select_group(const std::vector<WoldComponent>& labels, std::string_view group,
                               std::string_view prefix) {
  if (group == "all") return std::vector<bool>(labels.size(), true);
  if (std::none_of(kComponents.begin(), kComponents.end(),
                   [group](WoldComponent c) { return component_name(c) == group; }))
    throw std::invalid_argument(std::string(prefix) +
                                "group must be all, periodic, anisotropic or stochastic, not '" +
                                std::string(group) + "'");
  std::vector<bool> selected(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) selected[i] = component_name(labels[i]) == group;
  return selected;
}

SpectrumEdit spectrum_edit(const EditRequest& request, std::string_view prefix) {
  select_group({}, request.group, prefix);
  const std::string name(prefix);
  if (!std::isfinite(request.rotate_degrees) || !std::isfinite(request.scale) ||
      !(request.scale > 0.0))
    throw std::invalid_argument(name + "rotate must be finite and " + name +
                                "scale a positive number, not " + number(request.rotate_degrees) +
                                " and " + number(request.scale));
  if (!(std::abs(request.translate_x) <= kMaxTranslation) ||
      !(std::abs(request.translate_y) <= kMaxTranslation))
    throw std::invalid_argument(name + "translate must be in cycles per pixel, each within [-" +
                                number(kMaxTranslation) + ", " + number(kMaxTranslation) +
                                "], not " + number(request.translate_x) + "," +
                                number(request.translate_y));
  if (!(request.magnitude >= 0.0 && request.magnitude <= kMaxMagnitude))
    throw std::invalid_argument(name + "magnitude must be a number from 0 to " +
                                number(kMaxMagnitude) + ", not " + number(request.magnitude));
  // The bandwidths are quantised to a_b = 2^-b a_0 (section 4.3): a factor of 2^k shifts the band
  // index by -k.
  const double exponent = std::log2(request.bandwidth);
  if (!(request.bandwidth > 0.0) || exponent != std::round(exponent) ||
      std::abs(exponent) >= kMaxBands)
    throw std::invalid_argument(name +
                                "bandwidth must be a power of two such as 0.5 or 2 (the "
                                "bandwidths are quantised to powers of two, section 4.3 of the "
                                "paper), not " +
                                number(request.bandwidth));
  SpectrumEdit edit;
  edit.rotation = request.rotate_degrees * std::numbers::pi / 180.0;
  edit.scale = request.scale;
  edit.translation_x = request.translate_x;
  edit.translation_y = request.translate_y;
  edit.magnitude = request.magnitude;
  edit.bandwidth_shift = -static_cast<int>(exponent);
  return edit;
}

namespace {

constexpr std::array<std::string_view, 4> kGroupNames = {"all", "periodic", "anisotropic",
                                                         "stochastic"};
// The studio's sliders span the useful part of each range: half a turn either way, translations
// up to half the Nyquist frequency, magnitudes up to 4, two octaves of scale and three of bandwidth
// either way.
constexpr std::array<EditField, 5> kEditFields = {{
    {.name = "rotate",
     .help = "rotate the group's frequencies by DEG degrees, counter-clockwise",
     .default_value = 0.0,
     .slider = {.low = -180.0, .high = 180.0, .step = 1.0, .suffix = "\u00b0"}},
    {.name = "scale",
     .help = "multiply the group's frequencies by S (> 1: finer detail)",
     .default_value = 1.0,
     .slider = {.low = -2.0, .high = 2.0, .step = 0.05, .octaves = true, .prefix = "\u00d7"}},
    {.name = "translate",
     .help = "add FX,FY cycles per pixel to the group's frequencies",
     .default_value = 0.0,
     .components = 2,
     .max_abs = kMaxTranslation,
     .slider = {.low = -0.25, .high = 0.25, .step = 0.005, .suffix = " cycles/pixel"}},
    {.name = "magnitude",
     .help = "multiply the group's kernel magnitude K by this (the variance by its square)",
     .default_value = 1.0,
     .slider = {.low = 0.0, .high = 4.0, .step = 0.05, .prefix = "\u00d7"}},
    {.name = "bandwidth",
     .help = "multiply the group's bandwidth a by this power of two (< 1: sharper spectral "
             "Gaussians, longer-range kernels); each Gaussian keeps its variance",
     .default_value = 1.0,
     .slider = {.low = -3.0, .high = 3.0, .step = 1.0, .octaves = true, .prefix = "\u00d7"}},
}};

const GaborModel& gabor_of(const Model& model) {
  const auto* gabor = std::get_if<GaborModel>(&model.data().model);
  if (gabor == nullptr)
    throw std::invalid_argument("a " + std::string(model.method()) + " model is not a gabor model");
  return *gabor;
}

const std::vector<WoldComponent>& labels_of(const void* groups) {
  return *static_cast<const std::vector<WoldComponent>*>(groups);
}

std::shared_ptr<const void> find_groups(const Model& model) {
  return std::make_shared<const std::vector<WoldComponent>>(wold_components(gabor_of(model)));
}

nlohmann::ordered_json edit_groups_json(const Model& model, const void* groups) {
  return groups_json(gabor_of(model), labels_of(groups));
}

std::string groups_table(const Model& model, const void* groups) {
  std::array<char, 96> line{};
  std::snprintf(line.data(), line.size(), "%-14s%10s%16s\n", "group", "gaussians",
                "variance share");
  std::string table = line.data();
  for (const GroupShare& share : group_shares(gabor_of(model), labels_of(groups))) {
    std::snprintf(line.data(), line.size(), "%-14s%10zu%15.1f%%\n",
                  std::string(component_name(share.component)).c_str(), share.gaussians,
                  100.0 * share.variance_share);
    table += line.data();
  }
  return table;
}

EditResult edit(const Model& model, const void* groups, const EditValues& values,
                std::string_view prefix) {
  EditRequest request;
  request.group = values.group;
  const auto given = [&](std::string_view name, std::size_t component, double fallback) {
    const auto found = values.numbers.find(name);
    return found == values.numbers.end() || found->second.size() <= component
               ? fallback
               : found->second[component];
  };
  request.rotate_degrees = given("rotate", 0, request.rotate_degrees);
  request.scale = given("scale", 0, request.scale);
  request.translate_x = given("translate", 0, request.translate_x);
  request.translate_y = given("translate", 1, request.translate_y);
  request.magnitude = given("magnitude", 0, request.magnitude);
  request.bandwidth = given("bandwidth", 0, request.bandwidth);
  const SpectrumEdit spectrum = spectrum_edit(request, prefix);
  const GaborModel& gabor = gabor_of(model);
  const std::vector<bool> selected = select_group(labels_of(groups), request.group, prefix);
  GaborModel edited = edit_gaussians(gabor, selected, spectrum);
  const std::size_t dropped = gabor.gaussians().size() - edited.gaussians().size();
  std::string summary = request.group + " group: " +
                        std::to_string(std::count(selected.begin(), selected.end(), true)) +
                        " Gaussians edited";
  if (dropped > 0)
    summary += ", " + std::to_string(dropped) + " moved beyond Nyquist or to zero and dropped";
  return {with_method_model(model, std::move(edited)), std::move(summary)};
}

}  // namespace

const EditCapability kEdit{
    "edit a gabor model's spectrum by groups of Gaussians: periodic peaks, anisotropic lines, the "
    "stochastic rest (section 8 of the Gabor noise paper)",
    kGroupNames,
    kEditFields,
    &find_groups,
    &edit_groups_json,
    &groups_table,
    &edit};

}  // namespace stochtex::gabor
