#pragma once
// The sizes a packing run draws (docs/physics.md §1, §3: "each new particle gets a size from the PSD").
//   iid:        every size independent, Psd::sample_radius ([LP]'s rule, the default).
//   stratified: the k-th size comes from u_k = frac(u_0 + k g), g = (sqrt 5 - 1) / 2 (the
//               golden-ratio additive recurrence, a low-discrepancy sequence: every prefix of
//               N values covers [0, 1) with discrepancy O(log N / N), against ~0.9 / sqrt N for
//               iid draws), u_0 drawn once from the run's generator. Variance reduction: a bed of
//               a few hundred particles then honours the PSD histogram (KS ~ 0.005 at N = 500
//               instead of ~0.04), while each size still has the PSD's marginal law.
//               Mixtures: one u picks the component whose cumulative number-fraction bin
//               [F_{c-1}, F_c) holds it and is rescaled within the bin, (u - F_{c-1}) / f_c,
//               through that component's inverse CDF (bed::quantile_radius). Any interval of the
//               rescaled u is an interval of u, so both the component counts and every
//               component's sizes keep the sequence's O(log N / N) discrepancy.
#include <cstddef>
#include <string>

#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"

namespace powderbed::packgen {

enum class SizeSampling { iid, stratified };

SizeSampling parse_size_sampling(const std::string& text,
                                 const std::string& option = "--size-sampling");
const char* size_sampling_name(SizeSampling s);

class SizeSampler {
 public:
  // Stratified sampling draws u_0 from rng here (iid draws nothing until next()).
  SizeSampler(const bed::Psd& psd, SizeSampling mode, bed::Rng& rng);
  double next(bed::Rng& rng);  // the next radius (m)

 private:
  const bed::Psd& psd_;
  SizeSampling mode_;
  double u0_ = 0;
  std::size_t k_ = 0;
};

}  // namespace powderbed::packgen
