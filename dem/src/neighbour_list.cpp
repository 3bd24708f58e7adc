#include "neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "parallel.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::dem::detail {

void NeighbourList::configure(const Box& box, double r_max, double skin, std::size_t n) {
  box_ = box;
  skin_ = skin;
  double width = 2.0 * r_max + skin;
  // At most ~8 cells per particle (and 4096 per axis): a tall, sparse box would otherwise
  // spend each rebuild clearing millions of empty cells. Wider cells stay correct.
  const double cap = 8.0 * static_cast<double>(n) + 64.0;
  const double cells_at_width =
      (box.length[0] / width) * (box.length[1] / width) * (box.length[2] / width);
  if (cells_at_width > cap) width *= std::cbrt(cells_at_width / cap);
  for (int a = 0; a < 3; ++a) {
    const double cells = std::floor(box.length[a] / width);
    cells_[a] = static_cast<int>(std::clamp(cells, 1.0, 4096.0));
    cell_size_[a] = box.length[a] / cells_[a];
    if (box.periodic[a] && cells_[a] < 3) {
      std::ostringstream msg;
      msg << "--periodic: axis " << "xyz"[a] << " is " << box.length[a]
          << " m long, shorter than 3 neighbour cells of " << width
          << " m (accepted: length >= 3 (largest diameter + skin))";
      throw InputError(msg.str());
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
        for (std::uint32_t s = cell_start_[cell]; s < cell_start_[cell + 1]; ++s) {
          const std::uint32_t j = cell_particles_[s];
          if (j == i) continue;
          const double ex = box_.image(0, p.x[j] - p.x[i]);
          const double ey = box_.image(1, p.y[j] - p.y[i]);
          const double ez = box_.image(2, p.z[j] - p.z[i]);
          const double reach = ri + p.radius[j] + skin_;
          if (ex * ex + ey * ey + ez * ez <= reach * reach) f(j);
        }
      }
    }
  }
}

void NeighbourList::build(const ParticleView& p, int threads) {
  const std::size_t n = p.n;
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
  // Count partners, prefix-sum, then fill: both passes per particle, in parallel.
  offset_.assign(n + 1, 0);
  for_each_particle(n, threads, [&](std::size_t i) {
    std::uint32_t k = 0;
    for_each_candidate(p, i, [&](std::uint32_t) { ++k; });
    offset_[i + 1] = k;
  });
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  partners_.resize(offset_[n]);
  for_each_particle(n, threads, [&](std::size_t i) {
    std::uint32_t* out = partners_.data() + offset_[i];
    for_each_candidate(p, i, [&](std::uint32_t j) { *out++ = j; });
  });
  x0_.assign(p.x, p.x + n);
  y0_.assign(p.y, p.y + n);
  z0_.assign(p.z, p.z + n);
}

double NeighbourList::max_displacement2(const ParticleView& p, int threads) const {
  return max_over_particles(p.n, threads, [&](std::size_t i) {
    const double ex = box_.image(0, p.x[i] - x0_[i]);
    const double ey = box_.image(1, p.y[i] - y0_[i]);
    const double ez = box_.image(2, p.z[i] - z0_[i]);
    return ex * ex + ey * ey + ez * ez;
  });
}

}  // namespace powderbed::dem::detail
