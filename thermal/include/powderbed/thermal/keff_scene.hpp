#pragma once
// What an effective-conductivity scene specifies (SPEC.md §6): the walls, the solid and gas
// conductivities and the heat paths switched on. Radiation is not part of this network yet
// (docs/keff.md), so a scene cannot ask for it.
#include "powderbed/thermal/keff_gas_lens.hpp"
#include "powderbed/thermal/keff_paths.hpp"

namespace powderbed::thermal {

// constant: k_g as given; air: the [KE] polynomial at the mean wall temperature.
enum class GasModel { constant, air };

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
  bool contact_path = true, gas_path = true;

  // k_g of the (linear) network: the constant, or the air polynomial at the mean wall temperature.
  double gas_conductivity_used() const;
  // Throws InputError naming the field, the value and the accepted range.
  void validate() const;
};

}  // namespace powderbed::thermal
