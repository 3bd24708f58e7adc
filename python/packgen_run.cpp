// packgen in-process: packgen::PackOptions as a Python class and packgen::pack on a domain and a
// PSD string with the GIL released, the bed dict and the summary (packgen's --json fields,
// summary_json.hpp) out, as apps/packgen.cpp runs it less its file.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <string>
#include <tuple>
#include <vector>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "gil_callback.hpp"
#include "json_dict.hpp"
#include "python_warning.hpp"
#include "struct_binding.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/summary_json.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace {

// The phases in packgen's --phases syntax (parse_phases reads it back): "0:0.3,1".
std::string phases_text(const std::vector<packgen::Phase>& phases) {
  std::string text;
  for (std::size_t k = 0; k < phases.size(); ++k) {
    text += (k ? "," : "") + std::to_string(phases[k].approach);
    if (k + 1 < phases.size()) text += fmt::format(":{}", phases[k].until_density);
  }
  return text;
}

void bind_pack_options(py::module_& m) {
  using O = packgen::PackOptions;
  StructBinding<O>(m, "PackOptions", "How packgen packs (packgen::PackOptions; its options, same names).")
      .property(
          "approach", [](const O& o) { return o.phases.back().approach; },
          [](O& o, int approach) { o.phases = {packgen::Phase{approach, 1.0}}; },
          "contacts per new particle: 0 random, 1, 2, 3 (3D only); sets one phase")
      .property(
          "phases", [](const O& o) { return phases_text(o.phases); },
          [](O& o, const std::string& text) { o.phases = packgen::parse_phases(text, "phases"); },
          "approach[:density],... e.g. '0:0.3,1' (replaces approach)")
      .word("collision", &O::collision, &packgen::parse_collision, &packgen::collision_name,
            "raster | grid | kdtree")
      .field("raster_spacing", &O::raster_spacing, "raster grid spacing h, m (raster only)")
      .field("tries", &O::tries, "n_T: tries per size before a new size is drawn")
      .field("directions", &O::directions,
             "K: directions per 1-contact try (None: 10 in 2D, 16 in 3D)")
      .field("count", &O::count, "stop at N particles (0: off)")
      .field("target_density", &O::target_density, "stop at this density, 0 < F < 1 (0: off)")
      .field("max_failures", &O::max_failures,
             "stop after M consecutive failed placements (None: the default rule)")
      .field("retire_after", &O::retire_after,
             "failed tries around a particle before it stops being a partner (0: never)")
      .field("edge_fraction", &O::edge_fraction, "fraction of 0-contact tries along the walls")
      .word("site_order", &O::site_order, &packgen::parse_site_order, &packgen::site_order_name,
            "lowest | random (3D approach 3)")
      .word("size_sampling", &O::size_sampling, &packgen::parse_size_sampling,
            &packgen::size_sampling_name, "iid | stratified")
      .field("floor_seed", &O::floor_seed,
             "site order lowest: fraction of the floor first covered at random, 0 <= F < 1")
      .field("allow_huge", &O::allow_huge,
             "accept a domain or count above 1e9 particles (else refused as a unit slip)")
      .done();
}

py::tuple pack(const py::object& domain, const std::string& psd_text, std::uint64_t seed,
               packgen::PackOptions options, const py::object& progress) {
  const bed::Domain box = domain_from_python(domain, "domain");
  const bed::Psd psd = bed::Psd::parse(psd_text, "psd");
  // As the program for any --count given: refused when it cannot fit at any size (the library
  // checks only counts whose reservation matters).
  if (options.count > 0) packgen::check_count_fits(box, psd, options.count);
  if (given(progress)) {
    options.progress = [fn = py::handle(progress)](const packgen::PackProgress& p) {
      call_with_gil(fn, [&p] {
        py::dict d;
        d["n"] = p.n;
        d["density"] = p.density;
        d["fraction"] = p.fraction_done;
        return std::make_tuple(d);
      });
    };
  }
  packgen::PackResult result;
  {
    py::gil_scoped_release release;
    result = packgen::pack(box, psd, options, seed);
  }
  result.bed.provenance.rng_seed = seed;
  result.bed.provenance.stage = "packgen";
  if (!result.target_reached) warn("packgen: " + packgen::unreached_warning(result, options));
  return py::make_tuple(bed_to_dict(result.bed), json_dict([&](bed::JsonWriter& j) {
                          packgen::write_pack_json(j, result, options, seed);
                        }));
}

}  // namespace

void bind_packgen(py::module_& m) {
  bind_pack_options(m);
  m.def("pack", &pack, py::arg("domain"), py::arg("psd"), py::arg("seed"), py::arg("options"),
        py::arg("progress"));
}

}  // namespace powderbed::python
