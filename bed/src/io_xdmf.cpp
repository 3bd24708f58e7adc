// XDMF 3 sidecar of an HDF5 bed (docs/bed-format.md): ParaView opens the .xmf and reads the
// arrays from the .h5; docs/bed-format.md "Seeing true radii in ParaView" draws true radii.
#include <sstream>

#include "io_detail.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/xdmf.hpp"

namespace powderbed::bed::detail {

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// One <DataItem> pointing at /particles/<name> in the .h5.
void data_item(std::ostringstream& out, const std::string& h5, const char* name, std::size_t n,
               int cols, const char* number_type, int precision) {
  out << "        <DataItem Dimensions=\"" << n;
  if (cols > 1) out << ' ' << cols;
  out << "\" NumberType=\"" << number_type << "\" Precision=\"" << precision
      << "\" Format=\"HDF\">" << h5 << ":/particles/" << name << "</DataItem>\n";
}

void attribute(std::ostringstream& out, const std::string& h5, const char* name, std::size_t n,
               bool vector, const char* number_type, int precision) {
  out << "      <Attribute Name=\"" << name << "\" AttributeType=\""
      << (vector ? "Vector" : "Scalar") << "\" Center=\"Node\">\n";
  data_item(out, h5, name, n, vector ? 3 : 1, number_type, precision);
  out << "      </Attribute>\n";
}

}  // namespace

std::string xdmf_path(const std::string& h5_path) {
  if (extension_of(h5_path) == ".h5") return h5_path.substr(0, h5_path.size() - 3) + ".xmf";
  return h5_path + ".xmf";
}

std::string xdmf_text(const Bed& bed, const std::string& h5_file_name) {
  const std::string h5 = xml_escape(h5_file_name);
  const std::size_t n = bed.n();
  std::ostringstream out;
  out << "<?xml version=\"1.0\" ?>\n"
      << "<Xdmf Version=\"3.0\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"bed\" GridType=\"Uniform\">\n"
      << xdmf_polyvertex_topology(n, h5, "      ")
      << "      <Geometry GeometryType=\"XYZ\">\n";
  data_item(out, h5, "position", n, 3, "Float", 8);
  out << "      </Geometry>\n";
  attribute(out, h5, "radius", n, false, "Float", 8);
  attribute(out, h5, "id", n, false, "UInt", 8);
  if (!bed.material.empty()) attribute(out, h5, "material", n, false, "UInt", 2);
  if (bed.has_velocity()) attribute(out, h5, "velocity", n, true, "Float", 8);
  if (!bed.temperature.empty()) attribute(out, h5, "temperature", n, false, "Float", 8);
  if (!bed.phase.empty()) attribute(out, h5, "phase", n, false, "UChar", 1);
  out << "    </Grid>\n"
      << "  </Domain>\n"
      << "</Xdmf>\n";
  return out.str();
}

}  // namespace powderbed::bed::detail
