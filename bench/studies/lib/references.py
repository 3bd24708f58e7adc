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
