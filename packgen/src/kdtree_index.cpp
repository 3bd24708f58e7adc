#include "powderbed/packgen/kdtree_index.hpp"

#include <nanoflann.hpp>

namespace powderbed::packgen {

namespace {

// nanoflann dataset adaptor over the placed particles; only the first `count` are indexed.
struct ParticleCloud {
  const Particles& p;
  std::size_t count = 0;
  std::size_t kdtree_get_point_count() const { return count; }
  double kdtree_get_pt(std::size_t i, std::size_t axis) const {
    return axis == 0 ? p.x[i] : axis == 1 ? p.y[i] : p.z[i];
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<
    nanoflann::L2_Simple_Adaptor<double, ParticleCloud>, ParticleCloud, -1, std::size_t>;

// A result set that stops at the first overlapping particle.
struct FirstOverlap {
  using DistanceType = double;
  using IndexType = std::size_t;
  const Particles& p;
  double x, y, z, r, reach2;
  std::int64_t after;
  bool found = false;
  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return found; }
  // Once an overlap is found, a negative radius prunes every remaining branch and tree.
  double worstDist() const { return found ? -1.0 : reach2; }
  bool addPoint(double, std::size_t j) {
    if (static_cast<std::int64_t>(j) <= after) return true;
    found = overlaps(p.x[j] - x, p.y[j] - y, p.z[j] - z, p.r[j] + r);
    return !found;
  }
};

}  // namespace

struct KdTreeIndex::Impl {
  Impl(int dimension, double r_max_, const Particles& particles)
      : cloud{particles, 0},
        tree(dimension, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)),
        r_max(r_max_) {}
  ParticleCloud cloud;
  Tree tree;
  double r_max;
};

KdTreeIndex::KdTreeIndex(int dimension, double r_max, const Particles& particles)
    : impl_(std::make_unique<Impl>(dimension, r_max, particles)) {}

KdTreeIndex::~KdTreeIndex() = default;

void KdTreeIndex::insert(std::uint32_t i) {
  impl_->cloud.count = std::size_t{i} + 1;
  impl_->tree.addPoints(i, i);
}

bool KdTreeIndex::fits(double x, double y, double z, double r, std::int64_t after) const {
  // Search radius r + r_max with a relative margin so no candidate at the edge is missed.
  const double reach = (r + impl_->r_max) * (1 + 1e-9);
  FirstOverlap result{impl_->cloud.p, x, y, z, r, reach * reach, after};
  const double query[3] = {x, y, z};
  impl_->tree.findNeighbors(result, query, nanoflann::SearchParams());
  return !result.found;
}

}  // namespace powderbed::packgen
