#include "powderbed/thermal/explain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/evaporation.hpp"
#include "powderbed/thermal/fresnel_absorptance.hpp"
#include "powderbed/thermal/surface_losses.hpp"
#include "powderbed/thermal/wetting.hpp"

namespace powderbed::thermal {

namespace {

constexpr double kMatters = 1e-3;  // below this fraction of the laser flux a path is negligible

std::string verdict(double ratio, bool on) {
  const bool matters = ratio >= kMatters;
  if (matters) return on ? "matters (on)" : "MATTERS but is off: switch it on";
  return on ? "negligible: switching it off saves time" : "negligible (off)";
}

// A heat path's verdict over the whole run: `heating`, its flux over the laser's under the beam;
// `cooling`, the heat it carries off a lit particle in the cooling after the beam up to the run's
// end (ExplainReport). Small under the beam is not enough to switch it off: after the beam has
// passed, contacts and losses are what cool the track.
std::string path_verdict(double heating, double cooling, bool on) {
  if (heating >= kMatters) return verdict(heating, on);
  if (cooling >= kMatters) {
    return on ? "negligible under the beam; it sets the cooling after (keep it on)"
              : "negligible under the beam but sets the cooling after: switch it on";
  }
  return on ? "negligible under the beam and in the cooling after: switching it off saves time"
            : "negligible (off)";
}

// The mean of f(i) over the particles with contacts of this kind (`shape`: Σ A/L per particle).
template <class F>
double mean_over_connected(const bed::Bed& bed, const std::vector<double>& shape, F&& f) {
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (shape[i] <= 0) continue;
    sum += f(i);
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

// Conduction through this bed's contacts over the laser flux, k Σ shape (T_m - T0) per projected
// area (`dt`: T_m - T0), and what they carry off a particle over `t_cool`, t_cool k Σ shape /
// (m c) (`rho_c`: rho c), each the mean over the particles that have such contacts.
void contact_ratios(const bed::Bed& bed, const std::vector<double>& shape, double k, double dt,
                    double laser_flux, double rho_c, double t_cool, double& heating,
                    double& cooling) {
  heating = mean_over_connected(bed, shape, [&](std::size_t i) {
    return k * shape[i] * dt / (M_PI * bed.radius[i] * bed.radius[i]) / laser_flux;
  });
  cooling = mean_over_connected(bed, shape, [&](std::size_t i) {
    const double r = bed.radius[i];
    return t_cool * k * shape[i] / (rho_c * bed::sphere_volume(r));
  });
}

// The conduction ratios: [GZ]'s scale estimate and this bed's particle pairs and floor contacts;
// contact circles of a settled bed are small (a/r ~ 1e-2), so these are far below the estimate.
void conduction_ratios(const bed::Bed& bed, const Sinter& sinter, double k, double dt,
                       double r_mean, double rho_c, ExplainReport& r) {
  const std::size_t n = bed.n();
  std::vector<double> pair_shape(n, 0.0), floor_shape(n, 0.0);
  for (const auto& p : sinter.network().pairs) {
    pair_shape[p.i] += p.shape;
    pair_shape[p.j] += p.shape;
  }
  for (const auto& c : sinter.network().substrate) floor_shape[c.particle] += c.shape;
  r.conduction_scale = n > 0 ? k * dt / (2 * r_mean) / r.laser_flux : 0.0;
  contact_ratios(bed, pair_shape, k, dt, r.laser_flux, rho_c, r.cooling_time, r.conduction_ratio,
                 r.conduction_cooling);
  contact_ratios(bed, floor_shape, k, dt, r.laser_flux, rho_c, r.cooling_time, r.substrate_ratio,
                 r.substrate_cooling);
}

// The regime by King et al.'s normalised enthalpy, and evaporation at T_b over the laser.
void regime_numbers(const SinterScene& scene, const Material& m, ExplainReport& r) {
  const PhaseChange& pc = m.phase_change();
  const KingRegime king = king_regime(scene, m);
  r.normalised_enthalpy = king.normalised_enthalpy;
  r.keyhole_threshold = king.keyhole_threshold;
  // The scene's L_v: the material's curve holds none when evaporation carries it.
  const double latent = scene.phase_change.latent_vapour;
  const EvaporationParams vapour{pc.boiling_point, latent, scene.molar_mass,
                                 scene.ambient_pressure, scene.back_condensation};
  r.evaporation_ratio = latent * evaporation_mass_flux(vapour, pc.boiling_point) / r.laser_flux;
}

// The scale analysis's numbers (all but the text).
ExplainReport scale_numbers(const bed::Bed& bed, const SinterScene& scene, const Sinter& sinter) {
  ExplainReport r;
  const Material& m = sinter.material();
  const PhaseChange& pc = m.phase_change();
  const double t0 = scene.initial_temperature, t_m = pc.melting_point, t_v = pc.boiling_point;
  const double k = m.conductivity(t_m - pc.window);
  r.laser_flux =
      absorbed_flux({scene.power, scene.spot_radius, scene.absorptivity, 0.0}, 0.0, 0.0);
  const std::size_t n = bed.n();
  double r_mean = 0;
  for (const double radius : bed.radius) r_mean += radius / static_cast<double>(n > 0 ? n : 1);
  const double c_mean = m.solid_specific_heat(0.5 * (t0 + t_m));
  const double rho_c = m.density(t0) * c_mean;
  r.dwell_time = scene.spot_radius / scene.speed;
  r.cooling_time = std::max(0.0, sinter.t_end() - r.dwell_time);
  conduction_ratios(bed, sinter, k, t_m - t0, r_mean, rho_c, r);
  // The losses per unit area of a surface at the boiling point (surface_losses.hpp), and what
  // they take off a mean particle's projected area over the cooling, per the heat it holds at T_m.
  const SurfaceParams surface{scene.convection, scene.emissivity, scene.environment_temperature};
  r.convection_ratio = -convection_gain(surface, t_v, 1.0) / r.laser_flux;
  r.radiation_ratio = -radiation_gain(surface, t_v, 1.0) / r.laser_flux;
  const double held_area = rho_c * 4.0 / 3.0 * r_mean * (t_m - t0);  // per projected area, J/m^2
  if (held_area > 0) {
    r.convection_cooling = r.convection_ratio * r.laser_flux * r.cooling_time / held_area;
    r.radiation_cooling = r.radiation_ratio * r.laser_flux * r.cooling_time / held_area;
  }
  const double h_surface = scene.convection + radiation_conductance(surface, t_v, 1.0);
  r.biot_surface = h_surface * r_mean / 3 / k;
  r.biot_laser = r.laser_flux * r_mean / 3 / (k * (t_m - t0));
  r.optical_thickness = sinter.extinction() * sinter.surface().layer_height;
  r.heating_time = m.density(t0) * 4.0 / 3.0 * r_mean * c_mean * (t_m - t0) / r.laser_flux;
  const auto& grid = sinter.grid();
  r.absorptance = sinter.absorptance_at(grid.x0 + 0.5 * static_cast<double>(grid.nx - 1) * grid.dx);
  const SpreadCap cap = spherical_cap(bed::sphere_volume(r_mean),
                                      scene.contact_angle * M_PI / 180);
  r.wetting_time = m.density(t0) * bed::sphere_volume(r_mean) * c_mean /
                   (k * conduction_shape_factor(cap.base_radius, cap.centroid_height));
  // Particles that melt with wetting on bridge their molten neighbours (wetting.hpp): after the
  // beam those pairs conduct through necks of the smaller radius, [GZ]'s full-section scale
  // (A/L = π r² / 2r), not through the settled contacts, and a frozen bridge stays.
  r.bridged = scene.has(kWetting) && n > 0 && r.heating_time < r.dwell_time;
  if (r.bridged) {
    const double neck_shape = M_PI * r_mean / 2;
    const double held = rho_c * bed::sphere_volume(r_mean);  // J/K
    r.conduction_cooling = std::max(r.conduction_cooling, r.cooling_time * k * neck_shape / held);
    // and those on the substrate spread into caps, whose time constant is the wetting time.
    if (!sinter.network().substrate.empty() && r.wetting_time > 0)
      r.substrate_cooling = std::max(r.substrate_cooling, r.cooling_time / r.wetting_time);
  }
  regime_numbers(scene, m, r);
  return r;
}

// The printed report: one row per number with its verdict, then the time steps.
std::string report_text(const ExplainReport& r, const SinterScene& scene, const Sinter& sinter,
                        bool wetting_matters) {
  std::ostringstream out;
  char line[200];
  const auto row = [&](const char* name, double value, const std::string& note) {
    std::snprintf(line, sizeof line, "  %-34s %10.3g   %s\n", name, value, note.c_str());
    out << line;
  };
  out << "Scale analysis of the scene (Ganeriwala & Zohdi 2016 [GZ]: conduction ~1e-1,\n"
         "convection ~1e-5, radiation ~1e-4 of the laser flux during heating). A path is\n"
         "negligible only when it is so under the beam and in the cooling after it, to the run's end.\n";
  row("absorbed laser flux alpha I0 (W/m^2)", r.laser_flux, "");
  row("convection / laser", r.convection_ratio,
      path_verdict(r.convection_ratio, r.convection_cooling, scene.has(kConvection)));
  row("radiation / laser", r.radiation_ratio,
      path_verdict(r.radiation_ratio, r.radiation_cooling, scene.has(kRadiation)));
  row("laser dwell time w/v (s)", r.dwell_time, "");
  row("cooling time t_end - w/v (s)", r.cooling_time,
      "the longest a lit particle cools after the beam, to the run's end");
  row("convection: cooling / heat at T_m", r.convection_cooling, "");
  row("radiation: cooling / heat at T_m", r.radiation_cooling, "");
  row(scene.absorption == LaserAbsorption::ray_trace ? "absorptance (ray-trace)"
                                                      : "absorptance (beer-lambert)",
      r.absorptance,
      "316L near 1 um: flat ~0.3-0.35, powder layer ~0.6-0.7 (Boley et al. 2015; Trapp et al. "
      "2017)");
  // A bare plate has no particle rows (their numbers would be 0/0).
  if (sinter.particle_temperature().empty()) {
    out << "  (no particles: a bare plate; the particle rows do not apply)\n";
  } else {
    row("conduction scale k dT / D / laser", r.conduction_scale,
        "[GZ]'s estimate: as if particles touched over their whole section");
    row("conduction (particle pairs) / laser", r.conduction_ratio,
        path_verdict(r.conduction_ratio, r.conduction_cooling, scene.has(kConduction)));
    row("  in the cooling / heat at T_m", r.conduction_cooling,
        r.bridged ? "molten particles bridge (wetting): necks of the smaller radius conduct"
                  : "through this bed's contacts");
    row("conduction (to substrate) / laser", r.substrate_ratio,
        path_verdict(r.substrate_ratio, r.substrate_cooling, scene.has(kSubstrateContact)));
    row("  in the cooling / heat at T_m", r.substrate_cooling,
        r.bridged ? "molten particles spread on it (wetting): t_cool / wetting time"
                  : "through this bed's contacts");
    row("Biot number of surface losses", r.biot_surface,
        r.biot_surface < 0.1 ? "< 0.1: lumped particle temperatures are sound"
                             : ">= 0.1: lumped temperatures are questionable");
    row("Biot number of the laser flux", r.biot_laser,
        r.biot_laser < 0.1 ? "< 0.1: lumped heating is sound"
                           : ">= 0.1: a lit particle is hotter on top than the lumped value");
    row("optical thickness beta H_layer", r.optical_thickness,
        "laser reaching the substrate: exp(-beta H) = " +
            std::to_string(std::exp(-r.optical_thickness)));
    row("time to heat a mean particle to T_m (s)", r.heating_time,
        r.heating_time < r.dwell_time ? "shorter than the dwell: lit particles melt"
                                      : "longer than the dwell: particles may not melt");
    row("wetting time m c / (k pi a^2 / z_c) (s)", r.wetting_time,
        std::string(wetting_matters ? "shorter than the dwell, particles melt: wetting matters"
                                    : "particles do not melt or touch the substrate: negligible") +
            (scene.has(kWetting) ? " (on)" : wetting_matters ? " but is OFF" : " (off)"));
  }
  const auto on = [&](unsigned effect) { return scene.has(effect) ? " (on)" : " but is OFF"; };
  const bool keyhole = r.normalised_enthalpy > r.keyhole_threshold;
  row("normalised enthalpy dH/h_s (King 2014)", r.normalised_enthalpy,
      keyhole ? std::string("above pi T_b/T_m: keyhole regime, the depression matters") +
                    on(kDepression)
              : r.normalised_enthalpy > 0.5 * r.keyhole_threshold
                    ? std::string("transition: the surface nears T_b, the depression may open") +
                          on(kDepression)
                    : std::string("conduction regime"));
  row("keyhole threshold pi T_b / T_m", r.keyhole_threshold, "");
  row("evaporation at T_b / laser", r.evaporation_ratio,
      r.normalised_enthalpy > 0.5 * r.keyhole_threshold
          ? std::string("the surface reaches T_b: evaporation bounds it") + on(kEvaporation)
          : verdict(r.evaporation_ratio, scene.has(kEvaporation)));
  row("phase change window (K)", sinter.material().phase_change().window,
      scene.has(kPhaseChange) ? "phase change on" : "phase change OFF: no latent heat");
  out << "Time steps: grid bound " << sinter.stable_steps().grid << " s, particle bound "
      << sinter.stable_steps().particle << " s, run step " << sinter.dt() << " s with "
      << sinter.substeps() << " particle step(s) per grid step.\n";
  return out.str();
}

}  // namespace

KingRegime king_regime(const SinterScene& scene, const Material& m) {
  const PhaseChange& pc = m.phase_change();
  const double t0 = scene.initial_temperature, t_m = pc.melting_point;
  const double t_mid = 0.5 * (t0 + t_m);
  const double rho_c = m.density(t_mid) * m.solid_specific_heat(t_mid);
  const double diffusivity = m.solid_conductivity(t_mid) / rho_c;
  const double flat = scene.absorption == LaserAbsorption::ray_trace && scene.optics == Optics::fresnel
                          ? fresnel_absorptance({scene.index_n_solid, scene.index_k_solid}, 1.0)
                          : scene.absorptivity;
  const double w = scene.spot_radius;
  return {flat * scene.power / (M_PI * rho_c * t_m * std::sqrt(diffusivity * scene.speed * w * w * w)),
          M_PI * pc.boiling_point / t_m};
}

ExplainReport explain(const bed::Bed& bed, const SinterScene& scene, const Sinter& sinter) {
  ExplainReport r = scale_numbers(bed, scene, sinter);
  const bool particles_melt = r.heating_time < r.dwell_time;
  const bool wetting_matters = bed.n() > 0 && !sinter.network().substrate.empty() &&
                               particles_melt && r.wetting_time < r.dwell_time;
  r.text = report_text(r, scene, sinter, wetting_matters);
  return r;
}

}  // namespace powderbed::thermal
