#pragma once
// The contact law over a batch of contacts in contiguous arrays: the pair and box-face passes of
// a model whose contacts neither turn the particles nor keep a history (the drop's,
// docs/physics.md §4), which the engine (engine.hpp) runs instead of a call per contact.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "normal_law.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/sliding_friction.hpp"

namespace powderbed::dem::detail {

// The pair forces in three passes over a block of particles, so that the costly part runs
// without branches: (1) one flat loop over the block's list entries that writes each entry's
// index at slot m and advances m only when the pair touches (branch-free compaction: ~3 of 4
// entries of a settled bed are not in contact, a coin toss for a branch predictor, and a loop
// per particle mispredicts its varying trip count), then gathers the m contacts' separations,
// velocity differences and constants into contiguous arrays; (2) the contact law over them, a
// straight loop that the compiler vectorises (square roots and divisions two at a time with
// SSE2); (3) the sums (serial or gathered, see compute_forces).
struct ContactBuffer {
  std::vector<std::uint32_t> i, j, k;
  std::vector<double> dx, dy, dz, reach, elastic, damping, dvx, dvy, dvz, fx, fy, fz;
  std::size_t count = 0;

  void reserve(std::size_t entries) {
    const std::size_t size = entries + 1;  // pass 1 writes slot m even for the last entry
    if (i.size() >= size) return;
    for (auto* v : {&i, &j, &k}) v->resize(size);
    for (auto* v : {&dx, &dy, &dz, &reach, &elastic, &damping, &dvx, &dvy, &dvz, &fx, &fy, &fz}) {
      v->resize(size);
    }
  }
};

// Pass 2: the force on the lower index i of each contact (j gets -F), docs/physics.md §4: the scene's law
// (Hertz or linear) with the zeta damping along n = (x_j - x_i) / d, sliding friction on the tangential velocity. A plain
// function of restrict-qualified arrays, which the compiler vectorises (it does not through the
// buffer's members).
template <unsigned E, class Law>
void contact_kernel(std::size_t m, SlidingFrictionParams friction, const double* __restrict dx,
                    const double* __restrict dy, const double* __restrict dz,
                    const double* __restrict reach, const double* __restrict elastic,
                    const double* __restrict damping, const double* __restrict dvx,
                    const double* __restrict dvy, const double* __restrict dvz,
                    double* __restrict fx, double* __restrict fy, double* __restrict fz) {
  for (std::size_t c = 0; c < m; ++c) {
    const double d = std::sqrt(dx[c] * dx[c] + dy[c] * dy[c] + dz[c] * dz[c]);
    const double delta = reach[c] - d;
    const double inv_d = 1.0 / d;
    const double nx = dx[c] * inv_d, ny = dy[c] * inv_d, nz = dz[c] * inv_d;  // from i to j
    [[maybe_unused]] double rate = 0;  // approach rate, (v_i - v_j) . n
    if constexpr ((E & (kDamping | kFriction)) != 0) rate = dvx[c] * nx + dvy[c] * ny + dvz[c] * nz;
    double fn;
    if constexpr ((E & kDamping) != 0) {
      fn = Law::damped(elastic[c], damping[c], delta, rate);
    } else {
      fn = Law::elastic(elastic[c], delta);
    }
    double f[3] = {-fn * nx, -fn * ny, -fn * nz};
    if constexpr ((E & kFriction) != 0) {
      double ft[3];
      sliding_friction_force(friction, Law::normal_magnitude(fn), dvx[c] - rate * nx, dvy[c] - rate * ny,
                             dvz[c] - rate * nz, ft);
      f[0] += ft[0];
      f[1] += ft[1];
      f[2] += ft[2];
    }
    fx[c] = f[0];
    fy[c] = f[1];
    fz[c] = f[2];
  }
}

// Particles per pass of the three: their contacts' buffer (~100 bytes a contact, up to ~6
// contacts a particle in a dense bed) stays in the L2 cache between the passes.
constexpr std::size_t kContactBlock = 256;

}  // namespace powderbed::dem::detail
