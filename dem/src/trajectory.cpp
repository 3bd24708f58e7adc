#include "powderbed/dem/trajectory.hpp"

#include <hdf5.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_handle.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/bed/xdmf.hpp"

namespace powderbed::dem {

namespace {

using bed::H5Attr;
using bed::H5Dataset;
using bed::H5File;
using bed::H5Group;
using bed::H5Space;
using bed::H5Type;

void check(bool ok, const std::string& path, const std::string& what) {
  if (!ok) throw InputError("--trajectory: cannot write " + what + " to '" + path + "'");
}

// Variable-length UTF-8, as the bed files' strings (h5py reads str, not bytes).
void write_string_attribute(hid_t where, const char* name, const std::string& value,
                            const std::string& path) {
  H5Type type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  H5Space space(H5Screate(H5S_SCALAR));
  H5Attr attr(H5Acreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT));
  const char* text = value.c_str();
  check(attr.valid() && H5Awrite(attr, type, &text) >= 0, path, name);
}

// A dataset with its SI unit as the attribute `units` ("1": a number without unit).
void write_dataset(hid_t where, const char* name, hid_t type, const void* data, hsize_t rows,
                   hsize_t cols, const char* units, const std::string& path) {
  const hsize_t dims[2] = {rows, cols};
  H5Space space(H5Screate_simple(cols > 1 ? 2 : 1, dims, nullptr));
  H5Dataset set(H5Dcreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  check(set.valid() && H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0, path, name);
  write_string_attribute(set, "units", units, path);
}

template <class T>
void write_attribute(hid_t where, const char* name, hid_t type, T value, const std::string& path) {
  H5Space space(H5Screate(H5S_SCALAR));
  H5Attr attr(H5Acreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT));
  check(attr.valid() && H5Awrite(attr, type, &value) >= 0, path, name);
}



// XDMF temporal collection: one Polyvertex grid per snapshot, radius shared.
std::string trajectory_xdmf(const std::string& h5, std::size_t n,
                            const std::vector<std::pair<std::uint64_t, double>>& snapshots,
                            bool velocity) {
  std::ostringstream x;
  x.precision(17);
  const auto item = [&](const std::string& dims, const std::string& dataset) {
    x << "     <DataItem Dimensions=\"" << dims << "\" NumberType=\"Float\" Precision=\"8\" "
      << "Format=\"HDF\">" << h5 << ":" << dataset << "</DataItem>\n";
  };
  const std::string count = std::to_string(n);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"trajectory\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& [step, time] : snapshots) {
    const std::string group = bed::step_group(step);
    x << "   <Grid Name=\"step " << step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << time << "\"/>\n"
      << bed::xdmf_polyvertex_topology(n, h5, "    ") << "    <Geometry GeometryType=\"XYZ\">\n";
    item(count + " 3", group + "/position");
    x << "    </Geometry>\n"
      << "    <Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    item(count, "/radius");
    x << "    </Attribute>\n";
    if (velocity) {
      x << "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n";
      item(count + " 3", group + "/velocity");
      x << "    </Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return x.str();
}

}  // namespace

struct TrajectoryWriter::Impl {
  std::string path, temp;
  H5File file;
  std::size_t n = 0;
  std::vector<std::pair<std::uint64_t, double>> snapshots;  // (step, time)
  std::vector<double> xyz;                                   // scratch N×3
  bool velocity = false;                                     // the steps have velocities
};

TrajectoryWriter::TrajectoryWriter(const std::string& path, const bed::Bed& bed)
    : impl_(std::make_unique<Impl>()) {
  bed::silence_hdf5_errors();
  impl_->path = path;
  // "<path>.tmp.<pid>", registered so that SIGINT/SIGTERM removes it (bed/temp_files.hpp).
  impl_->temp = bed::temp_path_for(path);
  impl_->n = bed.n();
  bed::remove_stale_temp_files(path);  // left by a SIGKILLed run
  bed::register_temp_file(impl_->temp);
  impl_->file = H5File(H5Fcreate(impl_->temp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  if (!impl_->file.valid()) {
    bed::unregister_temp_file(impl_->temp);
    throw InputError("--trajectory: cannot create '" + path + "'");
  }
  write_string_attribute(impl_->file, "format", "powderbed.trajectory", path);
  write_attribute(impl_->file, "version", H5T_NATIVE_INT, 1, path);
  write_attribute(impl_->file, "n", H5T_NATIVE_UINT64, static_cast<std::uint64_t>(bed.n()), path);
  write_dataset(impl_->file, "radius", H5T_NATIVE_DOUBLE, bed.radius.data(), bed.n(), 1, "m", path);
  write_dataset(impl_->file, "id", H5T_NATIVE_UINT64, bed.id.data(), bed.n(), 1, "1", path);
  H5Group xdmf(H5Gcreate2(impl_->file, "xdmf", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  check(xdmf.valid(), path, "/xdmf");
  const std::vector<std::uint64_t> cells = bed::polyvertex_connectivity(bed.n());
  write_dataset(impl_->file, bed::kPolyvertexDataset, H5T_NATIVE_UINT64, cells.data(), bed.n(), 1,
                "1", path);
  H5Group steps(H5Gcreate2(impl_->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  check(steps.valid(), path, "/steps");
}

TrajectoryWriter::~TrajectoryWriter() {
  if (impl_ && impl_->file.valid()) {
    impl_->file.close();
    std::remove(impl_->temp.c_str());
    bed::unregister_temp_file(impl_->temp);
  }
}

void TrajectoryWriter::write(std::uint64_t step, double time, const bed::Bed& bed) {
  Impl& s = *impl_;
  const std::string name = bed::step_group(step);
  H5Group group(H5Gcreate2(s.file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  check(group.valid(), s.path, name);
  write_attribute(group, "time", H5T_NATIVE_DOUBLE, time, s.path);
  write_attribute(group, "step", H5T_NATIVE_UINT64, step, s.path);
  s.xyz.resize(3 * s.n);
  for (std::size_t i = 0; i < s.n; ++i) {
    s.xyz[3 * i] = bed.x[i];
    s.xyz[3 * i + 1] = bed.y[i];
    s.xyz[3 * i + 2] = bed.z[i];
  }
  write_dataset(group, "position", H5T_NATIVE_DOUBLE, s.xyz.data(), s.n, 3, "m", s.path);
  if (bed.has_velocity()) {
    for (std::size_t i = 0; i < s.n; ++i) {
      s.xyz[3 * i] = bed.vx[i];
      s.xyz[3 * i + 1] = bed.vy[i];
      s.xyz[3 * i + 2] = bed.vz[i];
    }
    write_dataset(group, "velocity", H5T_NATIVE_DOUBLE, s.xyz.data(), s.n, 3, "m/s", s.path);
    s.velocity = true;
  }
  s.snapshots.emplace_back(step, time);
}

void TrajectoryWriter::close() {
  Impl& s = *impl_;
  if (!s.file.valid()) return;
  const bool closed = s.file.close();
  const bool renamed = closed && std::rename(s.temp.c_str(), s.path.c_str()) == 0;
  if (!renamed) std::remove(s.temp.c_str());
  bed::unregister_temp_file(s.temp);
  check(renamed, s.path, "the file");
  const std::string xmf = bed::xdmf_sidecar_path(s.path);
  bed::TempFile xmf_temp(bed::temp_path_for(xmf));
  {
    std::ofstream out(xmf_temp.path());
    out << trajectory_xdmf(bed::file_name_of(s.path), s.n, s.snapshots, s.velocity);
    check(static_cast<bool>(out), xmf, "the XDMF text");
  }
  check(std::rename(xmf_temp.path().c_str(), xmf.c_str()) == 0, xmf, "the XDMF file");
  xmf_temp.release();
}

}  // namespace powderbed::dem
