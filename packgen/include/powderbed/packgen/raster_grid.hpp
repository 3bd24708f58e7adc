#pragma once
// The status grid of [LP] (docs/physics.md §3, "raster grid"): grid points of spacing h cover the
// domain; a placed particle sets the points inside it (|p - c| <= r) to 1; a candidate collides
// when a point strictly inside it (|p - c| < r) has status 1 (the sum of statuses is > 0).
// Approximate: overlaps up to about h pass and some valid positions are refused.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "powderbed/bed/domain.hpp"
#include "powderbed/packgen/particles.hpp"

namespace powderbed::packgen {

class RasterGrid {
 public:
  // One byte per grid point. Throws InputError naming --raster-spacing when h is not positive
  // or the grid would need more than `max_bytes` (the message gives the finest allowed h).
  RasterGrid(const bed::Domain& domain, double h, const Particles& particles,
             std::size_t max_bytes = std::size_t{2} << 30);

  void insert(std::uint32_t i);
  bool fits(double x, double y, double z, double r) const;

  // Grid points per axis for spacing h (floor(L / h) + 1; 1 on an unused axis).
  static std::array<std::size_t, 3> points(const bed::Domain& domain, double h);
  // The smallest spacing whose grid fits in max_bytes.
  static double finest_spacing(const bed::Domain& domain, std::size_t max_bytes);

 private:
  // Calls f(index, d2 - r2) for grid points within the box of the sphere, f returns true to stop.
  template <class F>
  bool visit(double x, double y, double z, double r, F&& f) const;

  const Particles& p_;
  int dimension_;
  std::array<double, 3> lower_;
  double h_;
  std::array<std::size_t, 3> n_;
  std::vector<std::uint8_t> status_;
};

}  // namespace powderbed::packgen
