#include "powderbed/bed/bed.hpp"

#include <cmath>
#include <fmt/format.h>
#include <unordered_set>

#include "powderbed/bed/errors.hpp"

namespace powderbed::bed {

void Bed::reserve(std::size_t count) {
  x.reserve(count);
  y.reserve(count);
  z.reserve(count);
  radius.reserve(count);
  id.reserve(count);
}

void Bed::add(double px, double py, double pz, double r) {
  // Ids are appended in increasing order by every stage, so the last one is the largest
  // (validate() still catches a repeat in a bed assembled otherwise).
  const std::uint64_t next = id.empty() ? 0 : id.back() + 1;
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
  radius.push_back(r);
  id.push_back(next);
}

namespace {

template <class T>
void check_size(const std::string& source, const char* name, const std::vector<T>& v,
                std::size_t n, bool optional) {
  if (optional && v.empty()) return;
  if (v.size() != n) {
    throw InputError(fmt::format(
        "{}: {} has {} entries but the bed has {} particles (accepted: one per particle)", source,
        name, v.size(), n));
  }
}

void check_finite(const std::string& source, const char* name, const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw InputError(fmt::format("{}: {}[{}] is {:g} (accepted: finite numbers)", source, name,
                                   i, v[i]));
    }
  }
}

}  // namespace

void Bed::validate(const std::string& source) const {
  domain.validate(source.c_str());
  const std::size_t count = n();
  check_size(source, "position x", x, count, false);
  check_size(source, "position y", y, count, false);
  check_size(source, "position z", z, count, false);
  check_size(source, "id", id, count, false);
  check_size(source, "velocity x", vx, count, true);
  check_size(source, "velocity y", vy, count, true);
  check_size(source, "velocity z", vz, count, true);
  check_size(source, "material", material, count, true);
  check_size(source, "temperature", temperature, count, true);
  check_size(source, "phase", phase, count, true);
  check_finite(source, "position x", x);
  check_finite(source, "position y", y);
  check_finite(source, "position z", z);
  check_finite(source, "radius", radius);
  check_finite(source, "velocity x", vx);
  check_finite(source, "velocity y", vy);
  check_finite(source, "velocity z", vz);
  check_finite(source, "temperature", temperature);
  for (std::size_t i = 0; i < count; ++i) {
    if (!(radius[i] > 0)) {
      throw InputError(
          fmt::format("{}: radius[{}] is {:g} (accepted: > 0)", source, i, radius[i]));
    }
  }
  for (std::size_t i = 0; i < phase.size(); ++i) {
    if (phase[i] > 2) {
      throw InputError(fmt::format("{}: phase[{}] is {} (accepted: 0 solid, 1 liquid, 2 gas)",
                                   source, i, int{phase[i]}));
    }
  }
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!seen.insert(id[i]).second) {
      throw InputError(
          fmt::format("{}: id {} appears twice (accepted: unique ids)", source, id[i]));
    }
  }
}

void Bed::validate_geometry(const std::string& source) const {
  const int dims = domain.dimension == 2 ? 2 : 3;
  double smallest = domain.length(0);
  int smallest_axis = 0;
  for (int a = 1; a < dims; ++a) {
    if (domain.length(a) < smallest) {
      smallest = domain.length(a);
      smallest_axis = a;
    }
  }
  const std::size_t count = n();
  for (std::size_t i = 0; i < count; ++i) {
    if (radius[i] >= smallest) {
      throw InputError(fmt::format(
          "{}: radius[{}] is {:g} m, not below the domain's smallest extent ({}: {:g} m) "
          "(accepted: radius < {:g} m; radii in um or mm instead of m?)",
          source, i, radius[i], "xyz"[smallest_axis], smallest, smallest));
    }
  }
  const std::vector<double>* centre[3] = {&x, &y, &z};
  for (std::size_t i = 0; i < count; ++i) {
    for (int a = 0; a < dims; ++a) {
      const double c = (*centre[a])[i];
      if (c < domain.lower[a] - radius[i] || c > domain.upper[a] + radius[i]) {
        throw InputError(fmt::format(
            "{}: particle {} (id {}) has {} = {:g} m, outside the domain [{:g}, {:g}] m by more "
            "than its radius {:g} m (accepted: every centre inside the domain; positions in um or "
            "mm instead of m?)",
            source, i, id[i], "xyz"[a], c, domain.lower[a], domain.upper[a], radius[i]));
      }
    }
  }
}

}  // namespace powderbed::bed
