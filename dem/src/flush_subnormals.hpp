#pragma once
// Subnormal numbers flushed to zero while a DEM run steps: FTZ and DAZ set in this thread's SSE
// control register for the guard's lifetime, the caller's mode restored after it.
//
// Why: a bed at rest damps its resting particles' velocity components geometrically (contact
// damping, gas drag) down through the subnormal range (below 2.2e-308), where every operation on
// them takes a microcode assist of ~100 cycles on x86. The [GZ] protocol at full stiffness
// (600 particles, 5e6 steps) spent 28 % of its time there (docs/results/deposit-speed.md). A
// speed of 1e-300 m/s is zero to any physics; the same run with and without the flush gave the
// same positions bit for bit and velocities that differ by under 3e-294 m/s. Flushing is
// deterministic, so results stay the same for any thread count: every OpenMP region of the
// engine sets the guard in each of its threads (dem/src/parallel.hpp).
//
// Other architectures keep IEEE subnormals (the guard does nothing there): a run is then as
// before, only slower.
#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace powderbed::dem::detail {

class FlushSubnormals {
 public:
#if defined(__SSE2__)
  FlushSubnormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
  ~FlushSubnormals() { _mm_setcsr(saved_); }
#else
  FlushSubnormals() = default;
#endif
  FlushSubnormals(const FlushSubnormals&) = delete;
  FlushSubnormals& operator=(const FlushSubnormals&) = delete;

 private:
#if defined(__SSE2__)
  // MXCSR bits (Intel SDM vol. 1, 10.2.3): FTZ is bit 15, DAZ bit 6.
  static constexpr unsigned kFlushToZero = 1u << 15;
  static constexpr unsigned kDenormalsAreZero = 1u << 6;
  unsigned saved_;
#endif
};

}  // namespace powderbed::dem::detail
