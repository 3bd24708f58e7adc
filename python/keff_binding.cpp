// keff in-process: keff::KeffScene as a Python class and the network's steady state on a bed
// dict (keff/include/powderbed/keff/scene.hpp, network.hpp, solve.hpp), as apps/keff.cpp runs it
// less its files and option words.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <cmath>
#include <tuple>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "gil_callback.hpp"
#include "struct_binding.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/keff/core_conductivity.hpp"
#include "powderbed/keff/network.hpp"
#include "powderbed/keff/scene.hpp"
#include "powderbed/keff/solve.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace {

void bind_keff_scene(py::module_& m) {
  using C = keff::ContactRadiusParams;
  StructBinding<C>(m, "ContactRadius",
                   "How keff takes a contact radius; the DEM law, moduli and softening of the "
                   "correction come from the bed's provenance (deposit and spread record them).")
      .field("hertz_correction", &C::hertz_correction,
             "contact radius from the equivalent Hertz overlap of a softened bed")
      .word("circle", &C::circle, keff::kContactCircleWords, "hertz | geometric")
      .done();
  using G = keff::GasLensParams;
  StructBinding<G>(m, "GasLens", "The gas path's lenses (keff/gas_lens.hpp).")
      .field("lens", &G::lens, "lens thickness over the particle radius")
      .field("min_gap", &G::min_gap, "l_min, m")
      .word("region", &G::region, keff::kLensRegionWords, "both-lenses | larger-lens")
      .done();
  using S = keff::KeffScene;
  StructBinding<S>(m, "KeffScene", "An effective-conductivity scene (keff::KeffScene).")
      .field("axis", &S::axis, "0, 1, 2: x, y, z; the hot wall is the upper face")
      .field("hot_temperature", &S::hot_temperature, "K")
      .field("cold_temperature", &S::cold_temperature, "K")
      .field("solid_conductivity", &S::solid_conductivity, "k_s, W/mK")
      .word("gas_model", &S::gas_model, keff::kGasModelWords, "constant | air")
      .field("gas_conductivity", &S::gas_conductivity, "k_g, W/mK (gas_model constant)")
      .field("calibration", &S::calibration, "A_c, scales the contact radius")
      .field("contact", &S::contact, "ContactRadius (or a dict of its fields)")
      .field("lens", &S::lens, "GasLens (or a dict of its fields)")
      .field("contact_path", &S::contact_path, "contact conduction on")
      .field("gas_path", &S::gas_path, "gas-gap conduction on")
      .field("radiation_path", &S::radiation_path, "radiation on")
      .field("emissivity", &S::emissivity, "of the particles")
      .field("wall_emissivity", &S::wall_emissivity, "of both walls")
      .field("rays", &S::rays, "Monte-Carlo rays per particle (view factors)")
      .field("seed", &S::seed, "random streams of the rays")
      .word("radiation_model", &S::radiation_model, keff::kRadiationModelWords, "pair | radiosity")
      .field("newton_tolerance", &S::newton_tolerance, "relative residual Newton stops at")
      .done();
}

py::dict result_dict(const keff::KeffResult& r, const keff::CoreConductivity& core) {
  py::dict d;
  d["k_eff"] = r.k_eff;
  d["heat_flow_hot"] = r.heat_flow_hot;
  d["heat_flow_cold"] = r.heat_flow_cold;
  d["share_contact"] = r.share_contact;
  d["share_gas"] = r.share_gas;
  d["share_radiation"] = r.share_radiation;
  d["k_core"] = core.k_core;
  d["drop_hot"] = core.drop_hot;
  d["drop_cold"] = core.drop_cold;
  d["rattlers"] = py::array_t<std::uint32_t>(static_cast<py::ssize_t>(r.rattlers.size()), r.rattlers.data());
  d["temperature"] = py::array_t<double>(static_cast<py::ssize_t>(r.temperature.size()), r.temperature.data());
  d["links"] = r.links;
  d["contact_links"] = r.contact_links;
  d["gas_links"] = r.gas_links;
  d["radiation_links"] = r.radiation_links;
  d["newton_iterations"] = r.newton_iterations;
  d["solver_iterations"] = r.solver_iterations;
  d["residual"] = r.residual;
  d["lost_rays"] = r.lost_rays;
  return d;
}

py::dict keff_of(const py::dict& bed_fields, keff::KeffScene scene, const py::object& progress) {
  const bed::Bed bed = bed_from_dict(bed_fields);
  // The correction's constants from the bed's record of its DEM run (apps/keff.cpp), the
  // circle as the scene chose it.
  const keff::ContactCircle circle = scene.contact.circle;
  scene.contact = keff::contact_radius_params(bed.provenance.contact, scene.contact.hertz_correction, {});
  scene.contact.circle = circle;
  scene.validate();
  std::function<void(double)> traced;
  if (given(progress)) {
    traced = [fn = py::handle(progress)](double fraction) {
      call_with_gil(fn, [=] { return std::make_tuple(fraction); });
    };
  }
  keff::KeffResult r;
  keff::CoreConductivity core;
  {
    py::gil_scoped_release release;
    const keff::KeffNetwork network = keff::build_keff_network(bed, scene, traced);
    r = keff::solve_keff(bed, scene, network);
    // As the program: no conducting path from wall to wall gives k_eff = 0, not a result.
    if (!(r.k_eff > 0) || !std::isfinite(r.k_eff))
      throw NumericalError(fmt::format("k_eff = {:g} W/mK: no heat path joins the two walls ({} of {} "
                                       "particles isolated)", r.k_eff, r.rattlers.size(), bed.n()));
    const double flux = (r.heat_flow_hot + r.heat_flow_cold) / 2 / network.wall_area;
    core = keff::core_conductivity(bed, scene.axis, r.temperature, r.rattlers, flux,
                                   scene.hot_temperature, scene.cold_temperature);
  }
  return result_dict(r, core);
}

}  // namespace

void bind_keff(py::module_& m) {
  bind_keff_scene(m);
  m.def("keff", &keff_of, py::arg("bed"), py::arg("scene"), py::arg("progress"));
}

}  // namespace powderbed::python
