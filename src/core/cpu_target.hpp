#pragma once
// Whether the evaluators take their vectorised path (render.hpp's CpuTarget): false when the
// scalar reference is forced with set_cpu_target(CpuTarget::reference).

namespace stochtex {

bool simd_enabled() noexcept;

// Ends a vectorised call (each method's dispatch wrapper in its simd.cpp): on a machine with AVX,
// clears the upper halves of the vector registers (vzeroupper). Left dirty by the AVX2 and
// AVX-512 targets, they slowed the SSE code that follows (the scalar reference, the rest of the
// process) by 2.3x on the development machine (measured: a tiling reference render after a SIMD
// one, 709 against 307 ns per sample).
void end_simd_call() noexcept;

}  // namespace stochtex
