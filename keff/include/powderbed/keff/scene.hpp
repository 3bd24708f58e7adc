#pragma once
// What an effective-conductivity scene specifies (docs/physics.md §6): the walls, the solid and gas
// conductivities, the grey-body radiation settings and the heat paths switched on.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "powderbed/bed/bed.hpp"

#include "powderbed/keff/gas_lens.hpp"
#include "powderbed/keff/paths.hpp"
#include "powderbed/bed/option_words.hpp"

namespace powderbed::keff {

// constant: k_g as given; air: the [KE] polynomial of docs/physics.md §6, each gas link at the mean
// temperature of its two ends (the network is then nonlinear and solved by Newton).
enum class GasModel { constant, air };
inline constexpr bed::OptionWord<GasModel> kGasModelWords[] = {{"constant", GasModel::constant},
                                                              {"air", GasModel::air}};

// pair: docs/physics.md §6's formula, one link per pair carrying both surface resistances; radiosity:
// the grey enclosure's network, one radiosity node per surface (radiation.hpp).
enum class RadiationModel { pair, radiosity };
inline constexpr bed::OptionWord<RadiationModel> kRadiationModelWords[] = {
    {"pair", RadiationModel::pair}, {"radiosity", RadiationModel::radiosity}};

// What the command line or scene says about how the bed was made; each given value must agree
// with the bed's provenance (bed::ContactProvenance). `young` is different: the particles'
// modulus E' at which the correction reads the packing (default: the bed's E).
struct ContactOptions {
  std::optional<std::string> law;
  std::optional<double> young_scale, stiffness, young;
};

// The Hertz correction's constants from the bed's record of its DEM run. Throws InputError (one
// line) when the correction is asked for and the bed records no contact law, when an option
// contradicts the record, for an unknown law, k_n <= 0, S <= 0 or E' <= 0.
ContactRadiusParams contact_radius_params(const bed::ContactProvenance& made,
                                          bool hertz_correction, const ContactOptions& given);

struct KeffScene {
  // The hot wall is the upper face of `axis` (domain.upper), the cold wall the lower face.
  int axis = 2;
  double hot_temperature = 305, cold_temperature = 295;  // K
  double solid_conductivity = 16.2;  // k_s, W/mK (316L at room temperature)
  GasModel gas_model = GasModel::constant;
  double gas_conductivity = 0.026;   // k_g, W/mK (air at 300 K), used when gas_model = constant
  double calibration = 1;            // A_c: scales the contact radius (metals: 1)
  ContactRadiusParams contact;
  GasLensParams lens;
  bool contact_path = true, gas_path = true, radiation_path = false;
  // Grey opaque spheres and walls (docs/physics.md §6): one emissivity for every particle, one for both
  // walls; view factors from `rays` Monte-Carlo rays per particle, random streams from `seed`.
  double emissivity = 0.5, wall_emissivity = 0.5;
  // 100: the cheapest count whose k_eff is within 1 % of 1e5 rays' (docs/results/keff-accuracy.md).
  std::size_t rays = 100;
  std::uint64_t seed = 1;
  RadiationModel radiation_model = RadiationModel::pair;
  // Newton stops at ‖R‖ / ‖Σ|q|‖ ≤ newton_tolerance: each particle's net heat flow against the
  // flows it balances (solve.cpp); docs/results/keff-accuracy.md measures what it costs.
  double newton_tolerance = 1e-10;

  // k_g of the linear start (and of every gas link when gas_model = constant): the constant, or
  // the air polynomial at the mean wall temperature.
  double gas_conductivity_used() const;
  // Throws InputError naming the field, the value and the accepted range.
  void validate() const;
};

}  // namespace powderbed::keff
