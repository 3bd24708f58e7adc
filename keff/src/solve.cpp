// The network over the particles that reach a wall (walls: Dirichlet values). Without radiation
// it is linear: the conductance Laplacian is solved once for θ = (T − T_cold) / (T_hot − T_cold)
// by Jacobi-preconditioned conjugate gradients. CG, not a sparse Cholesky: the fill-in of a 3D
// network makes SimplicialLDLT take 6 s at 27,000 particles where CG takes 0.5 s. The wall flows
// differ by exactly the sum of the residuals, so the tolerance bounds their mismatch.
//
// Radiation links carry σ G_r (T_j⁴ − T_i⁴): the start is the same linear solve with each
// radiation link replaced by its secant conductance between the wall temperatures,
// σ G_r (T_h² + T_c²)(T_h + T_c) (gas links that follow temperature: k_g at the mean wall
// temperature); then Newton on the particles' net heat flows R(T) = 0 with the analytic
// Jacobian (∂/∂T_i of σ G_r T_i⁴ is 4σ G_r T_i³). That Jacobian scales column j by 4σ G_r T_j³
// (and a gas link whose k_g follows its mean temperature, docs/physics.md §6's air polynomial, adds
// k_g'(T̄)/2 (T_j − T_i) to both slopes), so it is not symmetric: each step is solved by
// Jacobi-preconditioned BiCGSTAB (Eigen), CG's nonsymmetric sibling. A step that does not lower
// the residual is halved (backtracking), so a poor start cannot make Newton diverge.
#include "powderbed/keff/solve.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <string>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/radiative_exchange.hpp"
#include "powderbed/keff/paths.hpp"

namespace powderbed::keff {
namespace {

const char* const kAxisName[3] = {"x", "y", "z"};
// ‖residual‖ / ‖rhs‖ of each inner solve: the wall flows of the linear network then agree to
// ~1e-12 relative on beds of 1,000–100,000 particles (the issue asks 1e-8).
constexpr double kTolerance = 1e-12;
// The linear start's tolerance when Newton follows (radiation, or gas that follows temperature):
// the start is only Newton's first guess, whose steps take the residual to the scene's
// tolerance whatever the start; solving it to 1e-6, not 1e-12, halves its CG iterations.
constexpr double kStartTolerance = 1e-6;
constexpr int kMaxNewton = 50, kMaxHalvings = 30;
// Eigen runs ConjugateGradient<Lower|Upper>'s products on every OpenMP thread once the matrix has
// 20,000 nonzeros: one fork and barrier per iteration, which on a loaded 2-core machine waits for
// a descheduled thread (a 1,121-particle bed took 0.3-2 s on two threads, 0.02-0.07 s on one).
// Networks below this many unknowns use the Lower-only solver, whose product is serial.
constexpr std::ptrdiff_t kParallelUnknowns = 1 << 16;

// Union–find over the nodes plus the two walls (nodes: hot, nodes + 1: cold).
class Components {
 public:
  explicit Components(std::size_t count) : parent_(count) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t find(std::size_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::size_t> parent_;
};

std::size_t node(std::uint32_t j, std::size_t nodes) {
  return j == kHotWall ? nodes : j == kColdWall ? nodes + 1 : j;
}

bool is_wall(std::uint32_t j) { return j == kHotWall || j == kColdWall; }

double mean_radius(const bed::Bed& bed) {
  return bed.n() ? std::accumulate(bed.radius.begin(), bed.radius.end(), 0.0) /
                       static_cast<double>(bed.n())
                 : 0.0;
}

// The gap between the wall (the upper face of `axis`, or the lower) and the nearest particle
// surface, m: what a user needs to see when no particle reaches the wall.
double nearest_surface(const bed::Bed& bed, int axis, bool upper) {
  const auto a = static_cast<std::size_t>(axis);
  const std::vector<double>& centre = a == 0 ? bed.x : a == 1 ? bed.y : bed.z;
  double gap = HUGE_VAL;
  for (std::size_t p = 0; p < bed.n(); ++p) {
    const double h = upper ? bed.domain.upper[a] - centre[p] : centre[p] - bed.domain.lower[a];
    gap = std::min(gap, h - bed.radius[p]);
  }
  return gap;
}

using Matrix = Eigen::SparseMatrix<double>;

// A link's heat flow from its j end into its i end (W) and its slopes ∂q/∂T_i, ∂q/∂T_j.
struct LinkFlow {
  double q, d_i, d_j;
};

// The network's state: temperatures of the particles and the wall values. Whether gas links
// follow temperature (the air model) changes every gas link's flow: the flows, the residual and
// the Jacobian take it as a template argument, chosen once per solve (solve_keff), never tested
// per link.
struct State {
  const KeffNetwork& net;
  const std::vector<std::ptrdiff_t>& unknown;
  double t_hot, t_cold;

  double temperature(const std::vector<double>& t, std::uint32_t j) const {
    return j == kHotWall ? t_hot : j == kColdWall ? t_cold : t[j];
  }
  // Conduction: G (T_j − T_i), with the air model G k_g(T̄) / k_ref, T̄ = (T_i + T_j) / 2, whose
  // slopes carry k_g'(T̄) / 2 (T_j − T_i) as well; radiation: σ G_r (T_j⁴ − T_i⁴).
  template <bool GasFollows>
  LinkFlow flow(const KeffLink& l, const std::vector<double>& t) const {
    const double ti = t[l.i], tj = temperature(t, l.j);
    if (l.path == HeatPath::radiation) {
      return {bed::radiative_exchange(l.conductance, tj, ti), -bed::radiative_conductance(l.conductance, ti),
              bed::radiative_conductance(l.conductance, tj)};
    }
    if constexpr (GasFollows) {
      if (l.path == HeatPath::gas) {
        const double mean = (ti + tj) / 2, g = l.conductance / net.gas_reference;
        const double k = air_conductivity(mean), dk_half = air_conductivity_slope(mean) / 2;
        return {g * k * (tj - ti), g * (dk_half * (tj - ti) - k), g * (dk_half * (tj - ti) + k)};
      }
    }
    return {l.conductance * (tj - ti), -l.conductance, l.conductance};
  }
  template <bool GasFollows>
  bool nonlinear() const {
    for (const KeffLink& l : net.links)
      if (l.path == HeatPath::radiation || (GasFollows && l.path == HeatPath::gas)) return true;
    return false;
  }
  // Net heat flow into each unknown particle, and ‖R‖ / ‖Σ|q|‖.
  template <bool GasFollows>
  double residual(const std::vector<double>& t, Eigen::VectorXd& r) const {
    Eigen::VectorXd scale = Eigen::VectorXd::Zero(r.size());
    r.setZero();
    for (const KeffLink& l : net.links) {
      const std::ptrdiff_t u = unknown[l.i];
      if (u < 0) continue;
      const double q = flow<GasFollows>(l, t).q;
      r[u] += q;
      scale[u] += std::abs(q);
      if (is_wall(l.j)) continue;
      r[unknown[l.j]] -= q;
      scale[unknown[l.j]] += std::abs(q);
    }
    const double norm = scale.norm();
    return norm > 0 ? r.norm() / norm : 0;
  }
  // −∂R/∂T: R_i gains q and R_j loses it, so row i holds −∂q/∂T_i, −∂q/∂T_j and row j
  // ∂q/∂T_i, ∂q/∂T_j.
  template <bool GasFollows>
  Matrix jacobian(const std::vector<double>& t, std::ptrdiff_t count) const {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(net.links.size() * 4);
    for (const KeffLink& l : net.links) {
      const std::ptrdiff_t u = unknown[l.i];
      if (u < 0) continue;
      const LinkFlow f = flow<GasFollows>(l, t);
      triplets.emplace_back(u, u, -f.d_i);
      if (is_wall(l.j)) continue;
      const std::ptrdiff_t v = unknown[l.j];
      triplets.emplace_back(v, v, f.d_j);
      triplets.emplace_back(u, v, -f.d_j);
      triplets.emplace_back(v, u, f.d_i);
    }
    Matrix m(count, count);
    m.setFromTriplets(triplets.begin(), triplets.end());
    return m;
  }
};

// Jacobi-preconditioned CG to `tolerance`; UpLo: which triangle the product reads (both are
// stored), Lower|Upper being the one Eigen multithreads.
template <int UpLo>
Eigen::VectorXd conjugate_gradients(const Matrix& matrix, const Eigen::VectorXd& rhs,
                                    double tolerance, std::size_t& iterations) {
  Eigen::ConjugateGradient<Matrix, UpLo> cg;
  cg.setTolerance(tolerance);
  cg.compute(matrix);
  Eigen::VectorXd x = cg.solve(rhs);
  // {:f} here and below: the six decimals std::to_string gave the residuals.
  if (cg.info() != Eigen::Success || !x.allFinite())
    throw NumericalError(fmt::format(
        "keff: conjugate gradients did not converge on the network ({} iterations, residual "
        "{:f})",
        cg.iterations(), cg.error()));
  iterations += static_cast<std::size_t>(cg.iterations());
  return x;
}

// The linear start: conduction links as they are, radiation links by their secant conductance;
// returns the temperatures and adds the CG iterations to `iterations`.
std::vector<double> linear_solve(const State& s, std::ptrdiff_t count, std::size_t nodes,
                                 double tolerance, std::size_t& iterations) {
  const double th = s.t_hot, tc = s.t_cold;
  const double secant = bed::radiative_secant(1.0, th, tc);  // per m^2 of link conductance
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(s.net.links.size() * 4);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(count);
  for (const KeffLink& l : s.net.links) {
    const std::ptrdiff_t u = s.unknown[l.i];
    if (u < 0) continue;  // both ends in a rattler cluster
    const double g = l.path == HeatPath::radiation ? secant * l.conductance : l.conductance;
    triplets.emplace_back(u, u, g);
    if (is_wall(l.j)) {
      if (l.j == kHotWall) rhs[u] += g;
      continue;
    }
    const std::ptrdiff_t v = s.unknown[l.j];
    triplets.emplace_back(v, v, g);
    triplets.emplace_back(u, v, -g);
    triplets.emplace_back(v, u, -g);
  }
  Matrix matrix(count, count);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::VectorXd theta =
      count >= kParallelUnknowns
          ? conjugate_gradients<Eigen::Lower | Eigen::Upper>(matrix, rhs, tolerance, iterations)
          : conjugate_gradients<Eigen::Lower>(matrix, rhs, tolerance, iterations);
  std::vector<double> t(nodes, (th + tc) / 2);
  for (std::size_t p = 0; p < nodes; ++p)
    if (s.unknown[p] >= 0) t[p] = tc + (th - tc) * theta[s.unknown[p]];
  return t;
}

// The inner solve's relative tolerance on a Newton step from relative residual `rel` (inexact
// Newton, Dembo, Eisenstat & Steihaug 1982): the step need only bring ‖R‖ to a tenth of the
// target, η = 0.1 tolerance / rel, not to kTolerance; a start within 1e-6 of the answer then
// needs a 1e-5 reduction, not 1e-12, and the Newton test on R itself is unchanged. At most 0.5
// far from the answer (each step must still gain), at least kTolerance.
double newton_forcing(double rel, double tolerance) {
  return std::clamp(0.1 * tolerance / rel, kTolerance, 0.5);
}

// Newton from `t` to ‖R‖ / ‖Σ|q|‖ ≤ tolerance (the wall-flow mismatch is the sum of the R);
// fills the counters of `r`.
template <bool GasFollows>
void newton(const State& s, std::ptrdiff_t count, double tolerance, std::vector<double>& t,
            KeffResult& r) {
  Eigen::VectorXd res(count), trial_res(count);
  double rel = s.residual<GasFollows>(t, res);
  std::vector<double> trial;
  while (rel > tolerance) {
    if (r.newton_iterations == kMaxNewton)
      throw NumericalError(fmt::format(
          "keff: Newton did not converge in {} steps (relative residual {:f})", kMaxNewton, rel));
    ++r.newton_iterations;
    // The solver keeps a reference to the matrix.
    const Matrix jacobian = s.jacobian<GasFollows>(t, count);
    Eigen::BiCGSTAB<Matrix, Eigen::DiagonalPreconditioner<double>> solver;
    solver.setTolerance(newton_forcing(rel, tolerance));
    solver.compute(jacobian);
    const Eigen::VectorXd step = solver.solve(res);  // (−∂R/∂T) δ = R
    if (solver.info() != Eigen::Success || !step.allFinite())
      throw NumericalError("keff: BiCGSTAB did not converge on a Newton step (" +
                           std::to_string(solver.iterations()) + " iterations)");
    r.solver_iterations += static_cast<std::size_t>(solver.iterations());
    double fraction = 1;
    for (int halving = 0;; ++halving) {
      trial = t;
      bool positive = true;
      for (std::size_t p = 0; p < t.size(); ++p)
        if (s.unknown[p] >= 0) {
          trial[p] += fraction * step[s.unknown[p]];
          positive &= trial[p] > 0;
        }
      const double trial_rel = positive ? s.residual<GasFollows>(trial, trial_res) : HUGE_VAL;
      if (trial_rel < rel) {
        t.swap(trial);
        res.swap(trial_res);
        rel = trial_rel;
        break;
      }
      if (halving == kMaxHalvings)
        throw NumericalError("keff: Newton step does not lower the residual " +
                             std::to_string(rel) + " (stalled at round-off?)");
      fraction /= 2;
    }
  }
  r.residual = rel;
}

// The temperatures (the linear start, then Newton when a link is nonlinear), the wall flows
// and each path's dissipation Σ q ΔT at them.
template <bool GasFollows>
void solve_network(const State& s, std::ptrdiff_t count, std::size_t nodes, double tolerance,
                   KeffResult& r, double (&dissipation)[3]) {
  const bool nonlinear = s.nonlinear<GasFollows>();
  r.temperature = linear_solve(s, count, nodes, nonlinear ? kStartTolerance : kTolerance,
                               r.solver_iterations);
  if (nonlinear)
    newton<GasFollows>(s, count, tolerance, r.temperature, r);
  else
    r.newton_iterations = 1;
  for (const KeffLink& l : s.net.links) {
    if (s.unknown[l.i] < 0) continue;  // a rattler cluster's internal links carry nothing
    const double q = s.flow<GasFollows>(l, r.temperature).q;  // from j into i
    if (l.j == kHotWall) r.heat_flow_hot += q;
    if (l.j == kColdWall) r.heat_flow_cold -= q;
    dissipation[static_cast<int>(l.path)] += q * (s.temperature(r.temperature, l.j) -
                                                  r.temperature[l.i]);
  }
}

}  // namespace

KeffResult solve_keff(const bed::Bed& bed, const KeffScene& scene) {
  return solve_keff(bed, scene, build_keff_network(bed, scene));
}

KeffResult solve_keff(const bed::Bed& bed, const KeffScene& scene, const KeffNetwork& network) {
  const std::size_t n = bed.n(), nodes = std::max(n, network.node_count);
  const double t_hot = scene.hot_temperature, t_cold = scene.cold_temperature;
  KeffResult r;
  r.links = network.links.size();
  r.lost_rays = network.lost_rays;
  Components comp(nodes + 2);
  bool touches_hot = false, touches_cold = false;
  for (const KeffLink& l : network.links) {
    comp.join(l.i, node(l.j, nodes));
    touches_hot |= l.j == kHotWall;
    touches_cold |= l.j == kColdWall;
    (l.path == HeatPath::contact ? r.contact_links
     : l.path == HeatPath::gas   ? r.gas_links
                                 : r.radiation_links) += 1;
  }
  for (const bool hot : {true, false}) {
    if (hot ? touches_hot : touches_cold) continue;
    const double gap = nearest_surface(bed, scene.axis, hot);
    throw InputError(fmt::format(
        "axis: {} puts the {} wall at the {} {} face, which no particle reaches: the nearest "
        "particle's surface is {:.3g} m ({:.3g} diameters) from it (accepted: an axis whose "
        "walls the bed touches, within the gas lens or seeing it; a deposited bed touches its "
        "side walls, x and y)",
        kAxisName[scene.axis], hot ? "hot" : "cold", hot ? "upper" : "lower",
        kAxisName[scene.axis], gap, gap / (2 * mean_radius(bed))));
  }

  // Unknowns: nodes connected to a wall; the particles among the rest are rattlers.
  const std::size_t hot_root = comp.find(nodes), cold_root = comp.find(nodes + 1);
  std::vector<std::ptrdiff_t> unknown(nodes, -1);
  std::ptrdiff_t count = 0;
  for (std::size_t p = 0; p < nodes; ++p) {
    const std::size_t root = comp.find(p);
    if (root == hot_root || root == cold_root)
      unknown[p] = count++;
    else if (p < n)
      r.rattlers.push_back(static_cast<std::uint32_t>(p));
  }

  const State state{network, unknown, t_hot, t_cold};
  double dissipation[3] = {0, 0, 0};  // Σ q ΔT by path (Tellegen)
  if (network.gas_follows_temperature)
    solve_network<true>(state, count, nodes, scene.newton_tolerance, r, dissipation);
  else
    solve_network<false>(state, count, nodes, scene.newton_tolerance, r, dissipation);
  // Wall to wall through the gaps: the same flow leaves the hot wall and enters the cold one.
  const double direct = bed::radiative_exchange(network.wall_exchange, t_hot, t_cold);
  r.heat_flow_hot += direct;
  r.heat_flow_cold += direct;
  dissipation[static_cast<int>(HeatPath::radiation)] += direct * (t_hot - t_cold);
  r.temperature.resize(n);  // the radiosity nodes' τ are not particle temperatures
  const double total = dissipation[0] + dissipation[1] + dissipation[2];
  if (total > 0) {
    r.share_contact = dissipation[0] / total;
    r.share_gas = dissipation[1] / total;
    r.share_radiation = dissipation[2] / total;
  }
  const double q = (r.heat_flow_hot + r.heat_flow_cold) / 2;
  r.k_eff = q / network.wall_area * network.height / (t_hot - t_cold);
  return r;
}

}  // namespace powderbed::keff
