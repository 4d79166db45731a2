#include "core/cpu_target.hpp"

#include <hwy/targets.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <array>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stochtex/render.hpp"

namespace stochtex {
namespace {

// Each CpuTarget but the reference, worst first, with its Highway target bit.
constexpr std::array<std::pair<CpuTarget, std::int64_t>, 4> kHighwayTargets{{
    {CpuTarget::portable, HWY_SCALAR | HWY_EMU128},
    {CpuTarget::sse4, HWY_SSE4},
    {CpuTarget::avx2, HWY_AVX2},
    {CpuTarget::avx512, HWY_AVX3},
}};

std::atomic<bool> reference_forced{false};

// What the CPU offers among the compiled targets, read once before any mock of
// hwy::SetSupportedTargetsForTest (set_cpu_target() installs one).
std::int64_t machine_targets() {
  static const std::int64_t targets = hwy::SupportedTargets() & HWY_TARGETS;
  return targets;
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx"))) void zero_upper() noexcept {
  _mm256_zeroupper();
}
#endif

}  // namespace

void end_simd_call() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  static const bool avx = (machine_targets() & (HWY_AVX2 | HWY_AVX3)) != 0;
  if (avx) zero_upper();
#endif
}

bool simd_enabled() noexcept {
  return !reference_forced.load(std::memory_order_relaxed);
}

std::string_view cpu_target_name(CpuTarget target) {
  switch (target) {
    case CpuTarget::reference:
      return "reference";
    case CpuTarget::portable:
      return "portable";
    case CpuTarget::sse4:
      return "sse4";
    case CpuTarget::avx2:
      return "avx2";
    case CpuTarget::avx512:
      return "avx512";
  }
  return "unknown";
}

std::vector<CpuTarget> available_cpu_targets() {
  std::vector<CpuTarget> targets{CpuTarget::reference};
  for (const auto& [target, bit] : kHighwayTargets)
    if ((machine_targets() & bit) != 0) targets.push_back(target);
  return targets;
}

CpuTarget cpu_target() {
  if (!simd_enabled()) return CpuTarget::reference;
  // Highway's best target is the lowest set bit of the supported ones (a mock included).
  const std::int64_t supported = hwy::SupportedTargets() & HWY_TARGETS;
  const std::int64_t best = supported & -supported;
  for (const auto& [target, bit] : kHighwayTargets)
    if ((bit & best) != 0) return target;
  return CpuTarget::reference;
}

CpuTarget available_cpu_target(std::string_view name) {
  const std::vector<CpuTarget> targets = available_cpu_targets();
  std::string names;
  for (const CpuTarget target : targets) {
    if (cpu_target_name(target) == name) return target;
    if (!names.empty()) names += ", ";
    names += cpu_target_name(target);
  }
  throw std::invalid_argument("this machine cannot run '" + std::string(name) +
                              "'; its CPU targets are " + names);
}

void set_cpu_target(CpuTarget target) {
  std::int64_t bit = 0;
  for (const auto& [candidate, candidate_bit] : kHighwayTargets)
    if (candidate == target) bit = candidate_bit;
  if (target != CpuTarget::reference && (machine_targets() & bit) == 0)
    throw std::invalid_argument("set_cpu_target: this machine or build cannot run the " +
                                std::string(cpu_target_name(target)) +
                                " target; available_cpu_targets() lists those it can");
  const bool best = target == available_cpu_targets().back();
  // 0 removes the mock: Highway picks the machine's best target again.
  hwy::SetSupportedTargetsForTest(best || target == CpuTarget::reference ? 0 : bit);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
  reference_forced.store(target == CpuTarget::reference, std::memory_order_relaxed);
}

}  // namespace stochtex
