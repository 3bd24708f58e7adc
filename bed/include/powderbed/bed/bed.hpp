#pragma once
// The one bed of docs/bed-format.md: particles as a structure of arrays plus the domain and provenance.
#include <cstdint>
#include <string>
#include <vector>

#include "powderbed/bed/domain.hpp"

namespace powderbed::bed {

enum class Phase : std::uint8_t { solid = 0, liquid = 1, gas = 2 };

// Where a bed came from; written to the file root and /provenance.
// How a DEM stage made the bed: its normal contact law and what keff's Hertz correction of the
// contact radius needs (docs/bed-format.md). An empty law: not recorded (a geometric bed, an
// imported one, a file written before this was recorded).
struct ContactProvenance {
  std::string law;          // "hertz" | "linear" | ""
  double young = 0;         // particles' E, Pa (the material's, not softened)
  double poisson = 0;       // particles' nu
  double wall_young = 0;    // walls' E, Pa
  double wall_poisson = 0;  // walls' nu
  double young_scale = 1;   // hertz: the DEM ran with E / young_scale (particles and walls)
  double stiffness = 0;     // linear: k_n, N/m (pairs and walls)
  // hertz: particles below this radius (m) ran with E (r / R)^2 (deposit's fines.scaling =
  // stiffness, docs/deposit-fines.md), which keff's Hertz correction does not model; 0: none.
  double fines_stiffness_radius = 0;
};

struct Provenance {
  std::string created_by;    // "<app> <version>"
  std::string command_line;  // as typed
  std::uint64_t rng_seed = 0;
  std::string stage;         // "packgen", "deposit", "lattice", ...
  std::string scene;         // the whole resolved configuration, INI text
  ContactProvenance contact;
  // The printed precision of a bed read from text: the most significant digits any of its
  // centres or radii was printed with (a format prints at most that many; LAMMPS's default dump
  // format %g: 6, %.17g: 17, exact), 0 for a bed read from HDF5 or made here. Not stored in the
  // bed file: printed_precision_warning (io.hpp) reads it after an import.
  int printed_digits = 0;
};

struct Bed {
  Domain domain;
  // Required per-particle arrays (all of size n()).
  std::vector<double> x, y, z;     // centre, m (2D beds: z = 0)
  std::vector<double> radius;      // m
  std::vector<std::uint64_t> id;   // stable identity across stages
  // Optional per-particle arrays: empty when absent, else of size n().
  std::vector<double> vx, vy, vz;  // m/s
  std::vector<std::uint16_t> material;
  std::vector<double> temperature;  // K
  std::vector<std::uint8_t> phase;  // Phase values
  Provenance provenance;

  std::size_t n() const { return radius.size(); }
  bool has_velocity() const { return !vx.empty(); }

  // Appends a particle with id = last id + 1 (0 for the first); O(1).
  void add(double px, double py, double pz, double r);
  void reserve(std::size_t count);
  // Throws InputError naming `source` when arrays disagree in size, a value is NaN/Inf, a
  // radius is not positive, or ids repeat.
  void validate(const std::string& source) const;
  // What every reader checks after validate() (docs/hardening.md): each radius below the
  // domain's smallest extent (a larger one is the unit slip "radii in um?") and each centre
  // inside the domain to within its own radius on every axis (periodic axes too: beds are
  // stored wrapped). Throws InputError naming `source`, the particle, its value and the box.
  void validate_geometry(const std::string& source) const;
};

}  // namespace powderbed::bed
