#pragma once
// Whether the evaluators take their vectorised path (render.hpp's CpuTarget): false when the
// scalar reference is forced with set_cpu_target(CpuTarget::reference).

namespace stochtex {

bool simd_enabled() noexcept;

}  // namespace stochtex
