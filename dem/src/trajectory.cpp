// Trajectory snapshots through bed's time-series writer (bed::H5Output: datasets with units, the
// temporary name and the rename) and its temporal XDMF (bed::xdmf_particle_series).
#include "powderbed/dem/trajectory.hpp"

#include <utility>
#include <vector>

#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/xdmf.hpp"

namespace powderbed::dem {

struct TrajectoryWriter::Impl {
  explicit Impl(const std::string& path) : out(path) {}
  bed::H5Output out;
  std::size_t n = 0;
  std::vector<bed::XdmfParticleStep> steps;  // the XDMF grid of each snapshot written
  std::vector<double> xyz;                   // scratch N×3

  // `a`, `b`, `c` interleaved as N×3 rows, written to `name`.
  void write_rows(const std::string& name, const std::vector<double>& a,
                  const std::vector<double>& b, const std::vector<double>& c, const char* units) {
    xyz.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      xyz[3 * i] = a[i];
      xyz[3 * i + 1] = b[i];
      xyz[3 * i + 2] = c[i];
    }
    out.write(name, xyz, {n, 3}, units);
  }
};

TrajectoryWriter::TrajectoryWriter(const std::string& path, const bed::Bed& bed)
    : impl_(std::make_unique<Impl>(path)) {
  bed::H5Output& out = impl_->out;
  impl_->n = bed.n();
  out.attribute("/", "format", std::string("powderbed.trajectory"));
  out.attribute("/", "version", std::uint64_t{1});
  out.attribute("/", "n", static_cast<std::uint64_t>(bed.n()));
  out.write("/radius", bed.radius, {bed.n()}, "m");
  out.write("/id", bed.id, {bed.n()}, "1");
  out.write(bed::kPolyvertexDataset, bed::polyvertex_connectivity(bed.n()), {bed.n()}, "1");
}

TrajectoryWriter::~TrajectoryWriter() = default;

void TrajectoryWriter::write(std::uint64_t step, double time, const bed::Bed& bed) {
  Impl& s = *impl_;
  const std::string group = bed::step_group(step);
  s.out.attribute(group, "time", time);
  s.out.attribute(group, "step", step);
  s.write_rows(group + "/position", bed.x, bed.y, bed.z, "m");
  bed::XdmfParticleStep grid{step, time, group + "/position", {{"radius", "/radius"}}};
  if (bed.has_velocity()) {
    s.write_rows(group + "/velocity", bed.vx, bed.vy, bed.vz, "m/s");
    grid.fields.push_back({"velocity", group + "/velocity", true});
  }
  s.steps.push_back(std::move(grid));
}

void TrajectoryWriter::close() {
  Impl& s = *impl_;
  s.out.commit();
  const std::string h5 = bed::file_name_of(s.out.path());
  const std::string grids = bed::xdmf_particle_series("trajectory", s.n, h5, s.steps);
  bed::write_text_file(bed::xdmf_sidecar_path(s.out.path()), bed::xdmf_document(grids));
}

}  // namespace powderbed::dem
