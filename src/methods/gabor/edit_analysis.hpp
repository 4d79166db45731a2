#pragma once
// Editing a fitted Gabor noise (section 8): transforms of its Gaussians in frequency and their
// automatic grouping into the components of a 2-D Wold decomposition. Analysis-time tools (used by
// `stochtex edit`): evaluating a model needs none of them, so they live in stochtex::analysis.

#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "methods/capabilities.hpp"
#include "methods/gabor/model.hpp"

namespace stochtex::gabor {

// Transforms of the Gaussians in frequency, for all of them or a group.
// Which Gaussians an edit touches: a channel (-1 = all), a band range and a range of |omega|.
struct GaussianGroup {
  int channel = -1;
  int first_band = 0;
  int last_band = kMaxBands - 1;
  double min_frequency = 0.0;  // cycles per pixel
  double max_frequency = 1.0;
  bool contains(const GaussianComponent& g) const;
};

// omega' = scale * R(rotation) * omega + translation (rotation in radians, counter-clockwise),
// K' = magnitude * K, i.e. variance' = magnitude^2 * variance (section 8: the magnitude is the
// kernel amplitude K of eq. 2, the variance K^2 / (4 a^2) of section 4.4 follows),
// band' = band + bandwidth_shift (clamped to the quantised set: +1 halves the bandwidth a_b,
// i.e. a narrower spectral Gaussian and a wider kernel; the variance is kept).
struct SpectrumEdit {
  double rotation = 0.0;
  double scale = 1.0;
  double translation_x = 0.0;
  double translation_y = 0.0;
  double magnitude = 1.0;
  int bandwidth_shift = 0;
};

// The model with the group's Gaussians edited; Gaussians moved beyond Nyquist (|omega_x| or
// |omega_y| > 1/2) or scaled to zero are dropped, as the pixel grid cannot show them. The alias
// tables and budget split are rebuilt in linear time (section 6.2) by the model's constructor,
// which validates the result. Throws std::invalid_argument for a non-finite edit, a negative
// magnitude, or an edit that leaves no Gaussian.
GaborModel edit_gaussians(const GaborModel& model, const GaussianGroup& group,
                          const SpectrumEdit& edit);
// The same for the Gaussians i with selected[i] (one flag per model.gaussians()).
GaborModel edit_gaussians(const GaborModel& model, const std::vector<bool>& selected,
                          const SpectrumEdit& edit);

// Automatic grouping of the Gaussians (section 8), after the 2-D Wold decomposition (Francos,
// Meiri & Porat 1993; Liu 1997): a regular field is the sum of a harmonic part (spectral peaks:
// periodic patterns), an evanescent part (spectral energy on lines: strongly anisotropic
// patterns) and a purely indeterministic part (a diffuse spectrum: the stochastic rest). Each
// synthesis channel's spectrum (eq. 6) is decomposed on its own, as it is fitted on its own
// (section 7). The criteria, in order:
//  - periodic: narrow Gaussians (FWHM <= kPeriodicMaxFwhm cycles per pixel, i.e. band >= 6: waves
//    coherent over 60 pixels or more) away from DC (|omega| >= 3 FWHM) are clustered when within
//    2 FWHM of each other (a peak between frequency bins is fitted by neighbouring Gaussians). A
//    cluster is a spectral peak when it is compact (every member within 2 FWHM of its centre),
//    strong (at least kPeakMinShare of the channel's variance) and isolated: the spectrum at its
//    highest member stands kPeakProminence times above its mean on the ring 3 FWHM beyond the
//    cluster (as Liu detects harmonic peaks above the local level of the spectrum);
//  - anisotropic: the other Gaussians with a direction (|omega| >= 2 spectral standard
//    deviations) are binned by orientation mod pi (kOrientationBins bins). A run of bins whose
//    3-bin window holds kOrientationExcess times the share of an isotropic spectrum is a
//    candidate direction; its Gaussians are a line through the origin (an evanescent component)
//    when there are at least 3 of them and their energy spreads along the direction at least
//    kElongation times as far as across it (radial against tangential standard deviation, each
//    Gaussian counted with its own spectral spread), so a single off-centre blob is not a line;
//  - stochastic: everything else.
enum class WoldComponent : std::uint8_t { stochastic = 0, periodic = 1, anisotropic = 2 };
inline constexpr double kPeriodicMaxFwhm = 1.0 / 64.0;
inline constexpr double kPeakProminence = 4.0;
inline constexpr double kPeakMinShare = 1.0 / 256.0;
inline constexpr int kOrientationBins = 64;
inline constexpr double kOrientationExcess = 4.0;
inline constexpr double kElongation = 3.0;
std::string_view component_name(WoldComponent component);

// One label per model.gaussians(), in the same order.
std::vector<WoldComponent> wold_components(const GaborModel& model);

// How many Gaussians and what share of the variance each group holds (0 shares for a model
// without variance), in the order periodic, anisotropic, stochastic.
struct GroupShare {
  WoldComponent component = WoldComponent::stochastic;
  std::size_t gaussians = 0;
  double variance_share = 0.0;
};
std::array<GroupShare, 3> group_shares(const GaborModel& model,
                                       const std::vector<WoldComponent>& labels);
// {"gaussians": n, "groups": {"periodic": {"gaussians", "variance_share"}, ...}}: what
// `stochtex edit --list-groups --json` prints and the studio's /api/models/<id>/groups answers.
nlohmann::ordered_json groups_json(const GaborModel& model,
                                   const std::vector<WoldComponent>& labels);

// An edit as a person asks for it (`stochtex edit`'s options, the studio's edit panel): a group
// name ("all" or a component_name), degrees, and a bandwidth factor that is a power of two.
struct EditRequest {
  std::string group = "all";
  double rotate_degrees = 0.0;
  double scale = 1.0;
  double translate_x = 0.0;  // cycles per pixel, each within [-kMaxTranslation, kMaxTranslation]
  double translate_y = 0.0;
  double magnitude = 1.0;  // 0 to kMaxMagnitude
  double bandwidth = 1.0;
};
// Frequencies are in cycles per exemplar pixel: a translation beyond Nyquist moves every
// Gaussian out of the pixel grid's reach.
inline constexpr double kMaxTranslation = 1.0;
// The variance grows by the square: up to 1e3, variances (about 10 after analysis) stay far
// within the model value range (model/value_range.hpp).
inline constexpr double kMaxMagnitude = 1e3;
// The request checked and converted (radians, a band shift); a std::invalid_argument of one
// sentence otherwise, naming each value as `prefix` + its name ("--rotate" for the CLI).
SpectrumEdit spectrum_edit(const EditRequest& request, std::string_view prefix);
// One flag per label: the Gaussians of group `group` ("all" selects every one); a
// std::invalid_argument for another name.
std::vector<bool> select_group(const std::vector<WoldComponent>& labels, std::string_view group,
                               std::string_view prefix);

// The registry row's edit capability (methods/capabilities.hpp), through which `stochtex edit` and
// the studio's editor drive the above: the groups "all" and the Wold components, the fields of
// EditRequest (rotate in degrees, scale, translate FX,FY, magnitude, bandwidth).
extern const EditCapability kEdit;

}  // namespace stochtex::gabor
