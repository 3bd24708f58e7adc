#pragma once
// build's process map (docs/build.md "Process maps"): a patch built at each point of a power ×
// speed (× hatch) grid, each point judged on published criteria and on the porosity its own
// part came out with:
//
//   keyhole         ΔH/h_s > π T_b / T_m (King et al. 2014, J. Mater. Process. Technol. 214:
//                   the normalised enthalpy of sinter --explain), or the last layer's pools
//                   W / D <= 1.5 (Johnson et al. 2019, Acta Mater. 176), D their depth below the
//                   solid's top, which the vapour depression deepens where the scene has it
//   lack of fusion  the porosity of the part's interior (thermal/part_porosity.hpp: below the
//                   top the layer before the last left, as a measured density is) at or above 1 %, the
//                   density (99 %) the measured series of data/validation/part-density/ cross
//                   from dense to lack of fusion; beside it Tang, Pistorius & Beuth's
//                   (h/W)^2 + (t/D_t)^2 (Addit. Manuf. 14, 2017), D_t = t + D the pools' depth
//                   from the top of the new layer, is reported, not used
//   balling         a track of the last layer whose melt did not reach the solid (D = 0) and
//                   stayed molten over more than π times its width (Plateau–Rayleigh: a free
//                   liquid cylinder longer than π W breaks up; Yadroitsev et al. 2010, J. Mater.
//                   Process. Technol. 210)
//   dense           none of these
#include <string>
#include <vector>

#include "powderbed/bed/json.hpp"

namespace powderbed::app {

struct MapPoint {
  double power = 0, speed = 0, hatch = 0, layer = 0;  // W, m/s, m, m (the plate's drop)
  std::string folder;                                 // the point's layer files, in --out
  double porosity = 0;                                // the part's interior, after the last layer
  double whole_porosity = 0;                          // the part's to its final top
  double lack_of_fusion = 0;                          // the last layer's unbonded area fraction
  double remelt_mean = 0;                             // m, the last layer's
  double width = 0, depth = 0;                        // m, the last layer's mean pool
  double normalised_enthalpy = 0, keyhole_threshold = 0;
  std::size_t balling_tracks = 0, tracks = 0;         // of the last layer
  double layer_density = 0;                           // the last layer's
  double wall_time = 0;                               // s
  // P / (v h t), J/m^3.
  double energy_density() const { return power / (speed * hatch * layer); }
  // Tang et al.'s (h/W)^2 + (t/(t + D))^2 (infinite without a pool).
  double tang() const;
  // The regions the point falls in (keyhole, lack of fusion, balling), or {"dense"}.
  std::vector<std::string> regions() const;
};

// The porosity at and above which a point lacks fusion (a 99 % dense part).
inline constexpr double kDensePorosity = 0.01;

// map.json: the grid's points with their measures and regions, and the units of the numbers.
void write_map_json(bed::JsonWriter& j, const std::vector<MapPoint>& points, double wall);

}  // namespace powderbed::app
