#pragma once
// Fusion after a scan (docs/sinter.md "Fusion"): what melted becomes solid. A particle whose
// peak temperature reached T_m + (f − 1/2) ΔT had a melt fraction f at some moment (the apparent
// heat capacity spreads the latent heat evenly over the window ΔT around T_m): it leaves the
// powder and its volume joins the solid, spread evenly over the top-face columns under its
// projected disc (top_footprint), which raises the solid's top there by V w_c / (dx dy) — when
// its melt met molten solid (bonding.hpp); one that melted on solid that did not melt froze as
// a ball and stays in the bed as a sphere (balled).
// The default f = 1/2 fuses what reached T_m, the isotherm the melt pool is measured on, so the
// fused stripe is the measured melt (the window is the model's smoothing of melting at T_m, not
// a mushy zone it resolves); f = 1 fuses only what was wholly liquid. A particle below the
// threshold stays powder (sintered, not fused); a vaporised one left as vapour. Substrate
// nodes that melted are solid already and stay so.
//
// Conserved: mass. The solid above the plate's top face is ρ0 Σ_c dx dy (H_c − z_top) (every
// column owns dx dy, as the deposit is counted), and a fused particle's mass is ρ0 V: the
// weights sum to 1, so powder + solid + vapour after = powder + solid before, to round-off.
// ρ0 = ρ(T0), the density the solver gives particle masses.
#include <cstdint>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/bead.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

// What became of a particle of the scanned bed.
enum FusionState : std::uint8_t { kPowder = 0, kFused = 1, kVapour = 2, kBalled = 3 };
// Whether a particle in that state is still in the bed for the next layer (powder and balls).
inline bool stays_in_bed(std::uint8_t state) { return state == kPowder || state == kBalled; }

struct Fusion {
  bed::Bed powder;                    // the particles left in the bed: powder and balls (ids kept)
  TopHeight top;                      // the solid's new top, per top-face column i + nx j, m
  // The top before the capture (the scan's melt and its fused particles, levelled): what lies
  // between it and `top` is captured powder that never melted (part_porosity.hpp).
  TopHeight melt_top;
  std::vector<std::uint8_t> state;    // per particle of the scanned bed: a FusionState
  std::size_t fused = 0, vaporised = 0;
  std::size_t balled = 0;             // melted, met no molten solid: frozen balls left in the bed
  std::size_t captured = 0;           // of the fused: powder the grown solid swallowed (capture)
  double threshold = 0;               // K: T_m + (f - 1/2) ΔT
  double powder_mass_before = 0, powder_mass_after = 0;  // kg
  double solid_mass_before = 0, solid_mass_after = 0;    // kg, above the plate's top face
  double vaporised_mass = 0;                             // kg
  // kg: particles that merged into the pool during the scan (wetting): in the solid already, so
  // in solid_mass_before and not in powder_mass_before.
  double merged_mass = 0;
  Bead bead;  // how high `top` stands over the plate on the track's sections (bead.hpp)
  // Of the powder's mass the scan met (merged particles included), the share that joined the
  // solid: vapour and balls did not.
  double fused_fraction() const;
  // (powder + solid after + vapour) - (powder + solid before), over the total: round-off.
  double mass_error() const;
};

// Fuses the state `sinter` has reached on `bed` (the bed it was built on); melt_fraction f in
// (0, 1] (InputError naming fuse.melt-fraction otherwise).
//
// capture c > 0 (build: the next layer is spread on what stays): a powder particle that the
// grown solid overlaps by more than c r (bed::surface_overlap, on the surface the spread's
// floor touches) joins it too, its volume raised over its footprint as a fused one's (and levelled over L as the
// scan's deposit, below), until none is left so deep. A fused particle's volume spreads under its unfused neighbours as well; left where it
// is, such a neighbour would start the next spread deep inside a wall, and a softened contact
// fires it off at metres per second. Physically the melt pool draws in powder it touches (the
// denudation of the zone beside a track). c = 0 captures nothing (sinter --fuse).
//
// level L > 0 (build): the scan's deposit (the rise of the top over this fusion) is spread by a
// Gaussian of standard deviation L over the columns, each column's rise shared among the columns
// within 3 L by weights that sum to 1, so no volume is lost at the plate's edges. A stand-in for
// the capillary levelling of the melt before it freezes: its capillary time sqrt(rho l^3 /
// sigma) is ~25 us over l = 50 um (316L, sigma ~1.8 N/m), against the ~1 ms the track takes to
// solidify, so the melt is level across the pool when it freezes; without it the solid keeps a
// spike over each fused particle, between which a spread sphere finds pits with two walls. The
// levelling comes before the capture. L = 0 keeps the deposit where it fell (sinter --fuse).
//
// On a bed periodic along x or y whose grid spans the period, the solid's two edge rows become
// one seam (their mean, the volume kept) before the capture: the grid is not periodic, so a track
// crossing the seam raises one edge only, and the powder by the other edge would be left inside
// the step once the next spread joins them.
Fusion fuse(const bed::Bed& bed, const Sinter& sinter, double melt_fraction = 0.5,
            double capture = 0, double level = 0);

// Solid mass above the plate's top face of a top height map, kg.
double solid_mass(const SubstrateGeometry& g, const TopHeight& top, double density);

}  // namespace powderbed::thermal
