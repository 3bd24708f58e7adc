#pragma once
// The sinter run file (HDF5 time series + XDMF for ParaView):
//   /                      attrs format = "powderbed.sinter-run", version = 1, created_by,
//                          command_line; /provenance attr scene (the resolved configuration)
//   /particles             position N×3, radius N, id N
//   /substrate             attrs origin (x0, y0, z_top), spacing (dx, dy, dz), nodes (nx, ny, nz)
//   /steps/<k>             k: the step in 12 digits (lexical order = time order);
//                          attrs time, step; particle_temperature N, particle_phase N (0 solid,
//                          1 liquid, 2 gas), section_y nz×nx (substrate T on y = Ly/2),
//                          top ny×nx (substrate T on the top face), substrate nz×ny×nx
//                          (float32, only with full fields)
//   /melt                  peak temperatures: particle N, section_x nz×ny (x = Lx/2),
//                          section_y nz×nx, top ny×nx; attrs height, width, depth, x_plane,
//                          melting_point
//   /tracks                per scan segment (M of them): width, depth, height, length (m),
//                          peak_temperature, start_temperature (K), stored_energy (J),
//                          particles_molten, t_start, t_end (s), each M
//   /fusion                (sinter --fuse) top_height ny×nx (the solid's top z per top-face
//                          column, m), height ny×nx (above the plate), surface ny×nx×3 (the
//                          columns' x, y, top z: the XDMF grid "solid_top"), state N (0
//                          powder, 1 fused, 2 vaporised); attrs
//                          threshold (K), fused, vaporised, powder_mass_before/after,
//                          solid_mass_before/after (above the plate's top face), vaporised_mass
//                          (kg), mass_error
//   /fusion/lack_of_fusion ny×nx (build: per top-face column 0 not scanned, 1 bonded to the
//                          solid below, 2 lack of fusion; lack_of_fusion.hpp); attrs
//                          lack_of_fusion_fraction, scanned_columns, unbonded_columns
//   /part                  (build) the part so far (part_porosity.hpp): attrs layers, nx, ny,
//                          x0, y0, dx, dy, dz, z_top, porosity, core_columns; top ny×nx (m),
//                          scanned ny×nx (layers whose scan covered each column),
//                          never_molten M×3 (column, lo, hi: never-molten solid, m),
//                          solid_fraction and never_molten_fraction nk×ny×nx (cells of dz
//                          from the plate's top: the XDMF grid "part", cell data)
//   /summary               attrs: the numbers `sinter --json` prints
//   /xdmf/polyvertex       0..N-1, the particles' Polyvertex cells for ParaView
// Every dataset has its SI unit as the attribute `units` (K, m; "1" without unit).
// Arrays are row-major with x fastest. Written under a temporary name, renamed by finish().
#include <memory>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/lack_of_fusion.hpp"
#include "powderbed/thermal/part_porosity.hpp"
#include "powderbed/thermal/solver.hpp"

namespace powderbed::thermal {

class RunWriter {
 public:
  RunWriter(const std::string& path, const bed::Bed& bed, const Sinter& sinter,
            bool full_fields);
  ~RunWriter();
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  void snapshot(const Sinter& sinter);
  // Writes /fusion (before finish).
  void fusion(const Fusion& fused);
  // Writes /fusion/lack_of_fusion (after fusion, before finish).
  void lack_of_fusion(const LackOfFusion& lof);
  // Writes /part (build: after the layer's fusion, before finish).
  void part(const PartRecord& record);
  // Writes /melt and /summary (name -> value), commits the file and its .xmf sidecar.
  void finish(const Sinter& sinter, const SinterResult& result,
              const std::vector<std::pair<std::string, double>>& summary);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace powderbed::thermal
