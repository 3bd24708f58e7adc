#pragma once
// Exact collision back-end on nanoflann's dynamic kd-tree (KDTreeSingleIndexDynamicAdaptor):
// a radius search of radius r + r_max around the candidate, each hit tested with the shared
// exact predicate (particles.hpp), so it answers exactly as CellGrid does (docs/physics.md §3).
#include <cstdint>
#include <memory>

#include "powderbed/packgen/particles.hpp"

namespace powderbed::packgen {

class KdTreeIndex {
 public:
  KdTreeIndex(int dimension, double r_max, const Particles& particles);
  ~KdTreeIndex();
  KdTreeIndex(const KdTreeIndex&) = delete;
  KdTreeIndex& operator=(const KdTreeIndex&) = delete;

  void insert(std::uint32_t i);
  // As CellGrid::fits: only the particles with an index above `after` (-1: all) count.
  bool fits(double x, double y, double z, double r, std::int64_t after = -1) const;

 private:
  struct Impl;  // keeps nanoflann out of the public headers
  std::unique_ptr<Impl> impl_;
};

}  // namespace powderbed::packgen
