// bedconv: converts a bed between the formats of docs/bed-format.md, chosen by extension:
// .h5 <-> .csv, .h5 -> .data (LAMMPS), .dump (LAMMPS/LIGGGHTS) -> .h5, any readable -> any writable.
#include <iostream>
#include <string>

#include "common/app_main.hpp"
#include "common/options.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"

namespace {

using powderbed::InputError;
namespace app = powderbed::app;
namespace bed = powderbed::bed;
namespace po = boost::program_options;

bool has_extension(const std::string& path, const std::string& ext) {
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

int convert(int argc, char** argv) {
  po::options_description desc("bedconv options");
  desc.add_options()(
      "in", po::value<std::string>()->required(),
      "input bed: .h5, .csv (x,y,z,r in m; needs --domain) or .dump (LAMMPS/LIGGGHTS text "
      "dump; the last snapshot)")(
      "out", po::value<std::string>()->required(),
      "output bed: .h5 (with an .xmf sidecar for ParaView), .csv or .data (LAMMPS, atom_style "
      "sphere)")("domain", po::value<std::string>(),
                 "domain of a CSV input, m: xlo,ylo,zlo,xhi,yhi,zhi (zlo = zhi = 0 makes it 2D)")(
      "density", po::value<double>(),
      ("particle density written to .data output, kg/m^3 (default " +
       std::to_string(static_cast<int>(bed::kDefaultLammpsDensity)) + ", 316L steel)")
          .c_str());
  app::add_common_options(desc);
  po::positional_options_description positional;
  positional.add("in", 1).add("out", 1);
  po::variables_map vm;
  if (!app::parse_options("bedconv", "bedconv IN OUT [--domain ...] [--density RHO]", desc,
                          positional, argc, argv, vm))
    return 0;

  const std::string in = vm["in"].as<std::string>();
  const std::string out = vm["out"].as<std::string>();
  const bool csv_in = has_extension(in, ".csv") || has_extension(in, ".CSV");
  const bool data_out = has_extension(out, ".data") || has_extension(out, ".DATA");
  if (vm.count("density") && !data_out)
    throw InputError("--density: only used for .data output (OUT is '" + out + "')");
  if (vm.count("density")) {
    const double rho = vm["density"].as<double>();
    if (!(rho > 0)) {
      throw InputError("--density: " + std::to_string(rho) + " (accepted: > 0 kg/m^3)");
    }
  }
  // Before any reading or writing (docs/hardening.md): the extensions, the input a file, the
  // output's folder writable and the output not the input.
  app::check_extension({"IN", in}, {".h5", ".csv", ".dump"});
  app::check_extension({"OUT", out}, {".h5", ".csv", ".data"});
  app::check_paths({{"IN", in}}, {{"OUT", out}});

  bed::Bed b;
  if (csv_in) {
    if (!vm.count("domain")) {
      throw InputError(in + ": CSV carries no domain; give --domain xlo,ylo,zlo,xhi,yhi,zhi (m)");
    }
    const bed::Domain domain = app::parse_domain_bounds(vm["domain"].as<std::string>(), "--domain");
    b = bed::read_bed_any(in, &domain);
  } else {
    if (vm.count("domain"))
      throw InputError("--domain: only for CSV input ('" + in + "' carries its own domain)");
    b = bed::read_bed_any(in);
  }

  b.provenance.created_by = app::version_string("bedconv");
  b.provenance.command_line = app::command_line(argc, argv);
  if (data_out) {
    bed::write_lammps_data(b, out, vm.count("density") ? vm["density"].as<double>()
                                                       : bed::kDefaultLammpsDensity);
  } else {
    bed::write_bed_any(b, out);
  }

  if (vm.count("json")) {
    bed::JsonWriter json;
    json.begin_object()
        .value("in", in)
        .value("out", out)
        .value("particles", static_cast<std::uint64_t>(b.n()))
        .value("dimension", b.domain.dimension)
        .end_object();
    std::cout << json.str() << '\n';
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("bedconv", argc, argv, [&] { return convert(argc, argv); });
}
