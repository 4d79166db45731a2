// Vector twins of core/float_math.hpp's polynomials and core/hash.hpp's counter-based draws, one
// value per lane, with the scalar functions' operations in their order (no fused multiply-add: the
// build sets -ffp-contract=off; truncating conversions): every lane returns the scalar function's
// bytes on every SIMD target. Included by a method's simd.cpp once per target, after
// HWY_TARGET_INCLUDE and foreach_target.h (Highway's per-target include guard below).

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

// cos_turns in every lane.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF CosTurns(DF df, VF t) {
  const hn::RebindToSigned<DF> di;
  t = hn::Sub(t, hn::ConvertTo(df, hn::ConvertTo(di, t)));
  t = hn::Abs(t);
  t = hn::IfThenElse(hn::Gt(t, hn::Set(df, 0.5f)), hn::Sub(hn::Set(df, 1.0f), t), t);
  const auto upper = hn::Gt(t, hn::Set(df, 0.25f));
  const VF sign = hn::IfThenElse(upper, hn::Set(df, -1.0f), hn::Set(df, 1.0f));
  t = hn::IfThenElse(upper, hn::Sub(hn::Set(df, 0.5f), t), t);
  const VF x = hn::Mul(hn::Set(df, kTwoPi), t);
  const VF x2 = hn::Mul(x, x);
  VF p = hn::Mul(x2, hn::Set(df, 1.0f / 479001600.0f));
  p = hn::Mul(x2, hn::Add(hn::Set(df, -1.0f / 3628800.0f), p));
  p = hn::Mul(x2, hn::Add(hn::Set(df, 1.0f / 40320.0f), p));
  p = hn::Mul(x2, hn::Add(hn::Set(df, -1.0f / 720.0f), p));
  p = hn::Mul(x2, hn::Add(hn::Set(df, 1.0f / 24.0f), p));
  p = hn::Mul(x2, hn::Add(hn::Set(df, -1.0f / 2.0f), p));
  p = hn::Add(hn::Set(df, 1.0f), p);
  return hn::Mul(sign, p);
}

// exp_float in every lane.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF ExpFloat(DF df, VF x) {
  const hn::RebindToSigned<DF> di;
  const VF floor = hn::Set(df, kExpFloor);
  const VF clamped = hn::IfThenElse(
      hn::Lt(x, floor), floor,
      hn::IfThenElse(hn::Gt(x, hn::Set(df, kExpCeiling)), hn::Set(df, kExpCeiling), x));
  const VF t = hn::Mul(clamped, hn::Set(df, 1.44269504088896341f));
  const VF half = hn::IfThenElse(hn::Lt(t, hn::Zero(df)), hn::Set(df, -0.5f), hn::Set(df, 0.5f));
  const auto k = hn::ConvertTo(di, hn::Add(t, half));
  const VF kf = hn::ConvertTo(df, k);
  const VF r = hn::Sub(hn::Sub(clamped, hn::Mul(kf, hn::Set(df, 0.693359375f))),
                       hn::Mul(kf, hn::Set(df, -2.12194440e-4f)));
  const VF r2 = hn::Mul(r, r);
  VF p = hn::Add(hn::Mul(hn::Set(df, 1.9875691500e-4f), r), hn::Set(df, 1.3981999507e-3f));
  p = hn::Add(hn::Mul(p, r), hn::Set(df, 8.3334519073e-3f));
  p = hn::Add(hn::Mul(p, r), hn::Set(df, 4.1665795894e-2f));
  p = hn::Add(hn::Mul(p, r), hn::Set(df, 1.6666665459e-1f));
  p = hn::Add(hn::Mul(p, r), hn::Set(df, 5.0000001201e-1f));
  p = hn::Add(hn::Add(hn::Mul(p, r2), r), hn::Set(df, 1.0f));
  const VF scale = hn::BitCast(df, hn::ShiftLeft<23>(hn::Add(k, hn::Set(di, 127))));
  return hn::IfThenZeroElse(hn::Lt(x, floor), hn::Mul(p, scale));
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
