#include "neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include <omp.h>

#include "lane_tests.hpp"
#include "parallel.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::dem::detail {

void NeighbourList::configure(const Box& box, double r_max, double skin, std::size_t n) {
  box_ = box;
  skin_ = skin;
  const double least = 2.0 * r_max + skin;  // what finding every partner needs
  double width = least;
  // At most ~8 cells per particle (and 4096 per axis): a tall, sparse box would otherwise
  // spend each rebuild clearing millions of empty cells. Wider cells stay correct, but only
  // as wide as lets a periodic axis keep its 3 cells: a few particles left in a narrow periodic
  // box (a spread's layer after its overflow went) were refused as if the box were too narrow.
  const double cap = 8.0 * static_cast<double>(n) + 64.0;
  const double cells_at_width =
      (box.length[0] / width) * (box.length[1] / width) * (box.length[2] / width);
  if (cells_at_width > cap) width *= std::cbrt(cells_at_width / cap);
  for (int a = 0; a < 3; ++a) {
    const double axis_width =
        box.periodic[a] ? std::max(least, std::min(width, box.length[a] / 3.0 * (1.0 - 1e-9))) : width;
    const double cells = std::floor(box.length[a] / axis_width);
    cells_[a] = static_cast<int>(std::clamp(cells, 1.0, 4096.0));
    cell_size_[a] = box.length[a] / cells_[a];
    if (box.periodic[a] && cells_[a] < 3) {
      throw InputError(fmt::format(
          "--periodic: axis {} is {:g} m long, shorter than 3 neighbour cells of {:g} m "
          "(accepted: length >= 3 (largest diameter + skin))",
          "xyz"[a], box.length[a], least));
    }
  }
}

int NeighbourList::cell_coordinate(int axis, double v) const {
  // Clamped, so particles that left the box on a non-periodic axis stay in the edge cells
  // (clamping keeps partners within one cell of each other).
  const double c = std::floor((v - box_.lower[axis]) / cell_size_[axis]);
  return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(cells_[axis] - 1)));
}

template <class F>
void NeighbourList::for_each_candidate(const ParticleView& p, std::size_t i, F&& f) const {
  const int cx = cell_coordinate(0, p.x[i]);
  const int cy = cell_coordinate(1, p.y[i]);
  const int cz = cell_coordinate(2, p.z[i]);
  const double ri = p.radius[i];
  const WrappedImage image(box_);
  for (int dz = -1; dz <= 1; ++dz) {
    int kz = cz + dz;
    if (box_.periodic[2]) kz = (kz + cells_[2]) % cells_[2];
    if (kz < 0 || kz >= cells_[2]) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      int ky = cy + dy;
      if (box_.periodic[1]) ky = (ky + cells_[1]) % cells_[1];
      if (ky < 0 || ky >= cells_[1]) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        int kx = cx + dx;
        if (box_.periodic[0]) kx = (kx + cells_[0]) % cells_[0];
        if (kx < 0 || kx >= cells_[0]) continue;
        const std::size_t cell =
            (static_cast<std::size_t>(kz) * cells_[1] + ky) * cells_[0] + kx;
        // Half list: each pair under its lower index. A cell lists its particles by index,
        // so those above i are a tail of it, found by bisection (in a spread, whose particles
        // are put in cell order at each layer's start, most candidates lie below i).
        const std::uint32_t* first = cell_particles_.data() + cell_start_[cell];
        const std::uint32_t* last = cell_particles_.data() + cell_start_[cell + 1];
        for (auto s = static_cast<std::size_t>(std::upper_bound(first, last, i) - cell_particles_.data());
             s < cell_start_[cell + 1]; ++s) {
          const std::uint32_t j = cell_particles_[s];
          const double ex = image(0, sorted_[4 * s] - p.x[i]);
          const double ey = image(1, sorted_[4 * s + 1] - p.y[i]);
          const double ez = image(2, sorted_[4 * s + 2] - p.z[i]);
          const double reach = ri + sorted_[4 * s + 3] + skin_;
          if (ex * ex + ey * ey + ez * ez <= reach * reach) f(j);
        }
      }
    }
  }
}

// Count partners, prefix-sum, then fill: both passes per particle, in parallel.
void NeighbourList::fill_in_parallel(const ParticleView& p, int threads, std::size_t owners) {
  const std::size_t n = p.n;
  for_each_particle(owners, threads, [&](std::size_t i) {
    std::uint32_t k = 0;
    for_each_candidate(p, i, [&](std::uint32_t) { ++k; });
    offset_[i + 1] = k;
  });
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  partners_.resize(offset_[n]);
  owners_.resize(offset_[n]);
  for_each_particle(owners, threads, [&](std::size_t i) {
    std::uint32_t* out = partners_.data() + offset_[i];
    for_each_candidate(p, i, [&](std::uint32_t j) { *out++ = j; });
    std::fill(owners_.begin() + offset_[i], owners_.begin() + offset_[i + 1],
              static_cast<std::uint32_t>(i));
  });
}

void NeighbourList::build(const ParticleView& p, int threads, bool with_incident, std::size_t owners) {
  const std::size_t n = p.n;
  owners = std::min(owners, n);
  const std::size_t cells = static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2];
  // Counting sort of particles by cell (serial: O(N), and the order is then fixed).
  particle_cell_.resize(n);
  cell_start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c =
        (static_cast<std::size_t>(cell_coordinate(2, p.z[i])) * cells_[1] +
         cell_coordinate(1, p.y[i])) * cells_[0] + cell_coordinate(0, p.x[i]);
    particle_cell_[i] = static_cast<std::uint32_t>(c);
    ++cell_start_[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(n);
  {
    std::vector<std::uint32_t>& fill = offset_;  // reused as a cursor before offsets are built
    fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      cell_particles_[fill[particle_cell_[i]]++] = static_cast<std::uint32_t>(i);
    }
  }
  sorted_.resize(4 * n);
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t j = cell_particles_[s];
    sorted_[4 * s] = p.x[j];
    sorted_[4 * s + 1] = p.y[j];
    sorted_[4 * s + 2] = p.z[j];
    sorted_[4 * s + 3] = p.radius[j];
  }
  offset_.assign(n + 1, 0);
  if (threads <= 1) {  // one pass, appending in the order the parallel fill below writes
    partners_.clear();
    owners_.clear();
    for (std::size_t i = 0; i < owners; ++i) {
      for_each_candidate(p, i, [&](std::uint32_t j) {
        partners_.push_back(j);
        owners_.push_back(static_cast<std::uint32_t>(i));
      });
      offset_[i + 1] = static_cast<std::uint32_t>(partners_.size());
    }
    std::fill(offset_.begin() + static_cast<std::ptrdiff_t>(owners) + 1, offset_.end(), offset_[owners]);
  } else {
    fill_in_parallel(p, threads, owners);
  }
  if (with_incident) {
    // Serial fill in increasing i: a particle's pairs under lower indices arrive first, in the
    // order of those indices, then its own pairs are appended.
    incident_offset_.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      incident_offset_[i + 1] += offset_[i + 1] - offset_[i];
      for (std::uint32_t k = offset_[i]; k < offset_[i + 1]; ++k) ++incident_offset_[partners_[k] + 1];
    }
    for (std::size_t i = 0; i < n; ++i) incident_offset_[i + 1] += incident_offset_[i];
    incident_.resize(incident_offset_[n]);
    std::vector<std::uint32_t> cursor(incident_offset_.begin(), incident_offset_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = offset_[i]; k < offset_[i + 1]; ++k) {
        incident_[cursor[i]++] = 2 * k + 1;
        incident_[cursor[partners_[k]]++] = 2 * k;
      }
    }
  }
  x0_.assign(p.x, p.x + n);
  y0_.assign(p.y, p.y + n);
  z0_.assign(p.z, p.z + n);
}

namespace {

// Whether some particle of [begin, end) moved more than sqrt(limit2) from (x0, y0, z0): a
// restrict-qualified loop ORing above_bit (lane_tests.hpp), which the compiler vectorises. Both
// positions are wrapped into the box, so WrappedImage gives the separation's minimum image.
bool any_moved(std::size_t begin, std::size_t end, double limit2, const WrappedImage image,
               const double* __restrict x, const double* __restrict y,
               const double* __restrict z, const double* __restrict x0,
               const double* __restrict y0, const double* __restrict z0) {
  std::uint64_t moved = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const double ex = image(0, x[i] - x0[i]), ey = image(1, y[i] - y0[i]), ez = image(2, z[i] - z0[i]);
    moved |= above_bit(ex * ex + ey * ey + ez * ez, limit2);
  }
  return moved != 0;
}

}  // namespace

void NeighbourList::prune(const ParticleView& p, double margin) {
  margin_ = margin;
  const WrappedImage image(box_);
  hot_.clear();
  for (std::size_t k = 0; k < partners_.size(); ++k) {
    const std::uint32_t i = owners_[k], j = partners_[k];
    const double ex = image(0, p.x[j] - p.x[i]), ey = image(1, p.y[j] - p.y[i]), ez = image(2, p.z[j] - p.z[i]);
    const double reach = p.radius[i] + p.radius[j] + margin;
    if (ex * ex + ey * ey + ez * ez < reach * reach) hot_.push_back(static_cast<std::uint32_t>(k));
  }
  xp_.assign(p.x, p.x + p.n);
  yp_.assign(p.y, p.y + p.n);
  zp_.assign(p.z, p.z + p.n);
}

NeighbourList::Stale NeighbourList::stale(const ParticleView& p) const {
  const WrappedImage image(box_);
  const double half_margin = 0.5 * margin_;
  if (!any_moved(0, p.n, half_margin * half_margin, image, p.x, p.y, p.z, xp_.data(), yp_.data(), zp_.data())) {
    return Stale::no;
  }
  const double limit = 0.5 * (skin_ - margin_);
  return any_moved(0, p.n, limit * limit, image, p.x, p.y, p.z, x0_.data(), y0_.data(), z0_.data())
             ? Stale::build
             : Stale::prune;
}

bool NeighbourList::moved_more_than(const ParticleView& p, double limit, int threads) const {
  const double limit2 = limit * limit;
  if (threads <= 1) {
    return any_moved(0, p.n, limit2, WrappedImage(box_), p.x, p.y, p.z, x0_.data(), y0_.data(), z0_.data());
  }
  bool moved = false;
#pragma omp parallel num_threads(threads) reduction(|| : moved)
  {
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto rank = static_cast<std::size_t>(omp_get_thread_num());
    moved = any_moved(p.n * rank / team, p.n * (rank + 1) / team, limit2, WrappedImage(box_), p.x, p.y, p.z,
                      x0_.data(), y0_.data(), z0_.data());
  }
  return moved;
}

}  // namespace powderbed::dem::detail
