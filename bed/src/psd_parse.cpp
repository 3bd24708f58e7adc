// The PSD string syntax of psd.hpp (docs/physics.md §1): components, their keys, weights and the
// measured-table CSV, with one-line InputError messages naming component, kind and field.
#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"
#include "powderbed/bed/psd.hpp"

namespace powderbed::bed {

namespace {

// A lognormal without a window is truncated at mu -/+ this many sigma of ln(size) (psd.hpp).
constexpr double lognormal_default_window_sigmas = 5;
// Windows with less probability than this are refused: their truncated moments and inverse
// CDF would be dominated by underflow.
constexpr double min_window_mass = 1e-300;

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Whole string as a finite double (a leading '+' allowed); false otherwise.
bool to_number(const std::string& text, double& value) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && end == last && first != last && std::isfinite(value);
}

// Splits at '+' followed (after blanks) by a letter, i.e. the start of the next component's
// kind; a '+' inside a number (1e+6) is followed by a digit and stays.
std::vector<std::string> split_components(const std::string& spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i < spec.size(); ++i) {
    if (spec[i] != '+') continue;
    std::size_t next = i + 1;
    while (next < spec.size() && (spec[next] == ' ' || spec[next] == '\t')) ++next;
    if (next < spec.size() && std::isalpha(static_cast<unsigned char>(spec[next]))) {
      parts.push_back(spec.substr(start, i - start));
      start = i + 1;
    }
  }
  parts.push_back(spec.substr(start));
  return parts;
}

enum class Weight { none, count, frac, vfrac };

const char* weight_key(Weight w) {
  switch (w) {
    case Weight::count:
      return "count";
    case Weight::frac:
      return "frac";
    case Weight::vfrac:
      return "vfrac";
    case Weight::none:
      break;
  }
  return "none";
}

// One component being parsed: its keys and the context every message starts with.
class ComponentParser {
 public:
  ComponentParser(const std::string& option, std::size_t index, const std::string& text)
      : option_(option), index_(index) {
    const auto colon = text.find(':');
    kind_ = trim(colon == std::string::npos ? text : text.substr(0, colon));
    if (colon == std::string::npos) {
      fail("'" + trim(text) + "' is not kind:key=value,... (kinds: mono, gauss, lognormal, table)");
    }
    if (kind_ != "mono" && kind_ != "gauss" && kind_ != "lognormal" && kind_ != "table") {
      fail("unknown kind '" + kind_ + "' (accepted: mono, gauss, lognormal, table)");
    }
    std::stringstream fields(text.substr(colon + 1));
    std::string field;
    while (std::getline(fields, field, ',')) {
      field = trim(field);
      const auto eq = field.find('=');
      if (field.empty() || eq == std::string::npos) {
        fail("field '" + field + "' is not key=value");
      }
      const std::string key = trim(field.substr(0, eq));
      if (!values_.emplace(key, trim(field.substr(eq + 1))).second) {
        fail("key '" + key + "' given twice");
      }
    }
    if (!text.empty() && trim(text).back() == ',') fail("empty field after the last ','");
  }

  const std::string& kind() const { return kind_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: component {} ({}): {}", option_, index_, kind_, what));
  }

  // Refuses keys outside `accepted` (weights are accepted for every kind).
  void check_keys(const std::vector<std::string>& accepted) const {
    for (const auto& [key, value] : values_) {
      if (key == "count" || key == "frac" || key == "vfrac" || key == "basis") continue;
      if (std::find(accepted.begin(), accepted.end(), key) == accepted.end()) {
        std::string list;
        for (const auto& a : accepted) list += a + ", ";
        fail("unknown key '" + key + "' (accepted: " + list + "basis, count, frac, vfrac)");
      }
    }
  }

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  const std::string& text(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) fail("missing key '" + key + "'");
    return it->second;
  }

  double number(const std::string& key) const {
    double value = 0;
    if (!to_number(text(key), value)) {
      fail(key + " = '" + text(key) + "' is not a number");
    }
    return value;
  }
  // A size (diameter or radius): > 0.
  double size(const std::string& key) const {
    const double value = number(key);
    if (!(value > 0)) fail(key + " = " + text(key) + " is not a size (accepted: > 0)");
    return value;
  }

  SizeVariable on() const {
    if (!has("on")) return SizeVariable::diameter;
    if (text("on") == "diameter") return SizeVariable::diameter;
    if (text("on") == "radius") return SizeVariable::radius;
    fail("on = '" + text("on") + "' (accepted: radius, diameter)");
  }

  // basis=number|volume: what the size parameters describe (psd.hpp); `fallback` without it.
  PsdBasis basis(PsdBasis fallback) const {
    if (!has("basis")) return fallback;
    if (text("basis") == "number") return PsdBasis::number;
    if (text("basis") == "volume") return PsdBasis::volume;
    fail("basis = '" + text("basis") + "' (accepted: number, volume)");
  }

  // The weight key of this component, its value checked.
  Weight weight(double& value) const {
    const int given = int(has("count")) + int(has("frac")) + int(has("vfrac"));
    if (given > 1) fail("more than one of count, frac, vfrac (accepted: one)");
    if (has("count")) {
      if (!to_number(text("count"), value) || value < 1 || value != std::floor(value) ||
          value > 1e15) {
        fail("count = '" + text("count") + "' is not a positive integer");
      }
      return Weight::count;
    }
    for (const Weight w : {Weight::frac, Weight::vfrac}) {
      const std::string key = weight_key(w);
      if (!has(key)) continue;
      value = number(key);
      if (!(value > 0 && value <= 1))
        fail(key + " = " + text(key) + " (accepted: 0 < " + key + " <= 1)");
      return w;
    }
    return Weight::none;
  }

  void check_window(const PsdComponent& c) const {
    if (c.min > c.max) {
      fail(fmt::format("min {:g} > max {:g} (accepted: min <= max)", c.min, c.max));
    }
    const double mass = window_mass(c);
    if (!(mass >= min_window_mass)) {
      fail(fmt::format("window [{:g}, {:g}] has no probability mass (mass {:g} < 1e-300)", c.min,
                       c.max, mass));
    }
  }

 private:
  std::string option_;
  std::size_t index_;
  std::string kind_;
  std::map<std::string, std::string> values_;
};

PsdComponent parse_mono(const ComponentParser& p) {
  p.check_keys({"d", "r"});
  if (p.has("d") == p.has("r")) p.fail("give exactly one of d= (diameter) or r= (radius)");
  PsdComponent c;
  c.kind = PsdComponent::Kind::mono;
  c.on = p.has("d") ? SizeVariable::diameter : SizeVariable::radius;
  c.mean = c.min = c.max = p.size(p.has("d") ? "d" : "r");
  c.basis = p.basis(PsdBasis::number);  // one size: the same on either basis
  return c;
}

// Number fractions of table bins given by volume: a bin's number fraction is its volume fraction
// over its mean d^3 (r^3 alike) with sizes uniform by number within the bin,
// E[x^3] = (b^4 - a^4) / (4 (b - a)); normalised over the bins.
void volume_to_number_fractions(PsdComponent& c) {
  double sum = 0;
  for (std::size_t i = 0; i < c.fractions.size(); ++i) {
    const double a = c.edges[i], b = c.edges[i + 1];
    c.fractions[i] /= (b * b * b * b - a * a * a * a) / (4 * (b - a));
    sum += c.fractions[i];
  }
  for (double& f : c.fractions) f /= sum;
}

// P(a < X < b) of the standard normal without cancellation in the far tails.
double normal_mass(double a, double b) {
  const double s = std::sqrt(0.5);
  if (a + b > 0) return 0.5 * (std::erfc(a * s) - std::erfc(b * s));
  return 0.5 * (std::erfc(-b * s) - std::erfc(-a * s));
}

// A truncated normal on the volume basis has no closed-form number density (it is the normal
// over d^3): it becomes a table of this many equal bins over [min, max], each with its exact
// volume fraction. Within a bin the number density varies by at most (1 + dx/min)^3 with
// dx = (max - min) / 1024: the table's CDF differs from the exact one by well below 1e-3.
constexpr std::size_t volume_gauss_bins = 1024;

PsdComponent volume_gauss_as_table(const PsdComponent& g) {
  PsdComponent c;
  c.kind = PsdComponent::Kind::table;
  c.on = g.on;
  c.basis = PsdBasis::volume;
  c.min = g.min;
  c.max = g.max;
  const double dx = (g.max - g.min) / volume_gauss_bins;
  for (std::size_t i = 0; i <= volume_gauss_bins; ++i)
    c.edges.push_back(g.min + dx * static_cast<double>(i));
  c.edges.back() = g.max;
  for (std::size_t i = 0; i < volume_gauss_bins; ++i) {
    c.fractions.push_back(normal_mass((c.edges[i] - g.mean) / g.sd, (c.edges[i + 1] - g.mean) / g.sd));
  }
  volume_to_number_fractions(c);
  return c;
}

PsdComponent parse_gauss(const ComponentParser& p) {
  p.check_keys({"mean", "sd", "min", "max", "on"});
  PsdComponent c;
  c.kind = PsdComponent::Kind::gauss;
  c.on = p.on();
  // The mean of the untruncated normal may lie anywhere: the window keeps the sizes positive.
  c.mean = p.number("mean");
  c.sd = p.number("sd");
  if (c.sd < 0) p.fail("sd = " + p.text("sd") + " is negative (accepted: sd >= 0)");
  c.min = p.size("min");
  c.max = p.size("max");
  if (c.sd == 0 && c.min <= c.max && !(c.min <= c.mean && c.mean <= c.max)) {
    p.fail("sd = 0 with mean " + p.text("mean") + " outside [min, max] = [" + p.text("min") + ", " +
           p.text("max") + "] (accepted: min <= mean <= max)");
  }
  p.check_window(c);
  c.basis = p.basis(PsdBasis::number);
  if (c.basis == PsdBasis::volume && c.sd > 0) return volume_gauss_as_table(c);
  return c;
}

// z90 = Phi^-1(0.9) = -Phi^-1(0.1): ln d90 = mu + z90 sigma, ln d10 = mu - z90 sigma.
double z90() { return std::sqrt(2.0) * boost::math::erfc_inv(0.2); }

PsdComponent parse_lognormal(const ComponentParser& p) {
  p.check_keys({"median", "gsd", "d10", "d50", "d90", "min", "max", "on"});
  PsdComponent c;
  c.kind = PsdComponent::Kind::lognormal;
  c.on = p.on();
  const bool by_median = p.has("median") || p.has("gsd");
  const bool by_quantiles = p.has("d10") || p.has("d50") || p.has("d90");
  if (by_median && by_quantiles) p.fail("give median,gsd or d10,d50,d90, not both");
  if (!by_median && !by_quantiles) p.fail("missing key 'median' (or d10,d50,d90)");
  if (by_median) {
    const double median = p.size("median");
    const double gsd = p.number("gsd");
    if (!(gsd > 1)) p.fail("gsd = " + p.text("gsd") + " (accepted: geometric sd > 1)");
    c.mu = std::log(median);
    c.sigma = std::log(gsd);
  } else {
    // Least squares on ln d10 = mu - z90 sigma, ln d90 = mu + z90 sigma with mu = ln d50.
    const double d10 = p.size("d10");
    const double d50 = p.size("d50");
    const double d90 = p.size("d90");
    if (!(d10 < d50 && d50 < d90)) {
      p.fail("d10, d50, d90 = " + p.text("d10") + ", " + p.text("d50") + ", " + p.text("d90") +
             " (accepted: d10 < d50 < d90)");
    }
    c.mu = std::log(d50);
    c.sigma = std::log(d90 / d10) / (2 * z90());
  }
  // D10/D50/D90 are volume-based unless said otherwise (laser-diffraction data sheets give
  // them so); median/gsd are number-based. A volume-basis lognormal is the number-basis one
  // with ln d shifted by 3 sigma^2 (Hatch & Choate 1929): ln d_number = ln d_volume - 3 sigma^2.
  c.basis = p.basis(by_quantiles ? PsdBasis::volume : PsdBasis::number);
  const double shift = c.basis == PsdBasis::volume ? 3 * c.sigma * c.sigma : 0;
  c.mu -= shift;
  // The default window leaves 5 sigma on both sides of the number and the volume distribution.
  const double k = lognormal_default_window_sigmas;
  c.min = p.has("min") ? p.size("min") : std::exp(c.mu - k * c.sigma);
  c.max = p.has("max") ? p.size("max") : std::exp(c.mu + shift + k * c.sigma);
  p.check_window(c);
  return c;
}

// Table CSV (psd.hpp): header edge_low,edge_high,fraction, one bin per row, increasing; a gap
// between bins becomes an empty bin; fractions are normalised.
PsdComponent parse_table(const ComponentParser& p) {
  p.check_keys({"file", "on"});
  PsdComponent c;
  c.kind = PsdComponent::Kind::table;
  c.on = p.on();
  const std::string& path = p.text("file");
  try {
    require_regular_file(path, "file");  // a FIFO would block, /dev/zero never end
  } catch (const InputError& e) {
    p.fail(e.what());
  }
  std::ifstream in(path);
  if (!in) p.fail("file '" + path + "' cannot be read");
  auto bad = [&](std::size_t line, const std::string& what) {
    p.fail(fmt::format("file '{}' line {}: {}", path, line, what));
  };
  std::string line;
  std::size_t line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    if (!header) {
      std::string compact;
      for (const char ch : line) {
        if (ch != ' ' && ch != '\t') compact += ch;
      }
      if (compact != "edge_low,edge_high,fraction") {
        bad(line_no, "header '" + line + "' (expected edge_low,edge_high,fraction)");
      }
      header = true;
      continue;
    }
    std::stringstream row(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(row, cell, ',')) {
      double value = 0;
      const std::string number = trim(cell);
      if (!to_number(number, value)) bad(line_no, fmt::format("'{}' is not a number", number));
      v.push_back(value);
    }
    if (v.size() != 3) {
      bad(line_no, fmt::format("'{}' (expected edge_low,edge_high,fraction)", line));
    }
    if (!(v[0] > 0 && v[0] < v[1]))
      bad(line_no,
          fmt::format("bin [{:g}, {:g}] (accepted: 0 < edge_low < edge_high)", v[0], v[1]));
    if (v[2] < 0) bad(line_no, fmt::format("fraction {:g} (accepted: >= 0)", v[2]));
    if (!c.edges.empty() && v[0] < c.edges.back()) {
      bad(line_no, fmt::format("bin starts at {:g} below the previous bin's end {:g} (accepted: "
                               "increasing, non-overlapping bins)",
                               v[0], c.edges.back()));
    }
    if (c.edges.empty()) {
      c.edges.push_back(v[0]);
    } else if (v[0] > c.edges.back()) {
      c.edges.push_back(v[0]);
      c.fractions.push_back(0);
    }
    c.edges.push_back(v[1]);
    c.fractions.push_back(v[2]);
  }
  if (!header) p.fail("file '" + path + "': no header edge_low,edge_high,fraction");
  double sum = 0;
  for (const double f : c.fractions) sum += f;
  if (!(sum > 0)) p.fail("file '" + path + "': no bin with a fraction > 0");
  for (double& f : c.fractions) f /= sum;
  c.basis = p.basis(PsdBasis::number);
  if (c.basis == PsdBasis::volume) volume_to_number_fractions(c);
  return c;
}

}  // namespace

Psd Psd::parse(const std::string& spec, const std::string& option) {
  Psd psd;
  psd.text_ = trim(spec);
  if (psd.text_.empty()) {
    throw InputError(option +
                     ": empty PSD (expected e.g. mono:d=30e-6 or "
                     "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6)");
  }
  const auto parts = split_components(psd.text_);
  std::vector<Weight> weights;
  std::vector<double> weight_values;
  std::vector<ComponentParser> parsers;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const ComponentParser p(option, i + 1, parts[i]);
    PsdComponent c;
    if (p.kind() == "mono") {
      c = parse_mono(p);
    } else if (p.kind() == "gauss") {
      c = parse_gauss(p);
    } else if (p.kind() == "lognormal") {
      c = parse_lognormal(p);
    } else {
      c = parse_table(p);
    }
    double value = 0;
    weights.push_back(p.weight(value));
    weight_values.push_back(value);
    if (weights.back() == Weight::count) c.count = static_cast<std::size_t>(value);
    psd.components_.push_back(c);
    parsers.push_back(p);
  }

  // Every component weighted the same way, or none weighted (equal number fractions).
  for (std::size_t i = 1; i < weights.size(); ++i) {
    if (weights[i] == weights[0]) continue;
    if (weights[i] == Weight::none || weights[0] == Weight::none) {
      const std::size_t bare = weights[i] == Weight::none ? i : 0;
      const std::size_t other = bare == 0 ? i : 0;
      parsers[bare].fail(std::string("no count/frac/vfrac while component ") +
                         std::to_string(other + 1) + " has " + weight_key(weights[other]) +
                         " (accepted: weights on every component or on none)");
    }
    parsers[i].fail(std::string(weight_key(weights[i])) + " mixed with " + weight_key(weights[0]) +
                    " of component 1 (accepted: the same weight key on every component)");
  }
  // Number fractions: count and frac as given; vfrac divided by each component's E[r^3].
  std::vector<double> share(psd.components_.size(), 1.0);
  for (std::size_t i = 0; i < share.size(); ++i) {
    if (weights[i] == Weight::none) continue;
    share[i] = weight_values[i];
    if (weights[i] == Weight::vfrac) share[i] /= radius_moment(psd.components_[i], 3);
  }
  double total = 0;
  for (const double s : share) total += s;
  for (std::size_t i = 0; i < share.size(); ++i) {
    psd.components_[i].number_fraction = share[i] / total;
  }
  return psd;
}

}  // namespace powderbed::bed
