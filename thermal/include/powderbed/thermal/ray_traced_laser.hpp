#pragma once
// Ray-traced laser absorption on the bed's own spheres (after Boley, King & Khairallah 2015,
// Appl. Opt. 54:2477): rays drawn from the Gaussian beam profile (1/e^2 radius w) enter from
// above, vertically; at every hit, on a sphere, on the substrate's top face or on the wall of
// its vapour depression (vapour_depression.hpp) or on a part raised over the plate, the surface absorbs the fraction A of what the
// ray carries (SurfaceOptics: a constant per phase, or Fresnel's A(θ) of the metal's complex
// index at the angle of incidence) and the rest is reflected (Reflection: specularly, diffusely
// with Lambert's law, or by the solid top face's roughness) until the ray leaves upward, falls
// outside the substrate's extent, or carries
// less than `cutoff` of its start power. The substrate's surface is a height per column (the
// solid's top less the depression), bilinear between columns; a ray below its highest point
// marches in steps of half a grid spacing, the hit refined by bisection, and meets the spheres
// there as above. Every watt is booked: absorbed by
// particles + absorbed by the substrate + escaped upward + outside + dropped = incident, to
// round-off.
//
// Rays: ray k of N carries P/N and starts at radius w sqrt(-ln(1 - u_k)/2) and angle 2π v_k
// from the axis, u_k = (k + ξ)/N and v_k = frac(k φ + ζ) (φ the golden ratio; ξ, ζ drawn per
// trace): the radius follows the Gaussian's radial distribution exactly and the angles a
// low-discrepancy (Fibonacci) sequence. The maps converge about as N^-0.7 (measured:
// test_ray_traced_laser.cpp), faster than Monte Carlo's N^-0.5; not as 1/N, since the power a
// sphere takes jumps at its outline.
// Trace k of a run draws from the stream (seed, k) and its rays are split into fixed chunks
// summed in chunk order, so a map is the same for any number of threads.
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "powderbed/bed/option_words.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

// How reflected light leaves a hit: `specular` and `diffuse` (Lambert) on every surface;
// `rough`: the solid top face (the plate, earlier layers) keeps the specular share of its rms
// roughness (rough_reflection.hpp) and scatters the rest by Lambert's law, while particles
// (gas-atomised spheres, smooth to the beam as in Boley et al. 2015) and molten surfaces
// (smoothed by surface tension) are mirrors.
enum class Reflection { specular, diffuse, rough };
inline constexpr bed::OptionWord<Reflection> kReflectionWords[] = {
    {"specular", Reflection::specular}, {"diffuse", Reflection::diffuse}, {"rough", Reflection::rough}};

// How a surface absorbs: `constant`, one absorptivity per phase; `fresnel`, the Fresnel
// absorptance (fresnel_absorptance.hpp) of the phase's complex refractive index at the angle
// of incidence.
enum class Optics { constant, fresnel };
inline constexpr bed::OptionWord<Optics> kOpticsWords[] = {{"fresnel", Optics::fresnel},
                                                          {"constant", Optics::constant}};
struct SurfaceOptics {
  Optics model = Optics::constant;
  double alpha[2] = {0.33, 0.33};  // constant: solid, liquid
  std::complex<double> index[2] = {{3.235, 4.322}, {3.235, 4.322}};  // fresnel: solid, liquid (316L)
  // Absorbed fraction at a hit on a surface of phase `liquid` (0 or 1), cos θ = `cos_incidence`.
  double absorptance(unsigned liquid, double cos_incidence) const;
};

// The surfaces as one trace sees them: each particle's and each column's phase (0 solid, 1
// liquid; columns i + nx j, their top nodes), and the substrate's surface per column: the
// solid's top `rise` above the plate's top face (the part a build grew; empty: flat) less the
// depression's depth below that top (empty: none). The tracer's top plane is the surface's
// highest point; under it, rays march to the surface and still meet the spheres.
struct TraceSurfaces {
  std::vector<std::uint8_t> particle_phase, node_phase;
  std::vector<double> rise, depression;
};

struct RayTraceParams {
  std::size_t rays = 4000;        // rays per traced beam position
  double cutoff = 1e-4;           // a ray carrying less than this fraction of its power is dropped
  Reflection reflection = Reflection::rough;
  double roughness = 1e-6;        // rough: rms height σ of the solid top face, m (a ground plate)
  double wavelength = 1.07e-6;    // rough: the laser's vacuum wavelength, m (Yb fibre laser)
  std::uint64_t seed = 1;
  int max_bounces = 1000;         // a ray still bouncing after this many hits is dropped
};

// The beam's power split over the bed for one beam position, as fractions of the beam power.
struct AbsorptionMap {
  struct Entry {
    std::uint32_t target;  // particle index, or column index (i + nx j)
    double fraction;
  };
  std::vector<Entry> particles, nodes;  // sorted by target, fractions > 0
  double absorbed_particles = 0, absorbed_substrate = 0;
  double escaped = 0;   // left upward
  double outside = 0;   // reached the substrate plane beyond its x-y extent
  double dropped = 0;   // below the cutoff, or after max_bounces
  double hits = 0;      // mean number of surface hits per ray
  double absorbed_depression = 0;  // of absorbed_substrate: on the depression's walls
  double absorptance() const { return absorbed_particles + absorbed_substrate; }
};

// Throws InputError naming laser.rays or laser.ray-cutoff for rays = 0 or a cutoff outside
// (0, 1).
void validate(const RayTraceParams& params);

class BeamTracer {
 public:
  // The bed (kept by copy) over the substrate `g`. Throws as validate(params) does.
  BeamTracer(const bed::Bed& bed, const SubstrateGeometry& g, double spot_radius,
             const RayTraceParams& params, const SurfaceOptics& optics);
  ~BeamTracer();
  BeamTracer(const BeamTracer&) = delete;
  BeamTracer& operator=(const BeamTracer&) = delete;

  // The particles as they are now (arrays by the caller's index): those `gone` (vaporised, or
  // merged into the pool or another drop) leave the scene and rays pass where they were; the
  // rest take their present heights and radii (a coalesced drop has grown).
  void update(const std::vector<std::uint8_t>& gone, const std::vector<double>& z,
              const std::vector<double>& radius);

  // Traces the beam centred at (x, y) over `surfaces` (a hit between top nodes takes the
  // nearest node's phase). `trace` numbers the random stream. Power absorbed on the top face
  // or a depression's wall is booked on the columns around the hit (on their top nodes).
  AbsorptionMap trace(double x, double y, std::uint64_t trace, const TraceSurfaces& surfaces) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace powderbed::thermal
