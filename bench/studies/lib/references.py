"""The reference models and published numbers the studies set their results beside, each with
its source. [LP], [GZ] and [KE] are the main sources as docs/physics.md names them: Luberto &
de Payrebrune (2D geometric packing), Ganeriwala & Zohdi 2016 (deposition and laser heating of
a 316L bed), Kumar Yadav & Eshraghi 2016 (effective conductivity of a bed with MFiX-DEM). A
number quoted only in a page's prose stays in the study that writes it."""
import math
from collections import namedtuple


def zbs(porosity, kappa, c=1.25):
    """Zehner–Bauer–Schlünder stagnant conductivity k_eff/k_g of a packed bed of spheres, point
    contacts, no radiation, no Smoluchowski effect (Zehner & Schlünder, Chem. Ing. Tech. 42 (1970)
    933; VDI Heat Atlas, section M5): kappa = k_s/k_g, B = C ((1 - eps)/eps)^(10/9), C = 1.25
    for spheres. The closed form of the unit cell whose solid fills, at radius r, the height
    z(r) = B s / (1 + (B - 1) s), s = sqrt(1 - r^2), solid and gas in series along the heat flow,
    the cell's core taking the area fraction sqrt(1 - eps)."""
    b = c * ((1 - porosity) / porosity) ** (10 / 9)
    n = 1 - b / kappa
    core = 2 / n * ((1 - 1 / kappa) * b / n ** 2 * math.log(kappa / b) - (b + 1) / 2 - (b - 1) / n)
    root = math.sqrt(1 - porosity)
    return 1 - root + root * core


def k_air(t):
    """[KE]'s fit of air's conductivity (W/mK) at T (K), valid over 175–1900 K (docs/physics.md
    §6): keff's `--gas.model air`."""
    return 6.566e-12 * t ** 3 - 3.386e-8 * t ** 2 + 9.426e-5 * t + 7.505e-4


# [KE]'s five validation cases: their Table 2 (the uniform input ranges of the uncertainty
# study: k_s and k_g in W/mK, Young's modulus E in GPa; the particle diameter in m) and their
# Table 3 (the bed porosity, mean and sd over consolidation). `case` names the scenes
# data/scenes/ke2016-<case>.ini and ke2016-<case>-bed.ini.
Ke2016Case = namedtuple("Ke2016Case", "case label diameter k_s k_g young porosity")
KE2016_CASES = [
    Ke2016Case("steel-1mm", "steel 1.0 mm", 1.0e-3, (12.11, 45.0), (0.025, 0.027), (190, 206),
               (0.410, 0.010)),
    Ke2016Case("steel-3.2mm", "steel 3.2 mm", 3.2e-3, (12.11, 45.0), (0.025, 0.027), (190, 206),
               (0.418, 0.009)),
    Ke2016Case("copper-0.25mm", "copper 0.25 mm", 0.25e-3, (393, 409), (0.025, 0.027),
               (110, 128), (0.415, 0.009)),
    Ke2016Case("copper-0.15mm", "copper 0.15 mm", 0.15e-3, (393, 409), (0.025, 0.027),
               (110, 128), (0.416, 0.008)),
    Ke2016Case("lead-1.6mm", "lead 1.6 mm", 1.6e-3, (34.24, 36.36), (0.025, 0.027), (13.8, 16),
               (0.416, 0.009)),
]


# [KE]'s own k_eff of each case (mean, total sd, W/mK): not transcribed into this file, so the
# validation page shows them as missing rather than from memory. Add them as
# "case": (mean, sd) from the paper's table to have the page set them beside ours.
KE2016_KEFF = {}


def ke2016_case(case):
    """The entry of KE2016_CASES named `case`."""
    return next(c for c in KE2016_CASES if c.case == case)


# [KE]'s consolidation: the top wall lowered to these depths below the bed's surface, in
# particle radii, held and raised again (four consolidated beds beside the unconsolidated one).
KE2016_LID_DEPTHS = [0.25, 0.5, 0.75, 1.0]
# [KE]'s bed-generation uncertainty: eight steel 1 mm beds from different random insertions,
# k_eff sd 0.002 W/mK, neglected beside the other sources.
KE2016_BED_SEEDS = 8
KE2016_BED_SD = 0.002  # W/mK

# [GZ] 2016 (docs/physics.md §5): the melt pool (height, width, depth) in um on the plane
# x = Lx/2 of their single-track validation, their model and their experiment; and the cost of
# that pass with their model, about 3 CPU hours.
GZ2016_MELT_POOL_MODEL = (30.0, 85.0, 20.0)
GZ2016_MELT_POOL_EXPERIMENT = (26.0, 75.0, 30.0)
GZ2016_PASS_CPU_S = 3 * 3600.0

# [LP]'s 2D results on the 4 x 4 um square with the raster grid h = 0.015 um: the ranges of
# particle count, density and coordination number they report for the monodisperse
# (r = 0.075 um) and the truncated Gaussian PSD, 0-contact and 1-contact; key (psd, approach).
LP_2D = {
    ("mono", 0): ((500, 520), (0.55, 0.57), (1.8, 2.1)),
    ("mono", 1): ((560, 580), (0.62, 0.64), (3.25, 3.45)),
    ("gauss", 0): ((325, 425), (0.42, 0.52), (1.3, 1.5)),
    ("gauss", 1): ((525, 575), (0.68, 0.72), (3.3, 3.45)),
}


# ------------------------------------------------------------------------------------------------
# Melt pools of single tracks: the flat surface's Fresnel absorptance and Eagar–Tsai's moving
# Gaussian source (sinter_tracks.py).

def fresnel_normal(index):
    """The absorptance of a flat metal surface at normal incidence, 1 - |(N - 1)/(N + 1)|^2 for
    the complex index N = n + ik (s and p coincide there): 0.353 for iron's 3.235 + 4.322i
    (data/materials/316L.csv)."""
    r = (index - 1) / (index + 1)
    return 1 - abs(r) ** 2


class EagarTsai:
    """Eagar & Tsai's quasi-steady temperature under a moving Gaussian surface source on a
    semi-infinite body of constant properties (Eagar & Tsai, Welding J. 62 (1983) 346): the time
    integral of the instantaneous Gaussian point-source kernel in the frame of the source,
      T - T0 = q/(rho c) int_0^inf dtau gx gy gz,   s^2 = sigma^2 + 2 kappa tau,
      gx = exp(-(xi + v tau)^2 / (2 s^2)) / sqrt(2 pi s^2),  gy likewise in y,
      gz = 2 exp(-z^2 / (4 kappa tau)) / sqrt(4 pi kappa tau)          (adiabatic top),
    q = A P the absorbed power, sigma = w/2 for the 1/e^2 radius w (I ~ exp(-2 r^2 / w^2)), xi the
    distance ahead of the source along the track. The same solution as the reference of
    tests/thermal/test_moving_source.cpp, there with the box's Dirichlet faces by images; here
    the body is semi-infinite and t -> inf. No latent heat, no melt flow, no vaporisation. tau =
    u^2 removes the 1/sqrt(tau) at the surface."""

    def __init__(self, q, k, rho_c, w, v, t0=0.0):
        self.q, self.k, self.rho_c, self.sigma, self.v, self.t0 = q, k, rho_c, w / 2, v, t0
        self.kappa = k / rho_c

    def temperature(self, xi, y, z):
        """T at (xi, y, z), z <= 0 below the surface (z > 0 is read as -z)."""
        from scipy.integrate import quad
        kap, v, s0 = self.kappa, self.v, self.sigma ** 2

        def integrand(u):
            tau = u * u
            s2 = s0 + 2 * kap * tau
            gxy = math.exp(-((xi + v * tau) ** 2 + y * y) / (2 * s2)) / (2 * math.pi * s2)
            # 2u (from dtau) x 2 exp(-z^2 / 4 kappa u^2) / sqrt(4 pi kappa) / u
            return 4 * gxy * math.exp(-z * z / (4 * kap * tau)) / math.sqrt(4 * math.pi * kap) \
                if tau > 0 else (4 * gxy / math.sqrt(4 * math.pi * kap) if z == 0 else 0.0)

        # the integrand lives where xi + v tau is within a few s of 0, and dies as exp(-v^2 tau /
        # 4 kappa) beyond: integrate to where both are negligible, split at the passage.
        tau_end = max(0.0, -xi / v) + 200 * kap / v ** 2 + 40 * (self.sigma + abs(y)) / v
        tau_pass = -xi / v
        cuts = [0.0]
        if tau_pass > 0:
            cuts.append(math.sqrt(tau_pass))
        cuts.append(math.sqrt(tau_end))
        total = 0.0
        for a, b in zip(cuts, cuts[1:]):
            total += quad(integrand, a, b, limit=200, epsabs=0.0, epsrel=1e-9)[0]
        return self.t0 + self.q / self.rho_c * total

    def _extent(self, t_melt, along, scale):
        """The largest distance d from the track's axis (along 'y' on the surface or 'z' below
        the axis) at which T = t_melt, over the positions xi along the track: (d, xi there)."""
        from scipy.optimize import brentq, minimize_scalar

        def t_at(xi, d):
            return self.temperature(xi, d, 0.0) if along == "y" else self.temperature(xi, 0.0, -d)

        def reach(xi):
            if t_at(xi, 0.0) <= t_melt:
                return 0.0
            hi = scale
            while t_at(xi, hi) > t_melt:
                hi *= 2
            return brentq(lambda d: t_at(xi, d) - t_melt, 0.0, hi, xtol=1e-9)

        # the surface's hottest point lies a little behind the source; the pool's widest and
        # deepest sections further behind: scan, then refine around the best.
        length = self.melt_length(t_melt)
        if length == 0:
            return 0.0, 0.0
        xs = [self.sigma - (length + 2 * self.sigma) * i / 24 for i in range(25)]
        best = max(xs, key=reach)
        step = (length + 2 * self.sigma) / 24
        r = minimize_scalar(lambda xi: -reach(xi), bounds=(best - step, best + step),
                            method="bounded", options={"xatol": 1e-8})
        return (-r.fun, r.x) if -r.fun > reach(best) else (reach(best), best)

    def melt_length(self, t_melt):
        """The length of the T = t_melt isotherm along the track's centre line on the surface
        (0 when the surface does not melt)."""
        from scipy.optimize import brentq, minimize_scalar
        peak = minimize_scalar(lambda xi: -self.temperature(xi, 0.0, 0.0),
                               bounds=(-10 * self.sigma, self.sigma), method="bounded")
        if -peak.fun <= t_melt:
            return 0.0
        x_hot = peak.x
        front = x_hot
        while self.temperature(front, 0.0, 0.0) > t_melt:
            front += self.sigma
        back = x_hot
        while self.temperature(back, 0.0, 0.0) > t_melt:
            back -= 2 * self.sigma + (x_hot - back)
        f = lambda xi: self.temperature(xi, 0.0, 0.0) - t_melt
        return brentq(f, x_hot, front, xtol=1e-9) - brentq(f, back, x_hot, xtol=1e-9)

    def peak_temperature(self):
        """The surface's highest temperature (on the track's axis, a little behind the source)."""
        from scipy.optimize import minimize_scalar
        peak = minimize_scalar(lambda xi: -self.temperature(xi, 0.0, 0.0),
                               bounds=(-10 * self.sigma, self.sigma), method="bounded")
        return -peak.fun

    def melt_pool(self, t_melt):
        """(width, depth, length) of the T = t_melt isotherm, m: twice the largest half-width on
        the surface, the largest depth under the axis, the length on the axis."""
        scale = max(self.sigma, 1e-6)
        half, _ = self._extent(t_melt, "y", scale)
        depth, _ = self._extent(t_melt, "z", scale)
        return 2 * half, depth, self.melt_length(t_melt)
