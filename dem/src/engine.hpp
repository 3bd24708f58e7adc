#pragma once
// The DEM engine (issue 33: one engine, drivers on top): the particles and their rotation, the
// neighbour list with contact history, the contact model composed once per run
// (contact_model.hpp; batched through contact_kernel.hpp when it neither turns the particles
// nor keeps a history), the walls (the box's faces, the floor of earlier layers, the moving
// tool) with their histories, and the velocity Verlet step. The spreading driver (spread.cpp:
// supply, tool, layers, restart) and the drop's (drop_on_engine.cpp) run on it.
// Over 600 lines because it is one class whose parts share its arrays; the walls and the floor
// are the parts to move out as boundary objects once the drop solver's (solver.cpp) lid and
// insertion are drivers here.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <utility>
#include <vector>

#include "box.hpp"
#include "contact_kernel.hpp"
#include "contact_model.hpp"
#include "lane_tests.hpp"
#include "neighbour_list.hpp"
#include "parallel.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/height_map.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/surface_contacts.hpp"
#include "powderbed/dem/contact_moduli.hpp"
#include "powderbed/dem/fines_scaling.hpp"
#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/rolling_resistance.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/stokes_drag.hpp"
#include "powderbed/dem/time_step.hpp"

namespace powderbed::dem::detail {


inline double largest_radius(const bed::Bed& b) {
  double r_max = 0;
  for (const double r : b.radius) r_max = std::max(r_max, r);
  return r_max;
}

// A pair's force on its owner and the torques on both, stored per list entry by the parallel
// pair loop (Engine::parallel_pair_forces).
constexpr std::size_t kPairLoad = 9;

// Hot list entries per batch of the batched pair pass (Engine::batched_pair_forces): its
// buffer (~100 bytes a contact) stays in the L2 cache between the batch's passes.
constexpr std::size_t kBatchEntries = 1024;

// The walls a particle may touch, each with its own contact history.
enum WallSlot { kPlate, kTool, kXLow, kXHigh, kYLow, kYHigh, kTop, kWallSlots };

// The box's faces in the order a particle meets them: the plate (z low), the top, x low, x high,
// y low, y high (Engine::near_face).
constexpr std::size_t kFaces = 6;

// The floor's contacts (SpreadSettings::floor; bed/surface_contacts.hpp) follow the walls' slots
// in a particle's row of wall_history: per slot the facet it touches plus one (0: free; a
// triangle index is exact in a double), then its history. The flat plate uses kPlate's slot.
constexpr std::size_t kFloorSlots = bed::kMaxSurfaceContacts;
constexpr std::size_t kFloorSlotValues = 1 + kContactHistory;
constexpr std::size_t kFloorValuesAt = kWallSlots * kContactHistory;
constexpr std::size_t kWallValues = kFloorValuesAt + kFloorSlots * kFloorSlotValues;
static_assert(kWallValues == kWallHistoryValues, "spread.hpp's count of a particle's wall values");

// The contacts of the last force evaluation, in pair order (owner index ascending): what a
// neighbour-list build, a new layer or a restart carries over.
struct ActiveContacts {
  std::vector<std::uint32_t> i, j;
  std::vector<double> h;  // kContactHistory per contact
};

// The particles of `b` in the order of the cells of side `cell` they lie in (x fastest, then y,
// then z; ties by index), the frozen ones (`frozen` set) after all the others: particles that
// touch lie close together in memory, so the contact loop finds its partners in the nearest
// caches, and the moving ones are the first indices (Engine::moving).
inline std::vector<std::size_t> spatial_order(const bed::Bed& b, double cell, const std::vector<std::uint8_t>& frozen) {
  if (b.n() == 0) return {};
  const auto at = [&](int a, double v) {
    return static_cast<std::uint64_t>(std::max(0.0, std::floor((v - b.domain.lower[a]) / cell)));
  };
  const std::uint64_t nx = at(0, b.domain.upper[0]) + 1, ny = at(1, b.domain.upper[1]) + 1;
  std::vector<std::pair<std::uint8_t, std::uint64_t>> key(b.n());
  std::vector<std::size_t> order(b.n());
  for (std::size_t i = 0; i < b.n(); ++i) {
    key[i] = {frozen[i], (at(2, b.z[i]) * ny + at(1, b.y[i])) * nx + at(0, b.x[i])};
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return key[p] < key[q]; });
  return order;
}

// The spread's Verlet skin when SpreadSettings::skin is 0: 0.5 r_max, narrowed where a periodic
// axis would otherwise hold fewer than 3 cells of 2 r_max + skin (NeighbourList::configure), down
// to the drop's 0.2 r_max. The pair loop scans the pruned list (Engine::prune), so a wide skin costs
// only at builds and prunes, and makes builds rarer: on the blade scene 0.5 r_max spread the
// layer 6 % faster than 0.3 and as fast as 0.8 (docs/deposit-spread.md "Speed").
inline double default_skin(const Box& box, double r_max) {
  double skin = 0.5 * r_max;
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[a]) skin = std::min(skin, box.length[a] / 3.0 * (1.0 - 1e-9) - 2.0 * r_max);
  }
  return std::max(skin, 0.2 * r_max);
}

// The prune margin (NeighbourList::prune) as a fraction of the largest radius, at most half the
// skin: on the blade scene 0.05 r_max spread the layer 10 % faster than 0.03 (smaller: fewer hot
// entries but more prunes). Results do not depend on it.
constexpr double kPruneMargin = 0.05;

// The constants of kick_drift: the kick h, the step dt, gravity, and the wrap of x and y (z is
// never periodic: check_settings).
struct DriftConstants {
  double h, dt, g[3];
  BranchFreeWrap wrap;
};

// Engine::start_step's first pass over particles [0, count): v += h F / m, x += dt v (wrapped),
// F = m_weight g - c v (gravity and Stokes drag, stokes_drag.hpp), T = 0. A free function because GCC 12
// honours __restrict on parameters only: without it the loop over fifteen arrays needs more
// aliasing checks than GCC makes and runs one particle at a time. Non-zero when a velocity is
// not finite.
inline std::uint64_t kick_drift(std::size_t count, const DriftConstants k, double* __restrict x, double* __restrict y,
                         double* __restrict z, double* __restrict vx, double* __restrict vy, double* __restrict vz,
                         double* __restrict ax, double* __restrict ay, double* __restrict az, double* __restrict mx,
                         double* __restrict my, double* __restrict mz, const double* __restrict inv,
                         const double* __restrict weight, const double* __restrict c) {
  std::uint64_t bad = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const double vxi = vx[i] + k.h * ax[i] * inv[i], vyi = vy[i] + k.h * ay[i] * inv[i],
                 vzi = vz[i] + k.h * az[i] * inv[i];
    vx[i] = vxi;
    vy[i] = vyi;
    vz[i] = vzi;
    x[i] = k.wrap(0, x[i] + k.dt * vxi);
    y[i] = k.wrap(1, y[i] + k.dt * vyi);
    z[i] += k.dt * vzi;
    bad |= non_finite_bit(std::abs(vxi) + std::abs(vyi) + std::abs(vzi));
    ax[i] = weight[i] * k.g[0] - c[i] * vxi;
    ay[i] = weight[i] * k.g[1] - c[i] * vyi;
    az[i] = weight[i] * k.g[2] - c[i] * vzi;
    mx[i] = my[i] = mz[i] = 0;
  }
  return bad;
}

// The classical Runge–Kutta step's state over particles [0, n): the state at the step's start
// and the weighted sums of the stage derivatives (Engine::step_rk4).
struct Rk4State {
  std::vector<double> x0, y0, z0, u0, v0, w0, sx, sy, sz, su, sv, sw;

  void start(const bed::Bed& b, std::size_t n) {
    for (auto* v : {&x0, &y0, &z0, &u0, &v0, &w0, &sx, &sy, &sz, &su, &sv, &sw}) v->resize(n);
    std::copy_n(b.x.begin(), n, x0.begin());
    std::copy_n(b.y.begin(), n, y0.begin());
    std::copy_n(b.z.begin(), n, z0.begin());
    std::copy_n(b.vx.begin(), n, u0.begin());
    std::copy_n(b.vy.begin(), n, v0.begin());
    std::copy_n(b.vz.begin(), n, w0.begin());
  }

  // Stage k's derivative (the bed's velocities, F/m) into the sums, and the bed put at the next
  // stage's state (half a step, half a step, a whole step from the start).
  void stage(int k, double dt, bed::Bed& b, const double* fx, const double* fy, const double* fz,
             const double* inv_mass, std::size_t n) {
    const double weight = (k == 0 || k == 3) ? 1.0 : 2.0;
    const double next = k < 2 ? 0.5 * dt : dt;
    for (std::size_t i = 0; i < n; ++i) {
      const double d[6] = {b.vx[i], b.vy[i], b.vz[i], fx[i] * inv_mass[i], fy[i] * inv_mass[i],
                           fz[i] * inv_mass[i]};
      double* sum[6] = {&sx[i], &sy[i], &sz[i], &su[i], &sv[i], &sw[i]};
      for (int q = 0; q < 6; ++q) *sum[q] = k == 0 ? d[q] : *sum[q] + weight * d[q];
      if (k == 3) continue;
      b.x[i] = x0[i] + next * d[0];
      b.y[i] = y0[i] + next * d[1];
      b.z[i] = z0[i] + next * d[2];
      b.vx[i] = u0[i] + next * d[3];
      b.vy[i] = v0[i] + next * d[4];
      b.vz[i] = w0[i] + next * d[5];
    }
  }

  // The step's end: the start plus dt/6 of the weighted sums, wrapped on periodic axes; false
  // when a velocity is not finite.
  bool finish(double dt, const BranchFreeWrap& wrap, bed::Bed& b, std::size_t n) const {
    const double sixth = dt / 6.0;
    std::uint64_t bad = 0;
    for (std::size_t i = 0; i < n; ++i) {
      b.x[i] = wrap(0, x0[i] + sixth * sx[i]);
      b.y[i] = wrap(1, y0[i] + sixth * sy[i]);
      b.z[i] = z0[i] + sixth * sz[i];
      b.vx[i] = u0[i] + sixth * su[i];
      b.vy[i] = v0[i] + sixth * sv[i];
      b.vz[i] = w0[i] + sixth * sw[i];
      bad |= non_finite_bit(std::abs(b.vx[i]) + std::abs(b.vy[i]) + std::abs(b.vz[i]));
    }
    return bad == 0;
  }
};

// The entries of an index-ascending list of particles that lie in [p0, p1).
inline std::pair<const std::uint32_t*, const std::uint32_t*> candidates(const std::vector<std::uint32_t>& list, std::size_t p0,
                                                                 std::size_t p1) {
  const std::uint32_t* first = std::lower_bound(list.data(), list.data() + list.size(), p0);
  return {first, std::lower_bound(first, list.data() + list.size(), p1)};
}

struct Engine {
  Engine(bed::Bed& b, const Scene& sc, const SpreadSettings& st) : bed(b), scene(sc), settings(st) {}
  bed::Bed& bed;
  const Scene& scene;
  const SpreadSettings& settings;
  ContactModel model;
  Box box;
  double dt = 0;
  double g[3] = {0, 0, 0};
  ContactModuli moduli;  // the scene's, softened (contact_moduli.hpp)
  // `weight` is the mass gravity acts on and the kinetic energy counts, `mass` the inertial one:
  // they differ for the fines under mass scaling (fines_scaling.hpp, docs/physics.md §4
  // "Fines"), which also scales the rotational inertia.
  std::vector<double> weight, mass, inv_mass, inv_inertia, drag, wx, wy, wz, fx, fy, fz, tx, ty, tz;
  // Per particle E under fines stiffness scaling, from which its contacts take E* and G*; empty
  // without it (every contact has the scene's moduli).
  std::vector<double> young;
  // Particles [0, moving) are integrated; the others are frozen (SpreadSettings::freeze_depth):
  // they keep their places, act on the moving ones' contacts as fixed spheres, and their own
  // force arrays collect those contacts' reactions, which nothing reads.
  std::size_t moving = 0;
  // The contacts between two particles that are not integrated, kept out of the list (it holds
  // no pair of two of them) with their history: sleeping powder that wakes (sleep.hpp) takes its
  // contacts back, and a restart writes them (active()). In owner order.
  ActiveContacts dormant;
  // Per particle, steps in a row at rest (sleep.hpp); empty when the scene does not sleep.
  std::vector<std::uint32_t> quiet;
  // The frozen particles whose tops reach above the tool's lowest point (found at each layer's
  // start: frozen particles do not move), and how many times, step by step, the tool overlapped
  // one of them this layer. The tool's contacts are the moving particles' only, so it would
  // pass through such a particle without a force: sound freezing counts none (LayerSummary).
  std::vector<std::uint32_t> frozen_in_reach;
  std::uint64_t frozen_tool_contacts = 0;
  std::vector<double> wall_history;   // kWallValues per particle
  // Per particle, bit `slot` set when that wall's history may be non-zero (kPlate's: or a floor
  // slot is taken): a wall out of reach (most walls, most steps) then costs a test, not the
  // write of its six zeros.
  std::vector<std::uint8_t> wall_touch;
  std::vector<ContactConstants> wall;        // per particle
  std::vector<std::uint32_t> near_walls, near_tool;  // find_wall_candidates, at each prune
  // The box's top as the lid (lid_phase.hpp): its velocity (m/s, in its contacts' approach
  // rates), where find_wall_candidates last saw it, and how far it may move before they must be
  // found again (their test of the top is widened by it). 0 without a lid.
  double top_velocity = 0, top_at_search = 0, top_slack = 0;
  // With a model that batches, per face instead of near_walls (find_wall_candidates).
  std::array<std::vector<std::uint32_t>, kFaces> near_face;
  NeighbourList list;
  double prune_margin = 0;            // NeighbourList::prune's, m (Spreader sets it with the skin)
  std::vector<ContactConstants> pair;        // per list entry, made when it comes into contact
  std::vector<double> pair_reach;     // per list entry: r_i + r_j (apart from `pair`: every
                                      // entry's is read every step, the rest only in contact)
  std::vector<double> pair_history;   // kContactHistory per list entry
  std::vector<std::uint8_t> touching; // per list entry: in contact at the last evaluation
  // Threads of the particle and pair loops (SpreadSettings::threads, fixed at each layer's list
  // build): with more than one the list carries the incident pairs, and pair_load
  // (kPairLoad per entry) holds each touching pair's force and torques for the gather.
  int threads = 1;
  std::vector<double> pair_load;
  Rk4State rk4;  // step_rk4's arrays (empty with Verlet)
  // Per thread, the batch of a model that batches (ContactModel::batch; contact_kernel.hpp).
  std::vector<ContactBuffer> buffers = std::vector<ContactBuffer>(1);
  bed::HeightMap floor;               // the solid under the powder (empty: the flat plate)
  // The floor's highest and lowest node within reach of a sphere's footprint around each node
  // (floor_reach: the largest radius they were made for; the footprint also takes in the prune
  // margin): bounds that let a sphere high above the solid, or over a flat stretch of it, skip
  // the sampled contact, and one far above it be no wall candidate.
  bed::HeightMap floor_high, floor_low;
  double floor_reach = -1;
  // Per wall candidate i, the floor's triangles within its radius plus the margin at the last
  // prune (bed::triangles_near): floor_near[floor_first[i], + floor_count[i]), and where its
  // centre was then (to follow a wrap across a periodic seam). Until the next prune it moves
  // less than the margin, so no other triangle can come within its radius; the search of the
  // whole surface each step cost ~30 % of a build's second layer (perf, 2026-12-07).
  std::vector<bed::TriangleImage> floor_near;
  std::vector<std::uint32_t> floor_first, floor_count;
  std::vector<double> floor_seen_x, floor_seen_y;

  // The floor's highest point under a sphere of radius up to floor_reach centred over (x, y):
  // floor_high's bound, +inf until bound_floor has made it (every particle then a candidate).
  double floor_bound(double x, double y) const {
    return floor_high.empty() ? std::numeric_limits<double>::infinity() : floor_high.at(floor.cell(x, y));
  }

  void bound_floor() {
    const double r_max = largest_radius(bed);
    if (floor.empty() || r_max <= floor_reach) return;
    floor_reach = r_max;
    floor_high = floor_low = floor;
    // Beyond the radius, the prune margin: a wall candidate moves up to half of it between the
    // prunes that test it against floor_high (find_wall_candidates).
    const double footprint = r_max * (1 + kPruneMargin);
    const auto reach_x = static_cast<std::ptrdiff_t>(std::ceil(footprint / floor.dx)) + 1;
    const auto reach_y = static_cast<std::ptrdiff_t>(std::ceil(footprint / floor.dy)) + 1;
    const auto nx = static_cast<std::ptrdiff_t>(floor.nx), ny = static_cast<std::ptrdiff_t>(floor.ny);
    // Nodes k - reach .. k + reach along one axis: wrapped on a periodic one, else cut at its ends.
    const auto span = [](std::ptrdiff_t k, std::ptrdiff_t reach, std::ptrdiff_t n, bool periodic) {
      return periodic ? std::array{k - reach, k + reach}
                      : std::array{std::max<std::ptrdiff_t>(0, k - reach), std::min(n - 1, k + reach)};
    };
    for (std::ptrdiff_t j = 0; j < ny; ++j)
      for (std::ptrdiff_t i = 0; i < nx; ++i) {
        const auto at = [&](std::ptrdiff_t a, std::ptrdiff_t b) {
          return floor.node(floor.periodic_x ? bed::HeightMap::wrap_index(a, floor.nx) : static_cast<std::size_t>(a),
                            floor.periodic_y ? bed::HeightMap::wrap_index(b, floor.ny) : static_cast<std::size_t>(b));
        };
        double hi = at(i, j), lo = hi;
        const auto [b0, b1] = span(j, reach_y, ny, floor.periodic_y);
        const auto [a0, a1] = span(i, reach_x, nx, floor.periodic_x);
        for (std::ptrdiff_t b = b0; b <= b1; ++b)
          for (std::ptrdiff_t a = a0; a <= a1; ++a) {
            hi = std::max(hi, at(a, b));
            lo = std::min(lo, at(a, b));
          }
        floor_high.z[static_cast<std::size_t>(i + nx * j)] = hi;
        floor_low.z[static_cast<std::size_t>(i + nx * j)] = lo;
      }
  }
  std::uint64_t rebuilds = 0;
  // The tool.
  bool tool_on = false;
  bool synced = true;  // step(): no second half kick pending
  ToolProfile profile;
  double tool_x = 0, tool_v = 0;
  double tool_force[3] = {0, 0, 0};

  // The contact model, the (softened) moduli, gravity, zero velocities where the bed has none,
  // and the per-particle arrays.
  void set_up() {
    model = choose_contact_model(scene, settings.rotation);
    moduli = contact_moduli(scene, settings.young_scale);
    const double gravity = scene.has(kGravity) ? scene.gravity : 0.0;
    g[0] = gravity * std::sin(settings.gravity_tilt);
    g[2] = -gravity * std::cos(settings.gravity_tilt);
    if (!bed.has_velocity()) {
      bed.vx.assign(bed.n(), 0.0);
      bed.vy.assign(bed.n(), 0.0);
      bed.vz.assign(bed.n(), 0.0);
    }
    grow();
  }

  // The user's step (checked against the bound) or the recommended one.
  void set_time_step(const TimeStepBound& bound) {
    if (settings.dt > 0) {
      if (settings.dt > bound.stable && !settings.unsafe_dt) {
        throw InputError(fmt::format(
            "--dt: {:g} s is above the stable bound {:g} s (accepted: dt <= {:g} s, or add "
            "--unsafe-dt)",
            settings.dt, bound.stable, bound.stable));
      }
      dt = settings.dt;
    } else if (std::isfinite(bound.recommended)) {
      dt = bound.recommended;
    } else {
      throw InputError("--dt: no effect bounds the time step (hertz, walls and drag are off; "
                       "accepted: give --dt explicitly)");
    }
    model.coefficients.dt = dt;
  }

  // The neighbour list for the bed as it is now, with the carried contacts' history: the skin
  // (SpreadSettings::skin or default_skin), the prune margin and the threads for its particles.
  void rebuild(const ActiveContacts& carried) {
    const double r_max = largest_radius(bed);
    const double skin = settings.skin > 0 ? settings.skin : default_skin(box, r_max);
    list.configure(box, r_max, skin, bed.n());
    prune_margin = std::min(kPruneMargin * r_max, 0.5 * skin);
    threads = bed.n() < settings.parallel_min_particles ? 1
              : settings.threads > 0                    ? settings.threads
                                                        : omp_get_max_threads();
    rebuild_with(carried);
  }

  std::size_t n() const { return bed.n(); }
  ParticleView view() const { return {bed.x.data(), bed.y.data(), bed.z.data(), bed.radius.data(), n()}; }

  // Particle i against a wall: R* = r, m* = m, I_r = 7/5 m r^2 (rolling_resistance.hpp), and the
  // wall's E* and G* with the scene's E or, for stiffness-scaled fines, the particle's own.
  ContactPartners wall_partners(std::size_t i) const {
    const double r = bed.radius[i];
    ContactPartners p{moduli.wall, moduli.wall_shear, scene.stiffness, r, mass[i], 1.4 * mass[i] * r * r};
    if (!young.empty()) {
      const double nu = scene.material.poisson, wall_nu = scene.wall.poisson;
      p.e_star = effective_modulus(young[i], nu, moduli.wall_young, wall_nu);
      p.g_star = effective_shear_modulus(young[i], nu, moduli.wall_young, wall_nu);
    }
    return p;
  }

  // Per-particle arrays for particles appended since the last call (masses, zero rotation and
  // wall history, wall constants).
  void grow() {
    const std::size_t old = mass.size(), count = n();
    for (auto* v : {&weight, &mass, &inv_mass, &inv_inertia, &drag, &fx, &fy, &fz, &tx, &ty, &tz}) v->resize(count);
    if (scene.fines.scaling == FinesScaling::stiffness) young.resize(count);
    for (auto* v : {&wx, &wy, &wz}) v->resize(count, 0.0);
    wall_history.resize(count * kWallValues, 0.0);
    wall_touch.resize(count, 0);
    wall.resize(count);
    if (settings.sleep.on) quiet.assign(count, 0);  // every particle moves now
    for (std::size_t i = old; i < count; ++i) {
      const double r = bed.radius[i];
      weight[i] = bed::sphere_volume(r) * scene.material.density;
      mass[i] = weight[i] * fines_mass_factor(scene.fines, r);
      inv_mass[i] = 1.0 / mass[i];
      inv_inertia[i] = 1.0 / (0.4 * mass[i] * r * r);  // solid sphere, 2/5 m r^2
      drag[i] = scene.has(kDrag) ? stokes_drag_coefficient({scene.fluid_viscosity}, r) : 0.0;
      if (!young.empty()) young[i] = moduli.young * fines_stiffness_factor(scene.fines, r);
      wall[i] = model.constants(model.coefficients, wall_partners(i));
    }
    moving = count;  // until the next layer's start freezes some (sort_by_cell)
    // Every particle moves now, so no contact is dormant: the caller's carried contacts (its
    // active() before, or a restart's) hold them all.
    dormant = {};
  }

  // Which particles a layer's start freezes (SpreadSettings::freeze_depth): those whose
  // centres lie below `level`, stopped where they are. None when freezing is off.
  std::vector<std::uint8_t> freeze_below(double level) {
    std::vector<std::uint8_t> frozen(n(), 0);
    if (!(settings.freeze_depth > 0)) return frozen;
    for (std::size_t i = 0; i < n(); ++i) {
      if (!(bed.z[i] < level)) continue;
      frozen[i] = 1;
      bed.vx[i] = bed.vy[i] = bed.vz[i] = wx[i] = wy[i] = wz[i] = 0;
    }
    return frozen;
  }

  void find_frozen_in_reach() {
    frozen_in_reach.clear();
    frozen_tool_contacts = 0;
    const double lowest = profile.z_low - profile.rounding;
    for (std::size_t i = moving; i < n(); ++i)
      if (bed.z[i] + bed.radius[i] > lowest) frozen_in_reach.push_back(static_cast<std::uint32_t>(i));
  }

  void count_frozen_tool_contacts() {
    for (const std::uint32_t i : frozen_in_reach) {
      ToolContact t;
      if (tool_contact(profile, bed.x[i] - tool_x, bed.z[i], bed.radius[i], t)) ++frozen_tool_contacts;
    }
  }

  // Every contact with its history, in owner order: the list's touching entries and the dormant
  // ones (whose owners are not integrated, so they come after the list's).
  ActiveContacts active() const {
    ActiveContacts a;
    const std::uint32_t* owner = list.owners();
    const std::uint32_t* partner = list.partners();
    for (std::size_t k = 0; k < touching.size(); ++k) {
      if (!touching[k]) continue;
      a.i.push_back(owner[k]);
      a.j.push_back(partner[k]);
      a.h.insert(a.h.end(), pair_history.begin() + static_cast<std::ptrdiff_t>(k * kContactHistory),
                 pair_history.begin() + static_cast<std::ptrdiff_t>((k + 1) * kContactHistory));
    }
    a.i.insert(a.i.end(), dormant.i.begin(), dormant.i.end());
    a.j.insert(a.j.end(), dormant.j.begin(), dormant.j.end());
    a.h.insert(a.h.end(), dormant.h.begin(), dormant.h.end());
    return a;
  }

  // A list build that keeps the history of every contact: the new list's pair (i, j) takes
  // the history the old one had (contacts are few per particle: a short scan).
  // The particles reordered by the cells they lie in, the frozen ones last (spatial_order), everything kept per
  // particle with them; a carried contact whose owner would come after its partner is turned
  // round (its history is the force and torque on the owner: they change sign) and the
  // contacts are put back in owner order, as rebuild_with reads them; those between two frozen
  // particles go to `dormant`. Done at each layer's start (a spread carries powder millimetres
  // along x, and a bed of several layers in supply order had its contact partners scattered
  // through memory) and when powder falls asleep or wakes (sleep.hpp). `carried` must hold every
  // contact (active()).
  void sort_by_cell(ActiveContacts& carried, const std::vector<std::uint8_t>& frozen) {
    const std::vector<std::size_t> order = spatial_order(bed, 2.0 * largest_radius(bed), frozen);
    moving = static_cast<std::size_t>(std::count(frozen.begin(), frozen.end(), 0));
    const auto permute = [&](auto& values, std::size_t stride) {
      if (values.empty()) return;
      const auto old = values;
      for (std::size_t k = 0; k < order.size(); ++k)
        std::copy_n(old.begin() + static_cast<std::ptrdiff_t>(order[k] * stride), stride,
                    values.begin() + static_cast<std::ptrdiff_t>(k * stride));
    };
    for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius, &bed.vx, &bed.vy, &bed.vz, &bed.temperature,
                    &weight, &mass, &inv_mass, &inv_inertia, &drag, &young, &wx, &wy, &wz, &fx, &fy, &fz,
                    &tx, &ty, &tz}) {
      permute(*v, 1);
    }
    permute(quiet, 1);
    permute(bed.id, 1);
    permute(bed.material, 1);
    permute(bed.phase, 1);
    permute(wall, 1);
    permute(wall_touch, 1);
    permute(wall_history, kWallValues);
    std::vector<std::uint32_t> rank(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<std::uint32_t>(k);
    ActiveContacts turned;
    std::vector<std::size_t> by_owner(carried.i.size());
    for (std::size_t c = 0; c < by_owner.size(); ++c) {
      carried.i[c] = rank[carried.i[c]];
      carried.j[c] = rank[carried.j[c]];
      if (carried.i[c] > carried.j[c]) {
        std::swap(carried.i[c], carried.j[c]);
        for (std::size_t q = 0; q < kContactHistory; ++q) carried.h[c * kContactHistory + q] = -carried.h[c * kContactHistory + q];
      }
      by_owner[c] = c;
    }
    std::sort(by_owner.begin(), by_owner.end(), [&](std::size_t p, std::size_t q) {
      return std::pair(carried.i[p], carried.j[p]) < std::pair(carried.i[q], carried.j[q]);
    });
    dormant = {};
    for (const std::size_t c : by_owner) {
      ActiveContacts& to = carried.i[c] >= moving ? dormant : turned;  // owner < partner: both frozen
      to.i.push_back(carried.i[c]);
      to.j.push_back(carried.j[c]);
      to.h.insert(to.h.end(), carried.h.begin() + static_cast<std::ptrdiff_t>(c * kContactHistory),
                  carried.h.begin() + static_cast<std::ptrdiff_t>((c + 1) * kContactHistory));
    }
    carried = std::move(turned);
  }

  // The constants of the pair (i, j), made when it comes into contact (most list entries never
  // do: the skin's margin).
  ContactConstants pair_constants(std::size_t i, std::size_t j) const {
    const double ri = bed.radius[i], mi = mass[i], rj = bed.radius[j], mj = mass[j];
    ContactPartners p{moduli.pair, moduli.pair_shear, scene.stiffness, ri * rj / (ri + rj), mi * mj / (mi + mj),
                      rolling_inertia(mi, ri, mj, rj)};
    if (!young.empty()) {  // stiffness-scaled fines: the two particles' own moduli
      const double nu = scene.material.poisson;
      p.e_star = effective_modulus(young[i], nu, young[j], nu);
      p.g_star = effective_shear_modulus(young[i], nu, young[j], nu);
    }
    return model.constants(model.coefficients, p);
  }

  void rebuild_with(const ActiveContacts& a) {
    list.build(view(), threads, threads > 1, moving);
    const std::size_t entries = list.pair_entries();
    if (threads > 1) pair_load.resize(entries * kPairLoad);
    buffers.resize(static_cast<std::size_t>(threads));
    pair.resize(entries);
    pair_reach.resize(entries);
    pair_history.assign(entries * kContactHistory, 0.0);
    touching.assign(entries, 0);
    std::size_t first = 0;  // a's contacts of owner i start here (a is in owner order)
    for (std::size_t i = 0; i < n(); ++i) {
      while (first < a.i.size() && a.i[first] < i) ++first;
      std::size_t last = first;
      while (last < a.i.size() && a.i[last] == i) ++last;
      std::size_t k = list.offset(i);
      for (const std::uint32_t* it = list.begin(i); it != list.end(i); ++it, ++k) {
        const std::uint32_t j = *it;
        pair_reach[k] = bed.radius[i] + bed.radius[j];
        if (model.batch) pair[k] = pair_constants(i, j);  // the batch reads every entry's
        for (std::size_t c = first; c < last; ++c) {
          if (a.j[c] != j) continue;
          std::copy_n(a.h.begin() + static_cast<std::ptrdiff_t>(c * kContactHistory), kContactHistory,
                      pair_history.begin() + static_cast<std::ptrdiff_t>(k * kContactHistory));
          touching[k] = 1;
          pair[k] = pair_constants(i, j);
        }
      }
      first = last;
    }
    prune();
  }

  // Prunes the list (NeighbourList::prune, with the margin set beside the skin) and finds the
  // wall candidates for the same interval; ends the contacts of the entries it leaves out:
  // they are more than the margin apart, and the pair loop, which no longer sees them, would
  // have ended them this step.
  void prune() {
    list.prune(view(), prune_margin);
    find_wall_candidates();
    const std::uint32_t* hot = list.hot();
    const std::size_t hot_entries = list.hot_entries();
    for (std::size_t k = 0, q = 0; k < touching.size(); ++k) {
      if (q < hot_entries && hot[q] == k) {
        ++q;
      } else if (touching[k]) {
        std::fill_n(pair_history.begin() + static_cast<std::ptrdiff_t>(k * kContactHistory), kContactHistory, 0.0);
        touching[k] = 0;
      }
    }
  }

  // The start of a step in two passes over the moving particles: (1) kick_drift, the kick v += h F / m
  // (the first half kick, with the last step's second when it is pending: step()), the drift
  // x += dt v (wrapped on periodic axes) and the body forces at the half-step velocity (gravity
  // and Stokes drag, stokes_drag.hpp; torques zeroed); (2) NeighbourList::stale, after which the
  // list is rebuilt or pruned. Two loops rather than one, each of which vectorises. False when a
  // velocity is no longer finite.
  bool start_step(double h) {
    const DriftConstants k{h, dt, {g[0], g[1], g[2]}, BranchFreeWrap(box)};
    const std::uint64_t bad = or_over_chunks(moving, threads, [&](std::size_t b, std::size_t e) {
      return kick_drift(e - b, k, bed.x.data() + b, bed.y.data() + b, bed.z.data() + b, bed.vx.data() + b,
                        bed.vy.data() + b, bed.vz.data() + b, fx.data() + b, fy.data() + b, fz.data() + b,
                        tx.data() + b, ty.data() + b, tz.data() + b, inv_mass.data() + b, weight.data() + b,
                        drag.data() + b);
    });
    if (bad) return false;  // no list of non-finite positions: the caller stops the run
    refresh_list();
    return true;
  }

  // The list rebuilt or pruned when the moving particles have gone far enough since the last.
  void refresh_list() {
    ParticleView moved = view();
    moved.n = moving;
    switch (list.stale(moved)) {
      case NeighbourList::Stale::build:
        rebuild_with(active());
        ++rebuilds;
        break;
      case NeighbourList::Stale::prune:
        prune();
        break;
      case NeighbourList::Stale::no:
        break;
    }
  }

  // One step of the classical fourth-order Runge–Kutta method (deposit's --integrator rk4), for
  // a model that neither turns the particles nor keeps a history (the driver refuses the
  // others): the derivatives (v, F/m) at four stage states, weighted 1, 2, 2, 1, the list
  // refreshed at the step's start (a stage moves a particle less than a step does). The
  // velocities stay whole-step ones (no kick is ever pending).
  void step_rk4(std::uint64_t step_number) {
    refresh_list();
    rk4.start(bed, moving);
    for (int stage = 0; stage < 4; ++stage) {
      body_forces();
      contact_forces(false);
      rk4.stage(stage, dt, bed, fx.data(), fy.data(), fz.data(), inv_mass.data(), moving);
    }
    if (!rk4.finish(dt, BranchFreeWrap(box), bed, moving)) throw_non_finite(step_number);
  }

  // The wall histories of a restart or of the particles left after an overflow, with the
  // touch bits they imply.
  void set_wall_history(const std::vector<double>& h) {
    wall_history = h;
    wall_touch.assign(n(), 0);
    for (std::size_t i = 0; i < n(); ++i)
      for (int slot = 0; slot < kWallSlots; ++slot) {
        const double* v = wall_history.data() + i * kWallValues + slot * kContactHistory;
        if (std::any_of(v, v + kContactHistory, [](double x) { return x != 0.0; }))
          wall_touch[i] |= static_cast<std::uint8_t>(1u << slot);
      }
    for (std::size_t i = 0; i < n(); ++i)
      for (std::size_t k = 0; k < kFloorSlots; ++k)
        if (*floor_slot(i, k) != 0) wall_touch[i] |= static_cast<std::uint8_t>(1u << kPlate);
  }

  void leave_wall(std::size_t i, WallSlot slot) {
    if (!(wall_touch[i] & (1u << slot))) return;
    std::fill_n(wall_history.data() + i * kWallValues + slot * kContactHistory, kContactHistory, 0.0);
    if (slot == kPlate) std::fill_n(floor_slot(i, 0), kFloorSlots * kFloorSlotValues, 0.0);
    wall_touch[i] &= static_cast<std::uint8_t>(~(1u << slot));
  }

  double* floor_slot(std::size_t i, std::size_t k) {
    return wall_history.data() + i * kWallValues + kFloorValuesAt + k * kFloorSlotValues;
  }

  void wall_contact(std::size_t i, WallSlot slot, double delta, const double n[3],
                    const double wall_velocity[3], bool update) {
    if (delta <= 0) {
      leave_wall(i, slot);
      return;
    }
    wall_touch[i] |= static_cast<std::uint8_t>(1u << slot);
    surface_force(i, slot, wall_history.data() + i * kWallValues + slot * kContactHistory, delta, n, wall_velocity,
                  update);
  }

  // The force of a wall or the floor at overlap delta along n (from the centre into the
  // surface), with the contact's history h, added to particle i's (and to the tool's).
  void surface_force(std::size_t i, int slot, double* h, double delta, const double n[3],
                     const double wall_velocity[3], bool update) {
    const double dv[3] = {bed.vx[i] - wall_velocity[0], bed.vy[i] - wall_velocity[1],
                          bed.vz[i] - wall_velocity[2]};
    const double wi[3] = {wx[i], wy[i], wz[i]}, still[3] = {0, 0, 0};
    ContactForce c;
    model.force(model.coefficients, wall[i], delta, n, dv, wi, still, bed.radius[i] - delta, 0.0, h, update, c);
    fx[i] += c.f[0];
    fy[i] += c.f[1];
    fz[i] += c.f[2];
    tx[i] += c.ti[0];
    ty[i] += c.ti[1];
    tz[i] += c.ti[2];
    if (slot == kTool) {
      for (int a = 0; a < 3; ++a) tool_force[a] += c.f[a];
    }
  }

  // The plate, or the solid on it (SpreadSettings::floor): a contact at each local minimum of the
  // distance from the centre to the floor's triangles within the radius (bed/surface_contacts.hpp),
  // along the line from the centre to it; straight up when the centre is below the surface.
  void plate_contact(std::size_t i, bool update) {
    const double still[3] = {0, 0, 0};
    const double r = bed.radius[i], x = bed.x[i], y = bed.y[i], z = bed.z[i];
    if (floor.empty()) {
      const double n[3] = {0, 0, -1};
      wall_contact(i, kPlate, r - (z - box.lower[2]), n, still, update);
      return;
    }
    std::array<bed::SurfaceContact, kFloorSlots> c;
    std::size_t count = 0;
    const bed::GridCell cell = floor.cell(x, y);  // the bounds are maps on the floor's grid
    const double high = floor_high.at(cell);
    if (z - r <= high) {  // else above the solid's highest point within its reach: no contact
      const bool flat = high - floor_low.at(cell) <= 1e-9;  // under the whole footprint
      const double foot = flat ? high : floor.surface(cell);
      if (flat || foot >= z) {  // the plane's contact, or the centre below the surface: straight up
        c[0] = {floor.triangle_at(cell), {0, 0, foot - z}, std::abs(foot - z)};
        count = foot - z + r > 0 ? 1 : 0;
      } else {
        const auto wrapped = [](double now, double seen, bool periodic, double period, std::size_t cells) {
          return periodic ? std::lround((now - seen) / period) * static_cast<std::ptrdiff_t>(cells) : 0;
        };
        count = bed::surface_contacts(
            floor, x, y, z, r, {floor_near.data() + floor_first[i], floor_count[i]},
            {wrapped(x, floor_seen_x[i], floor.periodic_x, floor.period_x(), floor.nx - 1),
             wrapped(y, floor_seen_y[i], floor.periodic_y, floor.period_y(), floor.ny - 1)},
            c);
      }
    }
    floor_contacts(i, c, count, update);
  }

  // The floor's contacts of particle i, each with the history of the slot that touched the same
  // facet at the last evaluation, else of a slot whose facet none touches now (a sphere rolling
  // across an edge keeps its spring, as LIGGGHTS hands a mesh contact's history to the next
  // triangle), else a fresh one. Slots left over are freed.
  void floor_contacts(std::size_t i, const std::array<bed::SurfaceContact, kFloorSlots>& c, std::size_t count,
                      bool update) {
    if (count == 0 && !(wall_touch[i] & (1u << kPlate))) return;
    std::array<std::size_t, kFloorSlots> slot;
    std::array<bool, kFloorSlots> taken{};
    const auto facet = [&](std::size_t k) { return *floor_slot(i, k); };
    const auto claim = [&](std::size_t m, auto&& fits) {
      for (std::size_t k = 0; k < kFloorSlots; ++k)
        if (!taken[k] && fits(k)) {
          taken[k] = true;
          slot[m] = k;
          return true;
        }
      return false;
    };
    const auto touched_now = [&](double f) {
      for (std::size_t m = 0; m < count; ++m)
        if (f == static_cast<double>(c[m].facet + 1)) return true;
      return false;
    };
    std::array<bool, kFloorSlots> matched{};
    for (std::size_t m = 0; m < count; ++m)
      matched[m] = claim(m, [&](std::size_t k) { return facet(k) == static_cast<double>(c[m].facet + 1); });
    for (std::size_t m = 0; m < count; ++m)
      if (!matched[m] && !claim(m, [&](std::size_t k) { return facet(k) != 0 && !touched_now(facet(k)); }))
        claim(m, [&](std::size_t k) { return facet(k) == 0; });
    for (std::size_t k = 0; k < kFloorSlots; ++k)
      if (!taken[k]) std::fill_n(floor_slot(i, k), kFloorSlotValues, 0.0);
    constexpr std::uint8_t plate_bit = 1u << kPlate;
    wall_touch[i] = count > 0 ? static_cast<std::uint8_t>(wall_touch[i] | plate_bit)
                              : static_cast<std::uint8_t>(wall_touch[i] & ~plate_bit);
    const double still[3] = {0, 0, 0};
    for (std::size_t m = 0; m < count; ++m) {
      double* s = floor_slot(i, slot[m]);
      s[0] = static_cast<double>(c[m].facet + 1);
      const double d = c[m].distance;
      const bool below = c[m].offset[2] >= 0;  // the centre at or below the surface: straight up
      const double n[3] = {below ? 0 : c[m].offset[0] / d, below ? 0 : c[m].offset[1] / d,
                           below ? -1 : c[m].offset[2] / d};
      surface_force(i, kPlate, s + 1, below ? bed.radius[i] + c[m].offset[2] : bed.radius[i] - d, n, still, update);
    }
  }

  // The moving particles that may touch a wall before the next prune, found at each prune:
  // none moves more than half the prune margin (`margin`) from where the prune saw it, and the
  // tool only moves on along +x within a layer (each layer's start rebuilds), so a particle
  // farther than that from the plate, the box's top and its side faces (walls), or lower than
  // the tool's bottom or behind it by more than its reach plus the margin (tool), cannot touch
  // them before the next prune. A particle whose history with a wall may be non-zero is kept
  // with that wall: it touched it at the last evaluation. With a floor (the solid of earlier
  // layers) the plate's test is against the floor's highest node within reach of the particle
  // (floor_bound: the bilinear surface and its triangles never rise above a node), so powder
  // over a low stretch of the solid, or high above it, is no candidate. Against the floor's
  // highest point overall, two thirds of a build's third layer were, with one in three of
  // them touching it (2026-12-07).
  void find_wall_candidates() {
    const double margin = 0.5 * prune_margin;
    constexpr std::uint8_t tool_bit = 1u << kTool;
    near_walls.clear();
    near_tool.clear();
    for (auto& list_of_face : near_face) list_of_face.clear();
    const bool walls = scene.has(kWalls);  // off only in a drop (check_settings)
    top_at_search = box.upper[2];
    floor_near.clear();
    if (!floor.empty() && floor_first.size() < moving) {
      floor_first.resize(moving);
      floor_count.resize(moving);
      floor_seen_x.resize(moving);
      floor_seen_y.resize(moving);
    }
    for (std::size_t i = 0; i < moving; ++i) {
      const double r = bed.radius[i], x = bed.x[i], y = bed.y[i], z = bed.z[i], reach = r + margin;
      const double plate = floor.empty() ? box.lower[2] : std::max(box.lower[2], floor_bound(x, y));
      const bool x_open = walls && !box.periodic[0], y_open = walls && !box.periodic[1];
      const bool near[kFaces] = {walls && z - plate < reach, walls && box.upper[2] - z < reach + top_slack,
                                 x_open && x - box.lower[0] < reach, x_open && box.upper[0] - x < reach,
                                 y_open && y - box.lower[1] < reach, y_open && box.upper[1] - y < reach};
      bool plate_candidate = false;  // plate_contact may be asked of it before the next prune
      if (model.batch) {  // no history: a face's candidates are those within reach of it
        for (std::size_t f = 0; f < kFaces; ++f)
          if (near[f]) near_face[f].push_back(static_cast<std::uint32_t>(i));
        plate_candidate = near[0];
      } else if (std::any_of(near, near + kFaces, [](bool b) { return b; }) || (wall_touch[i] & ~tool_bit) != 0) {
        near_walls.push_back(static_cast<std::uint32_t>(i));
        plate_candidate = true;
      }
      if (plate_candidate && !floor.empty()) {
        floor_first[i] = static_cast<std::uint32_t>(floor_near.size());
        bed::triangles_near(floor, x, y, z, reach, floor_near);
        floor_count[i] = static_cast<std::uint32_t>(floor_near.size() - floor_first[i]);
        floor_seen_x[i] = x;
        floor_seen_y[i] = y;
      }
      const double tool_reach = r + profile.rounding + margin;
      const bool tool = tool_on && ((wall_touch[i] & tool_bit) != 0 ||
                                    (profile.z_low - z < tool_reach && x > tool_x - profile.half_width - tool_reach));
      if (tool) near_tool.push_back(static_cast<std::uint32_t>(i));
    }
  }

  // The plate, the box's top and the side faces that are not periodic (a particle the tool
  // throws up stays in the box, so the bed stays a valid bed file).
  void static_walls(std::size_t i, bool update) {
    const double still[3] = {0, 0, 0};
    const double r = bed.radius[i];
    plate_contact(i, update);
    {
      const double n[3] = {0, 0, 1}, lid[3] = {0, 0, top_velocity};
      wall_contact(i, kTop, r - (box.upper[2] - bed.z[i]), n, lid, update);
    }
    for (int axis = 0; axis < 2; ++axis) {
      if (box.periodic[axis]) continue;
      const double p = axis == 0 ? bed.x[i] : bed.y[i];
      double n[3] = {0, 0, 0};
      n[axis] = -1;
      wall_contact(i, axis == 0 ? kXLow : kYLow, r - (p - box.lower[axis]), n, still, update);
      n[axis] = 1;
      wall_contact(i, axis == 0 ? kXHigh : kYHigh, r - (box.upper[axis] - p), n, still, update);
    }
  }

  void tool_wall(std::size_t i, bool update) {
    ToolContact t;
    if (!tool_contact(profile, bed.x[i] - tool_x, bed.z[i], bed.radius[i], t)) {
      leave_wall(i, kTool);
      return;
    }
    // Surface velocity: the tool's translation plus its spin about the roller's axis.
    const double ex = t.surface[0], ez = t.surface[2] - profile.z_low;
    const double omega = settings.tool.shape == ToolShape::roller ? settings.tool.omega : 0.0;
    const double v[3] = {tool_v + omega * ez, 0.0, -omega * ex};
    wall_contact(i, kTool, t.delta, t.n, v, update);
  }

  // The candidates' walls, then their tool contacts: each particle still adds its walls in the
  // order plate, top, sides, tool, and the tool's force sums its contacts by index.
  // The static walls touch only their particle's arrays, so they run on the threads; the tool
  // sums its force over its candidates, in index order, on one.
  void wall_forces(bool update) {
    if (model.batch) {
      batched_walls(update);
    } else if (threads > 1) {
      for_each_particle(near_walls.size(), threads, [&](std::size_t q) { static_walls(near_walls[q], update); });
    } else {
      for (const std::uint32_t i : near_walls) static_walls(i, update);
    }
    for (const std::uint32_t i : near_tool) tool_wall(i, update);
  }

  // Pass 1 of the box's faces as a batch (a model that batches: ContactModel::batch) for the
  // moving particles [p0, p1), face by face (so each particle meets its faces in the order of
  // static_walls): each face within a radius of a centre as a pair partner of radius 0 at the
  // foot of the perpendicular (separation: the foot minus the centre; reach: the radius), so
  // the pairs' kernel gives its force. A centre at or past the face (a particle about to be
  // lost) has its foot put a radius away on the face's outer side with the reach lengthened to
  // match, so the normal still points out of the box. The plate is a face only without a floor.
  void collect_faces(std::size_t p0, std::size_t p1, ContactBuffer& b) {
    std::size_t m = 0;
    if (floor.empty()) m = collect_face<2, 0>(p0, p1, b, m);
    m = collect_face<2, 1>(p0, p1, b, m);
    if (!box.periodic[0]) m = collect_face<0, 1>(p0, p1, b, collect_face<0, 0>(p0, p1, b, m));
    if (!box.periodic[1]) m = collect_face<1, 1>(p0, p1, b, collect_face<1, 0>(p0, p1, b, m));
    b.count = m;
  }

  // collect_faces's contacts with face (Axis, Side: 0 low, 1 high), appended at m; returns the
  // new count. Compiled per face, so the axis and side cost nothing in the loop.
  template <int Axis, int Side>
  std::size_t collect_face(std::size_t p0, std::size_t p1, ContactBuffer& b, std::size_t m) {
    constexpr std::size_t f = Axis == 2 ? Side : 2 + 2 * Axis + Side;
    constexpr double side = Side == 0 ? -1.0 : 1.0;
    const auto [first, last] = candidates(near_face[f], p0, p1);
    b.reserve(m + static_cast<std::size_t>(last - first));
    const double* at = Axis == 0 ? bed.x.data() : Axis == 1 ? bed.y.data() : bed.z.data();
    for (const std::uint32_t* it = first; it != last; ++it) {
      const std::uint32_t i = *it;
      const double r = bed.radius[i];
      const double gap = Side == 0 ? at[i] - box.lower[Axis] : box.upper[Axis] - at[i];
      if (!(gap < r)) continue;
      const double d = gap > 0 ? gap : r;
      b.i[m] = i;
      b.dx[m] = Axis == 0 ? side * d : 0.0;
      b.dy[m] = Axis == 1 ? side * d : 0.0;
      b.dz[m] = Axis == 2 ? side * d : 0.0;
      b.reach[m] = gap > 0 ? r : r - gap + d;
      b.elastic[m] = wall[i].elastic;
      b.damping[m] = wall[i].damping;
      b.dvx[m] = bed.vx[i];
      b.dvy[m] = bed.vy[i];
      b.dvz[m] = Axis == 2 && Side == 1 ? bed.vz[i] - top_velocity : bed.vz[i];  // the lid moves
      ++m;
    }
    return m;
  }

  // The walls of a model that batches, in blocks of particles: the floor's contacts (when there
  // is one) one by one, then the box's faces as a batch (collect_faces), each added to its
  // particle in static_walls's order.
  void batched_walls(bool update) {
    for_each_chunk(moving, threads, [&](std::size_t begin, std::size_t end) {
      ContactBuffer& b = buffers[static_cast<std::size_t>(omp_get_thread_num())];
      for (std::size_t p0 = begin; p0 < end; p0 += kBatchEntries) {
        const std::size_t p1 = std::min(end, p0 + kBatchEntries);
        if (!floor.empty()) {
          const auto [first, last] = candidates(near_face[0], p0, p1);
          for (auto it = first; it != last; ++it) plate_contact(*it, update);
        }
        collect_faces(p0, p1, b);
        model.batch(b.count, model.coefficients.sliding, b.dx.data(), b.dy.data(), b.dz.data(), b.reach.data(),
                    b.elastic.data(), b.damping.data(), b.dvx.data(), b.dvy.data(), b.dvz.data(), b.fx.data(),
                    b.fy.data(), b.fz.data());
        for (std::size_t c = 0; c < b.count; ++c) {
          fx[b.i[c]] += b.fx[c];
          fy[b.i[c]] += b.fy[c];
          fz[b.i[c]] += b.fz[c];
        }
      }
    });
  }

  // The pair loop's view of the run: local copies of the arrays' addresses (the contact model's
  // force is a call through a pointer, and through a member the compiler would reload each
  // address after every call). contact(k) evaluates list entry k: false when the pair does not
  // touch (a contact it had ends), else its force and torques in `c`.
  struct PairPass {
    const std::uint32_t *owner, *partner;
    const double *x, *y, *z, *r, *vx, *vy, *vz, *ox, *oy, *oz, *reach_of;
    double* history;
    std::uint8_t* touch;
    ContactConstants* constants;
    ContactFn force;
    const ContactCoefficients* coefficients;
    WrappedImage image;  // positions are wrapped at every drift
    const Engine* run;
    bool update;

    bool contact(std::size_t k, ContactForce& c) const {
      const std::uint32_t i = owner[k], j = partner[k];
      const double ex = image(0, x[j] - x[i]), ey = image(1, y[j] - y[i]), ez = image(2, z[j] - z[i]);
      const double d2 = ex * ex + ey * ey + ez * ez, reach = reach_of[k];
      double* h = history + k * kContactHistory;
      if (d2 >= reach * reach) {
        if (touch[k]) {
          std::fill_n(h, kContactHistory, 0.0);
          touch[k] = 0;
        }
        return false;
      }
      if (!touch[k]) constants[k] = run->pair_constants(i, j);
      touch[k] = 1;
      const double d = std::sqrt(d2), delta = reach - d, inv_d = 1.0 / d;
      const double n[3] = {ex * inv_d, ey * inv_d, ez * inv_d};
      const double dv[3] = {vx[i] - vx[j], vy[i] - vy[j], vz[i] - vz[j]};
      const double wi[3] = {ox[i], oy[i], oz[i]}, wj[3] = {ox[j], oy[j], oz[j]};
      force(*coefficients, constants[k], delta, n, dv, wi, wj, r[i] - 0.5 * delta, r[j] - 0.5 * delta, h, update, c);
      return true;
    }
  };

  PairPass pair_pass(bool update) {
    return {list.owners(), list.partners(), bed.x.data(), bed.y.data(), bed.z.data(), bed.radius.data(),
            bed.vx.data(), bed.vy.data(), bed.vz.data(), wx.data(), wy.data(), wz.data(), pair_reach.data(),
            pair_history.data(), touching.data(), pair.data(), model.force, &model.coefficients,
            WrappedImage(box), this, update};
  }

  // Pass 1 of a batch (contact_kernel.hpp) over hot entries [q0, q1): each entry's touch bit,
  // and the touching ones' pairs, separations, velocity differences and constants gathered
  // into b. The compaction has no branch (the count advances by the test's 0 or 1).
  void collect_batch(std::size_t q0, std::size_t q1, ContactBuffer& b) {
    b.reserve(q1 - q0);
    const std::uint32_t* __restrict hot = list.hot();
    const std::uint32_t* __restrict owner = list.owners();
    const std::uint32_t* __restrict partner = list.partners();
    const double* __restrict x = bed.x.data();
    const double* __restrict y = bed.y.data();
    const double* __restrict z = bed.z.data();
    const double* __restrict reach = pair_reach.data();
    std::uint8_t* __restrict touch = touching.data();
    std::uint32_t* __restrict bk = b.k.data();
    const WrappedImage image(box);
    std::size_t m = 0;
    for (std::size_t q = q0; q < q1; ++q) {
      const std::uint32_t k = hot[q], i = owner[k], j = partner[k];
      const double ex = image(0, x[j] - x[i]), ey = image(1, y[j] - y[i]), ez = image(2, z[j] - z[i]);
      const bool in = ex * ex + ey * ey + ez * ez < reach[k] * reach[k];
      touch[k] = static_cast<std::uint8_t>(in);
      bk[m] = k;
      m += static_cast<std::size_t>(in);
    }
    b.count = m;
    for (std::size_t c = 0; c < m; ++c) {
      const std::uint32_t k = bk[c], i = owner[k], j = partner[k];
      b.i[c] = i;
      b.j[c] = j;
      b.dx[c] = image(0, x[j] - x[i]);
      b.dy[c] = image(1, y[j] - y[i]);
      b.dz[c] = image(2, z[j] - z[i]);
      b.reach[c] = reach[k];
      b.elastic[c] = pair[k].elastic;
      b.damping[c] = pair[k].damping;
      b.dvx[c] = bed.vx[i] - bed.vx[j];
      b.dvy[c] = bed.vy[i] - bed.vy[j];
      b.dvz[c] = bed.vz[i] - bed.vz[j];
    }
  }

  // Passes 1 and 2 of a batch: the forces of the touching entries among hot [q0, q1) in b.
  void batch_forces(std::size_t q0, std::size_t q1, ContactBuffer& b) {
    collect_batch(q0, q1, b);
    model.batch(b.count, model.coefficients.sliding, b.dx.data(), b.dy.data(), b.dz.data(), b.reach.data(),
                b.elastic.data(), b.damping.data(), b.dvx.data(), b.dvy.data(), b.dvz.data(), b.fx.data(),
                b.fy.data(), b.fz.data());
  }

  // The pair forces of a model that batches (ContactModel::batch: no torques, no history), in
  // the serial loop's order: F on i, -F on j, contact by contact in increasing hot entry.
  void batched_pair_forces() {
    ContactBuffer& b = buffers[0];
    double *ax = fx.data(), *ay = fy.data(), *az = fz.data();
    for (std::size_t q0 = 0, entries = list.hot_entries(); q0 < entries; q0 += kBatchEntries) {
      batch_forces(q0, std::min(entries, q0 + kBatchEntries), b);
      for (std::size_t c = 0; c < b.count; ++c) {
        const std::uint32_t i = b.i[c], j = b.j[c];
        ax[i] += b.fx[c];
        ay[i] += b.fy[c];
        az[i] += b.fz[c];
        ax[j] -= b.fx[c];
        ay[j] -= b.fy[c];
        az[j] -= b.fz[c];
      }
    }
  }

  // The pair forces and torques added to the particles', in one fixed order: each particle's
  // contributions in increasing list entry (what the serial loop's F on i, -F on j gives).
  void pair_forces(bool update) {
    if (model.batch && threads <= 1) {
      batched_pair_forces();
      return;
    }
    if (threads > 1) {
      parallel_pair_forces(update);
      return;
    }
    const PairPass pass = pair_pass(update);
    double *ax = fx.data(), *ay = fy.data(), *az = fz.data(), *mx = tx.data(), *my = ty.data(), *mz = tz.data();
    const std::uint32_t* hot = list.hot();
    for (std::size_t q = 0, entries = list.hot_entries(); q < entries; ++q) {
      const std::size_t k = hot[q];
      ContactForce c;
      if (!pass.contact(k, c)) continue;
      const std::uint32_t i = pass.owner[k], j = pass.partner[k];
      ax[i] += c.f[0];
      ay[i] += c.f[1];
      az[i] += c.f[2];
      ax[j] -= c.f[0];
      ay[j] -= c.f[1];
      az[j] -= c.f[2];
      mx[i] += c.ti[0];
      my[i] += c.ti[1];
      mz[i] += c.ti[2];
      mx[j] += c.tj[0];
      my[j] += c.tj[1];
      mz[j] += c.tj[2];
    }
  }

  // The same on `threads` threads: the hot entries' contacts into pair_load (each entry is one
  // thread's), then each moving particle gathers its touching entries in NeighbourList's
  // incident order, which is increasing entry: the serial loop's sums, bit for bit. (The frozen
  // particles' sums, which nothing reads, are not made.)
  void parallel_pair_forces(bool update) {
    const PairPass pass = pair_pass(update);
    const std::uint32_t* hot = list.hot();
    double* load = pair_load.data();
    for_each_chunk(list.hot_entries(), threads, [&](std::size_t begin, std::size_t end) {
      if (model.batch) {
        ContactBuffer& b = buffers[static_cast<std::size_t>(omp_get_thread_num())];
        for (std::size_t q0 = begin; q0 < end; q0 += kBatchEntries) {
          batch_forces(q0, std::min(end, q0 + kBatchEntries), b);
          for (std::size_t c = 0; c < b.count; ++c) {
            double* out = load + std::size_t{b.k[c]} * kPairLoad;
            out[0] = b.fx[c];
            out[1] = b.fy[c];
            out[2] = b.fz[c];
            std::fill_n(out + 3, 6, 0.0);  // no torques
          }
        }
        return;
      }
      for (std::size_t q = begin; q < end; ++q) {
        ContactForce c;
        if (!pass.contact(hot[q], c)) continue;
        double* out = load + hot[q] * kPairLoad;
        std::copy_n(c.f, 3, out);
        std::copy_n(c.ti, 3, out + 3);
        std::copy_n(c.tj, 3, out + 6);
      }
    });
    const std::uint8_t* touch = touching.data();
    for_each_particle(moving, threads, [&](std::size_t p) {
      double f[3] = {fx[p], fy[p], fz[p]}, t[3] = {tx[p], ty[p], tz[p]};
      for (const std::uint32_t* e = list.incident_begin(p); e != list.incident_end(p); ++e) {
        const std::uint32_t k = *e >> 1;
        if (!touch[k]) continue;
        const double* c = load + std::size_t{k} * kPairLoad;  // f, t_owner, t_partner
        const bool owner = (*e & 1u) != 0;
        const double sign = owner ? 1.0 : -1.0;
        const double* torque = owner ? c + 3 : c + 6;
        for (int a = 0; a < 3; ++a) {
          f[a] += sign * c[a];
          t[a] += torque[a];
        }
      }
      fx[p] = f[0];
      fy[p] = f[1];
      fz[p] = f[2];
      tx[p] = t[0];
      ty[p] = t[1];
      tz[p] = t[2];
    });
  }

  // Gravity and Stokes drag (stokes_drag.hpp) at the velocities as they are, torques zeroed:
  // what start_step computes in its pass, for a layer's first evaluation.
  void body_forces() {
    for (std::size_t i = 0; i < moving; ++i) {
      fx[i] = weight[i] * g[0] - drag[i] * bed.vx[i];
      fy[i] = weight[i] * g[1] - drag[i] * bed.vy[i];
      fz[i] = weight[i] * g[2] - drag[i] * bed.vz[i];
      tx[i] = ty[i] = tz[i] = 0;
    }
  }

  // The contact forces and torques added to the body forces; `update` advances the contact
  // histories by one step (false: a fresh evaluation of the same state, at a layer's start, that
  // changes nothing).
  void contact_forces(bool update) {
    tool_force[0] = tool_force[1] = tool_force[2] = 0;
    wall_forces(update);
    if (scene.has(kHertz)) pair_forces(update);
  }

  void forces() {
    body_forces();
    contact_forces(false);
  }

  // v += h F / m and omega += h T / I (or omega only); whether every velocity is still finite
  // (a NaN fails the comparison, as Inf does), tested with no branch so the loops vectorise.
  bool kick(double h, bool translation = true) {
    return or_over_chunks(moving, threads, [&](std::size_t begin, std::size_t end) {
      const auto axis = [&](double* __restrict v, const double* __restrict f, const double* __restrict inv) {
        std::uint64_t bad = 0;
        for (std::size_t i = begin; i < end; ++i) {
          v[i] += h * f[i] * inv[i];
          bad |= non_finite_bit(v[i]);
        }
        return bad;
      };
      std::uint64_t bad = 0;
      if (model.rotation) {  // else no torque ever acts and the particles never turn
        bad = axis(wx.data(), tx.data(), inv_inertia.data()) | axis(wy.data(), ty.data(), inv_inertia.data()) |
              axis(wz.data(), tz.data(), inv_inertia.data());
      }
      if (translation) {
        bad |= axis(bed.vx.data(), fx.data(), inv_mass.data()) | axis(bed.vy.data(), fy.data(), inv_mass.data()) |
               axis(bed.vz.data(), fz.data(), inv_mass.data());
      }
      return bad;
    }) == 0;
  }

  // Velocity Verlet with each step's second half kick deferred and taken with the next step's
  // first, v += dt F / m in one pass instead of two (`synced`: no kick is pending, the
  // velocities are a whole step's); sync() takes a pending one alone, where whole-step
  // velocities are read (a layer's end, a restart's state). The forces see the half-step
  // velocities either way.
  void step(std::uint64_t step_number) {
    const double h = synced ? 0.5 * dt : dt;
    const bool finite = kick(h, false) & start_step(h);
    if (!finite) throw_non_finite(step_number);
    contact_forces(true);
    if (tool_on) count_frozen_tool_contacts();
    synced = false;
  }

  void sync(std::uint64_t step_number) {
    if (synced) return;
    if (!kick(0.5 * dt)) throw_non_finite(step_number);
    synced = true;
  }

  // The bed at the last whole step: a copy with the pending half kick's velocities.
  bed::Bed whole_step_bed() const {
    bed::Bed copy = bed;
    if (synced) return copy;
    for (std::size_t i = 0; i < moving; ++i) {
      const auto v = whole_step_velocity(i);
      copy.vx[i] = v[0];
      copy.vy[i] = v[1];
      copy.vz[i] = v[2];
    }
    return copy;
  }

  // The kinetic energy at the last whole step, whether or not its second half kick is pending.
  double kinetic_energy() const {
    double energy = 0;  // the frozen particles' is 0
    for (std::size_t i = 0; i < moving; ++i) {
      const auto v = whole_step_velocity(i);
      energy += 0.5 * weight[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    return energy;
  }

  // The largest speed at the last whole step, m/s.
  double max_speed() const {
    double fastest = 0;
    for (std::size_t i = 0; i < moving; ++i) {
      const auto v = whole_step_velocity(i);
      fastest = std::max(fastest, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    return std::sqrt(fastest);
  }

  // Particle i's velocity at the last whole step: what sync()'s kick would make it, to the bit.
  std::array<double, 3> whole_step_velocity(std::size_t i) const {
    if (synced) return {bed.vx[i], bed.vy[i], bed.vz[i]};
    const double h = 0.5 * dt;
    return {bed.vx[i] + h * fx[i] * inv_mass[i], bed.vy[i] + h * fy[i] * inv_mass[i],
            bed.vz[i] + h * fz[i] * inv_mass[i]};
  }

  // The particles' force on the box's top face now (the lid's, N), from the whole step's
  // velocities: each contact's normal force (the tangential ones lie in the face), summed in
  // index order over the walls' candidates (every particle that can touch the top is one);
  // the histories are read, not advanced.
  double top_force() const {
    const double n[3] = {0, 0, 1}, still[3] = {0, 0, 0};
    double total = 0;
    for (const std::uint32_t i : model.batch ? near_face[1] : near_walls) {
      const double delta = bed.radius[i] - (box.upper[2] - bed.z[i]);
      if (!(delta > 0)) continue;
      const auto v = whole_step_velocity(i);
      const double dv[3] = {v[0], v[1], v[2] - top_velocity};
      double h[kContactHistory];
      std::copy_n(wall_history.data() + i * kWallValues + kTop * kContactHistory, kContactHistory, h);
      ContactForce c;
      model.force(model.coefficients, wall[i], delta, n, dv, still, still, bed.radius[i] - delta, 0.0, h, false, c);
      total -= c.f[2];
    }
    return total;
  }

  [[noreturn]] void throw_non_finite(std::uint64_t step_number) const {
    std::size_t i = 0;
    while (i + 1 < n() && std::isfinite(bed.vx[i] + bed.vy[i] + bed.vz[i] + wx[i] + wy[i] + wz[i])) ++i;
    throw NumericalError(fmt::format(
        "particle id {} (index {}) has a non-finite velocity at step {} (t = {:g} s); try a "
        "smaller --dt",
        bed.id[i], i, step_number, static_cast<double>(step_number) * dt));
  }

};

}  // namespace powderbed::dem::detail
