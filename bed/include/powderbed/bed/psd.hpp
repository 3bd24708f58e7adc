#pragma once
// Particle size distributions of docs/physics.md §1 and the PSD string syntax shared by all programs:
//   one or more components joined by '+', each
//     mono:d=D | mono:r=R
//     gauss:mean=M,sd=S,min=A,max=B[,on=radius|diameter]
//     lognormal:median=M,gsd=G[,min=A,max=B][,on=...]      (geometric sd G > 1)
//     lognormal:d10=A,d50=B,d90=C[,min=..,max=..]          (fitted lognormal, diameters)
//     table:file=PATH[,on=radius|diameter]                  (CSV: bin edges and fractions)
//   each optionally weighted by count=N (number of particles), frac=F (number fraction) or
//   vfrac=F (volume fraction). Parameters are diameters unless on=radius. SI units (m).
//   basis=number|volume on every kind says whether the sizes describe the number distribution or
//   the volume (mass) distribution, as laser diffraction reports it. Default: volume for
//   lognormal d10/d50/d90 (the values of powder data sheets), number for every other form. A
//   volume-basis lognormal is stored as its number-basis twin, ln d_n = ln d_v - 3 sigma^2
//   (Hatch & Choate 1929); a volume-basis table divides each bin's fraction by the bin's mean
//   d^3; a volume-basis gauss becomes a fine table (psd_parse.cpp); mono is the same on both.
//   Without weights the components get equal number fractions; count and frac/vfrac cannot be
//   mixed; frac and vfrac values are normalised over the components.
//   gauss: the mean may lie outside [min, max] (even <= 0: the window keeps sizes positive);
//   sd = 0 is a point mass at the mean, allowed when min <= mean <= max.
//   A lognormal without min/max is truncated at exp(mu -/+ 5 sigma) (5.7e-7 of its mass lies
//   outside), so that every PSD has a finite largest particle (cell lists are sized from it);
//   on the volume basis the window reaches 5 sigma beyond the volume median too.
//   d10/d50/d90: mu = ln d50 and sigma = ln(d90/d10) / (2 z90), z90 = Phi^-1(0.9) = 1.28155
//   (least squares on ln d10 = mu - z90 sigma, ln d90 = mu + z90 sigma with mu fixed by d50).
//   Components are split at a '+' followed by a letter (so 1e+6 stays a number); a table path
//   must therefore contain neither ',' nor '+' followed by a letter.
//   Table CSV: header line edge_low,edge_high,fraction then one bin per row (number fraction,
//   normalised; uniform within a bin); blank lines and lines starting with '#' are skipped.
#include <cstddef>
#include <string>
#include <vector>

#include "powderbed/bed/random.hpp"

namespace powderbed::bed {

enum class SizeVariable { radius, diameter };
enum class PsdBasis { number, volume };
const char* basis_name(PsdBasis basis);

struct PsdComponent {
  enum class Kind { mono, gauss, lognormal, table };
  Kind kind = Kind::mono;
  SizeVariable on = SizeVariable::diameter;  // the variable the parameters below describe
  PsdBasis basis = PsdBasis::number;  // the basis the user gave; the parameters below are by number
  double mean = 0;   // mono: the size; gauss: mean of the untruncated normal
  double sd = 0;     // gauss: sd of the untruncated normal
  double mu = 0;     // lognormal: mean of ln(size)
  double sigma = 0;  // lognormal: sd of ln(size)
  double min = 0;    // truncation window (gauss, lognormal), in `on` units
  double max = 0;
  std::vector<double> edges;      // table: bin edges, increasing, in `on` units
  std::vector<double> fractions;  // table: number fraction per bin (normalised)
  double number_fraction = 1;     // weight of this component, by number, normalised over the PSD
  std::size_t count = 0;          // count=N when given (0 otherwise)
};

class Psd {
 public:
  // Parses the PSD string syntax above. Throws InputError naming the component and field
  // (e.g. "--psd: component 1 (gauss): min 4e-05 > max 2e-05") for: unknown kind or key,
  // missing key, non-number, size <= 0, sd < 0, min > max, a window with no probability mass,
  // mixed count/frac weights, unreadable table file. `option` names the option in messages.
  static Psd parse(const std::string& spec, const std::string& option = "--psd");
  static Psd mono_radius(double radius);

  const std::vector<PsdComponent>& components() const { return components_; }
  const std::string& text() const { return text_; }

  // Draws one radius (m): picks a component by number fraction, then inverse-CDF sampling on
  // its truncated window (docs/physics.md §1). Uses 2 uniform draws.
  double sample_radius(Rng& rng) const;
  // Number-weighted CDF of the radius, for KS tests.
  double cdf_radius(double radius) const;
  double min_radius() const;
  double max_radius() const;
  double mean_radius() const;         // number mean, analytic (truncated moments)
  double mean_radius_squared() const; // E[r^2], analytic
  double mean_radius_cubed() const;   // E[r^3], analytic
  // Sum of count= weights, 0 when no component has one.
  std::size_t total_count() const;

 private:
  std::vector<PsdComponent> components_;
  std::string text_;
};

// One component on its own, in radius (m) whatever `on` says (the PSD's members are these
// mixed by number_fraction): E[r^k] for k = 1, 2, 3; P(R <= r); and the inverse CDF at
// u in [0, 1) (docs/physics.md §1), which is what sample_radius uses for its second draw.
double radius_moment(const PsdComponent& component, int k);
double cdf_radius(const PsdComponent& component, double radius);
double quantile_radius(const PsdComponent& component, double u);
// Probability mass of the untruncated gauss/lognormal inside [min, max] (1 for mono, table).
double window_mass(const PsdComponent& component);

// The q-quantile (0 < q < 1) of the diameters 2 r of `radii`, by number or by volume (each
// particle weighted by r^3): the smallest sampled diameter whose cumulative weight reaches q.
// 0 for no radii.
double sample_diameter_quantile(std::vector<double> radii, double q, PsdBasis basis);

// Kolmogorov–Smirnov distance sup |F_n(r) - F(r)| between sampled radii and the PSD.
double ks_distance(std::vector<double> radii, const Psd& psd);

}  // namespace powderbed::bed
