#pragma once
// The small blade spread of the recoater tests (test_spread.cpp, test_sleep.cpp): 15 um spheres
// of 316L ([GZ]'s) on a lattice supply, a 100 um blade with a 60 um gap at 0.2 m/s over a
// 1.5 x 0.3 mm strip periodic along y, 30 um layers, softened 1e3 times as the scenes are.
#include <cstdint>
#include <random>

#include "beds.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::test {

constexpr double kRadius = 15e-6;
constexpr double kYoungScale = 1e3;  // the scenes' softening (data/scenes/spread-blade.ini)

inline dem::Scene granular_scene(double mu, double mu_r, dem::FrictionModel model) {
  dem::Scene s;  // 316L of [GZ]
  s.material.friction = mu;
  s.material.rolling = mu_r;
  s.friction_model = model;
  s.effects = dem::kGravity | dem::kHertz | dem::kDamping | dem::kFriction | dem::kWalls;
  return s;
}

inline bed::Bed lattice_supply(const bed::Domain& region, std::uint64_t) {
  bed::Bed b;
  b.domain = region;
  const double pitch = 32e-6, r = kRadius;
  for (double z = region.lower[2] + r + 1e-6; z + r <= region.upper[2]; z += pitch)
    for (double y = region.lower[1] + r + 1e-6; y + r <= region.upper[1]; y += pitch)
      for (double x = region.lower[0] + r + 1e-6; x + r <= region.upper[0]; x += pitch)
        b.add(x, y, z, r);
  return b;
}

inline dem::SpreadSettings small_spread() {
  dem::SpreadSettings st;
  st.young_scale = kYoungScale;
  st.tool.thickness = 100e-6;
  st.tool.gap = 60e-6;
  st.tool.speed = 0.2;
  st.tool.start = 0.1e-3;
  st.tool.end = 1.2e-3;
  st.supply_x0 = 0.16e-3;
  st.supply_x1 = 0.4e-3;
  st.supply_height = 0.15e-3;
  st.supply = lattice_supply;
  st.layer_thickness = 30e-6;
  return st;
}

inline bed::Bed strip() {
  bed::Bed b = test::box_bed(1.5e-3, 0.3e-3, 0.6e-3);
  b.domain.periodic = {false, true, false};
  return b;
}

// small_spread's lattice supply with each sphere moved by up to 0.9 um along each axis (the
// lattice leaves 2 um between spheres), drawn from `seed` and the layer: one more seed of the
// same spread (the spread is chaotic, so the jitter gives a different layer).
inline dem::SupplyMaker jittered_supply(std::uint64_t seed) {
  return [seed](const bed::Domain& region, std::uint64_t layer) {
    bed::Bed b = lattice_supply(region, layer);
    std::mt19937_64 draw(seed * 1000003u + layer);
    std::uniform_real_distribution<double> jitter(-0.9e-6, 0.9e-6);
    for (std::size_t i = 0; i < b.n(); ++i) {
      b.x[i] += jitter(draw);
      b.y[i] += jitter(draw);
      b.z[i] += jitter(draw);
    }
    return b;
  };
}

// How many particles of bed a (after the run that returned ra) differ from b's (rb) in x, z,
// v_x, the spin about y or the id: a continued run against the uninterrupted one.
inline std::size_t particles_differing(const bed::Bed& a, const dem::SpreadSummary& ra, const bed::Bed& b,
                                       const dem::SpreadSummary& rb) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < b.n(); ++i) {
    differ += (a.x[i] != b.x[i] || a.z[i] != b.z[i] || a.vx[i] != b.vx[i] || ra.state.wy[i] != rb.state.wy[i] ||
               a.id[i] != b.id[i]) ? 1 : 0;
  }
  return differ;
}

}  // namespace powderbed::test
