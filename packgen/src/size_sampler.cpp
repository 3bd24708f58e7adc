#include "powderbed/packgen/size_sampler.hpp"

#include <algorithm>
#include <cmath>

#include "powderbed/bed/errors.hpp"

namespace powderbed::packgen {

namespace {

// (sqrt 5 - 1) / 2: the most irrational step, whose partial sums leave the smallest gaps.
constexpr double kGolden = 0.6180339887498948482;

}  // namespace

SizeSampling parse_size_sampling(const std::string& text, const std::string& option) {
  if (text == "iid") return SizeSampling::iid;
  if (text == "stratified") return SizeSampling::stratified;
  throw InputError(option + ": '" + text + "' (accepted: iid or stratified)");
}

const char* size_sampling_name(SizeSampling s) {
  return s == SizeSampling::iid ? "iid" : "stratified";
}

SizeSampler::SizeSampler(const bed::Psd& psd, SizeSampling mode, bed::Rng& rng)
    : psd_(psd), mode_(mode) {
  if (mode_ == SizeSampling::stratified) u0_ = bed::uniform01(rng);
}

// size_sampler.hpp: iid = Psd::sample_radius; stratified = the golden-ratio sequence through
// the mixture's component bins and the component's inverse CDF.
double SizeSampler::next(bed::Rng& rng) {
  if (mode_ == SizeSampling::iid) return psd_.sample_radius(rng);
  const double t = u0_ + static_cast<double>(k_++) * kGolden;
  const double u = t - std::floor(t);
  const auto& components = psd_.components();
  double below = 0;
  std::size_t c = 0;
  while (c + 1 < components.size() && u >= below + components[c].number_fraction) {
    below += components[c].number_fraction;
    ++c;
  }
  // Rescaled into [0, 1) within the bin; the last bin absorbs the rounding of the fractions.
  const double f = components[c].number_fraction;
  const double v = f > 0 ? std::clamp((u - below) / f, 0.0, std::nextafter(1.0, 0.0)) : 0.0;
  return bed::quantile_radius(components[c], v);
}

}  // namespace powderbed::packgen
