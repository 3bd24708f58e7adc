#pragma once
// Sleeping powder (SpreadSettings::sleep; docs/deposit-spread.md "Sleeping powder"): the
// particles at rest under the tool stop being integrated, and wake when what moves pushes them.
//
// A sleeper is one of the engine's frozen particles (Engine::moving and after): not integrated,
// its walls not evaluated, its contacts with other sleepers dormant (Engine::dormant: neither
// moves, so their forces cannot change). A particle falls asleep when it has moved slower than
// SleepSettings::speed (its centre and its surface about the centre) for SleepSettings::steps
// steps in a row, lies wholly under the tool's lowest point, and every particle it touches is
// as calm or asleep: the sleeping powder keeps a rim of calm awake powder between it and what
// moves. A sleeper wakes, with the sleepers it touches, when an awake particle touching it
// moves faster than SleepSettings::wake_speed. This is the deactivation of rigid-body engines
// (Bullet's sleeping thresholds, Box2D's islands) with a rim in place of whole islands: in a
// bed every grain touches every other through its contacts, so an island would never sleep
// while the tool moves.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine.hpp"

namespace powderbed::dem::detail {

class SleepBook {
 public:
  explicit SleepBook(Engine& engine) : run(engine) {}

  // After each step's forces: counts the awake particles' steps at rest and changes the sets
  // when a sleeper is pushed or, at most once every SleepSettings::steps steps, when enough
  // particles are ready to sleep.
  void after_step() {
    const SleepSettings& s = run.settings.sleep;
    const Tally t = tally(s);
    asleep_steps += static_cast<double>(run.n() - run.moving);
    ++since_change;
    const bool sleeping = since_change >= s.steps && t.ready > 0 && t.ready >= run.moving / kShare;
    if (!t.woken.empty() || sleeping) change(s, t.woken);
  }

  double asleep_steps = 0;   // sleepers x steps
  std::uint64_t changes = 0;

 private:
  // Fewer particles ready than 1/kShare of the awake ones wait: each change reorders the bed and
  // rebuilds the list.
  static constexpr std::size_t kShare = 32;

  // The tool's lowest point (+inf without a tool): a particle sleeps only wholly under it, so
  // the tool, whose contacts are the awake particles' only, never meets a sleeper (the tool
  // only rises, layer after layer).
  double tool_lowest() const {
    return run.tool_on ? run.profile.z_low - run.profile.rounding : std::numeric_limits<double>::infinity();
  }

  // Particle i (awake) has rested long enough, wholly under the tool's lowest point.
  bool rested(std::size_t i, const SleepSettings& s, double lowest) const {
    return run.quiet[i] >= s.steps && run.bed.z[i] + run.bed.radius[i] < lowest;
  }

  // What one pass over the awake particles finds: how many could sleep now, and the sleepers
  // that a particle faster than the wake speed touches (a sleeper may be named more than once).
  struct Tally {
    std::size_t ready = 0;
    std::vector<std::uint32_t> woken;
  };

  // The awake particles' steps in a row at rest counted, and the Tally. A sleeper's index is
  // above every awake one's, so its pairs with the awake are entries those own: only the fast
  // particles' entries are read.
  Tally tally(const SleepSettings& s) {
    const double lowest = tool_lowest(), rest2 = s.speed * s.speed, wake2 = s.wake_speed * s.wake_speed;
    const bool sleepers = run.moving < run.n();
    const std::uint32_t* partner = run.list.partners();
    Tally t;
    for (std::size_t i = 0; i < run.moving; ++i) {
      const double r = run.bed.radius[i];
      const double vx = run.bed.vx[i], vy = run.bed.vy[i], vz = run.bed.vz[i];
      const double speed2 = vx * vx + vy * vy + vz * vz;
      const double spin2 = (run.wx[i] * run.wx[i] + run.wy[i] * run.wy[i] + run.wz[i] * run.wz[i]) * r * r;
      run.quiet[i] = speed2 < rest2 && spin2 < rest2 ? run.quiet[i] + 1 : 0;
      if (rested(i, s, lowest)) ++t.ready;
      if (!sleepers || !(speed2 > wake2)) continue;
      for (std::size_t k = run.list.offset(i); k < run.list.offset(i + 1); ++k)
        if (run.touching[k] && partner[k] >= run.moving) t.woken.push_back(partner[k]);
    }
    return t;
  }

  // Per particle, 1 for the awake ones that fall asleep now: rested long enough under the
  // tool, and touching only particles that have too or stay asleep.
  std::vector<std::uint8_t> calm(const SleepSettings& s, const std::vector<std::uint8_t>& wake) const {
    const double lowest = tool_lowest();
    std::vector<std::uint8_t> settled(run.n(), 0), out(run.n(), 0);
    for (std::size_t i = 0; i < run.n(); ++i) {
      settled[i] = i >= run.moving ? wake[i] == 0 : rested(i, s, lowest);
      out[i] = i < run.moving && settled[i];
    }
    const std::uint32_t* owner = run.list.owners();
    const std::uint32_t* partner = run.list.partners();
    const std::uint32_t* hot = run.list.hot();
    for (std::size_t q = 0; q < run.list.hot_entries(); ++q) {
      const std::uint32_t k = hot[q], i = owner[k], j = partner[k];
      if (!run.touching[k]) continue;
      if (!settled[i]) out[j] = 0;
      if (!settled[j]) out[i] = 0;
    }
    return out;
  }

  // The sets changed: the pushed sleepers wake with the sleepers they touch, the calm ones fall
  // asleep (stopped), the bed is reordered (Engine::sort_by_cell), the list rebuilt and the
  // forces evaluated anew (the woken ones' for their next kick).
  void change(const SleepSettings& s, const std::vector<std::uint32_t>& woken) {
    std::vector<std::uint8_t> wake(run.n(), 0);
    for (const std::uint32_t j : woken) wake[j] = 1;
    for (std::size_t c = 0; c < run.dormant.i.size(); ++c) {  // the pushed ones' sleeping partners
      const std::uint32_t i = run.dormant.i[c], j = run.dormant.j[c];
      if (wake[i] == 1 && wake[j] == 0) wake[j] = 2;
      if (wake[j] == 1 && wake[i] == 0) wake[i] = 2;
    }
    const std::vector<std::uint8_t> falls = calm(s, wake);
    std::vector<std::uint8_t> asleep(run.n(), 0);
    for (std::size_t i = 0; i < run.n(); ++i) {
      if (i >= run.moving) {
        asleep[i] = wake[i] == 0;
        run.quiet[i] = 0;
      } else if (falls[i]) {
        asleep[i] = 1;
        run.bed.vx[i] = run.bed.vy[i] = run.bed.vz[i] = run.wx[i] = run.wy[i] = run.wz[i] = 0;
      }
    }
    ActiveContacts carried = run.active();
    run.sort_by_cell(carried, asleep);
    run.rebuild_with(carried);
    ++run.rebuilds;
    run.body_forces();
    run.contact_forces(false);
    ++changes;
    since_change = 0;
  }

  Engine& run;
  std::uint64_t since_change = 0;
};

}  // namespace powderbed::dem::detail
