// Vector twins of core/float_math.hpp's polynomials (the same source, core/float_math.inc) and
// core/hash.hpp's counter-based draws, one value per lane, with the scalar functions' operations in
// their order (no fused multiply-add: the build sets -ffp-contract=off; truncating conversions):
// every lane returns the scalar function's bytes on every SIMD target. Included by a method's
// simd.cpp once per target, after HWY_TARGET_INCLUDE and foreach_target.h (Highway's per-target
// include guard below).

#if defined(STOCHTEX_CORE_SIMD_MATH_HPP_) == defined(HWY_TARGET_TOGGLE)
#ifdef STOCHTEX_CORE_SIMD_MATH_HPP_
#undef STOCHTEX_CORE_SIMD_MATH_HPP_
#else
#define STOCHTEX_CORE_SIMD_MATH_HPP_
#endif

#include <hwy/highway.h>

#include "core/float_math.hpp"
#include "core/hash.hpp"

HWY_BEFORE_NAMESPACE();
namespace stochtex::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// float_math.inc's operations on the vectors of DF and their int32 lanes.
template <class DF>
struct VectorOps {
  using VF = hn::Vec<DF>;
  using DI = hn::RebindToSigned<DF>;
  using VI = hn::Vec<DI>;
  DF df;
  HWY_INLINE VF constant(float c) const { return hn::Set(df, c); }
  HWY_INLINE VF truncate(VF v) const { return hn::ConvertTo(df, hn::ConvertTo(DI(), v)); }
  HWY_INLINE VF abs(VF v) const { return hn::Abs(v); }
  HWY_INLINE VF above(VF a, VF b, VF x, VF y) const { return hn::IfThenElse(hn::Gt(a, b), x, y); }
  HWY_INLINE VF below(VF a, VF b, VF x, VF y) const { return hn::IfThenElse(hn::Lt(a, b), x, y); }
  HWY_INLINE VI to_int(VF v) const { return hn::ConvertTo(DI(), v); }
  HWY_INLINE VF to_float(VI i) const { return hn::ConvertTo(df, i); }
  HWY_INLINE VF power_of_two(VI i) const {
    return hn::BitCast(df, hn::ShiftLeft<23>(hn::Add(i, hn::Set(DI(), 127))));
  }
};

#include "core/float_math.inc"

// cos_turns in every lane.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF CosTurns(DF df, VF t) {
  return cos_turns_of(VectorOps<DF>{df}, t);
}

// exp_float in every lane.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF ExpFloat(DF df, VF x) {
  return exp_float_of(VectorOps<DF>{df}, x);
}

// pcg_hash in every lane.
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE VU PcgHash(DU du, VU v) {
  const VU state = hn::Add(hn::Mul(v, hn::Set(du, 747796405u)), hn::Set(du, 2891336453u));
  const VU shift = hn::Add(hn::ShiftRight<28>(state), hn::Set(du, 4u));
  const VU word = hn::Mul(hn::Xor(state >> shift, state), hn::Set(du, 277803737u));
  return hn::Xor(hn::ShiftRight<22>(word), word);
}

// CounterRng(key).next() at draw number `counter` of each lane.
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE VU CounterDraw(DU du, std::uint32_t key, VU counter) {
  return PcgHash(du, hn::Xor(hn::Set(du, key), PcgHash(du, counter)));
}

// CounterRng::uniform() from a draw in every lane: the top 24 bits, exact as float.
template <class DF, class VU>
HWY_INLINE hn::Vec<DF> UniformFromDraw(DF df, VU draw) {
  const hn::RebindToSigned<DF> di;
  return hn::Mul(hn::ConvertTo(df, hn::BitCast(di, hn::ShiftRight<8>(draw))),
                 hn::Set(df, 1.0f / 16777216.0f));
}

}  // namespace stochtex::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // STOCHTEX_CORE_SIMD_MATH_HPP_
