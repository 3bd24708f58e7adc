#pragma once
// Bed statistics of docs/physics.md §2.
#include <cstddef>
#include <map>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/psd.hpp"

namespace powderbed::bed {

// Volume (3D) of the part of a sphere (centre height zc, radius r) with z0 <= z <= z1, by exact
// spherical caps; area (2D) of the part of a disk with y0 <= y <= y1 by circular segments.
double sphere_slab_volume(double r, double zc, double z0, double z1);
double disk_strip_area(double r, double yc, double y0, double y1);

// Packing density of the domain box: particle volume (area) inside the box / box volume (area).
double packing_density(const Bed& bed);
// Packing density of the horizontal layer z in [z0, z1] (2D: y in [z0, z1]) across the domain.
double layer_density(const Bed& bed, double z0, double z1);

struct ContactStats {
  double tolerance = 0;                 // pair in contact when d <= (r_i + r_j)(1 + tolerance)
  std::size_t contacts = 0;             // particle–particle contacts
  double coordination = 0;              // Z = 2 contacts / N
  std::vector<std::size_t> histogram;   // histogram[k] = number of particles with k contacts
  std::size_t rattlers = 0;             // particles touching nothing: no particle, wall or floor
  std::size_t wall_contacts = 0;        // particle–wall contacts (non-periodic faces), same tol
};
ContactStats contact_stats(const Bed& bed, double tolerance);
// The same for several tolerances at once (one neighbour search), in the order given.
std::vector<ContactStats> contact_stats(const Bed& bed, const std::vector<double>& tolerances);

// max over overlapping pairs of (r_i + r_j - d) / (r_i + r_j); 0 when no pair overlaps.
double max_relative_overlap(const Bed& bed);

struct Histogram {
  std::vector<double> edges;   // size bins + 1
  std::vector<double> counts;  // number per bin
  std::vector<double> target;  // expected number per bin from the target PSD (empty if none)
};
// Histogram of radii over `bins` equal bins spanning the sample (or the PSD window if given).
Histogram radius_histogram(const Bed& bed, std::size_t bins, const Psd* target = nullptr);

struct Series {
  std::vector<double> x, y;  // bin centres and values
};
// Radial distribution function g(r) for r in (0, r_max], `bins` bins, normalised by the
// number density; no edge correction beyond counting only particles farther than r_max from
// non-periodic faces as centres (so g -> 1 at large r in the bulk).
Series radial_distribution(const Bed& bed, double r_max, std::size_t bins);
// Packing density profile phi(z) (2D: phi(y)) over `bins` layers of the domain height.
Series density_profile(const Bed& bed, std::size_t bins);

struct OrderStats {
  double tolerance = 0;       // bond when d <= (r_i + r_j)(1 + tolerance), as contact_stats
  double q6_local_mean = 0;   // mean of Steinhardt's local q6 over the counted particles
  double q6_global = 0;       // Steinhardt's global Q6 over all bonds of the counted particles
  std::size_t particles = 0;  // counted: >= 1 bond and centre >= margin from non-periodic faces
  std::size_t bonds = 0;      // bonds of the counted particles (a bond between two counts twice)
};
// Bond-orientational order (Steinhardt, Nelson & Ronchetti 1983), l = 6, bonds = contacts at
// `tolerance`: q6(i) = sqrt(4 pi / 13 sum_m |mean_j Y6m(r_ij)|^2), Q6 the same with the mean
// over every bond of the counted particles. FCC: 0.57452, simple cubic: 0.35355; random packings
// ~0.35-0.45 local, near 0 global. 3D beds only (throws InputError for 2D).
OrderStats bond_order(const Bed& bed, double tolerance, double margin = 0);

struct VoronoiStats {
  std::vector<double> local_fraction;  // per particle: sphere volume / Laguerre cell volume
                                       // (NaN for cells cut by the domain boundary)
  std::size_t interior = 0;            // number of cells fully inside the domain
  double mean = 0, sd = 0;             // over interior cells
};
// Local packing fractions from the radical (Laguerre) Voronoi tessellation, 3D beds only
// (CGAL regular triangulation). Throws InputError for 2D beds.
VoronoiStats voronoi_stats(const Bed& bed);

}  // namespace powderbed::bed
