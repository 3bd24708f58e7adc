"""A blade-spread scene as the spread studies read it (spread_peer, spread_layers, spread_accuracy):
deposit's resolved options as dotted names (its --print-config: the scene, the overrides and
deposit's own defaults), the numbers a study needs, the LIGGGHTS restitution that matches the
scene's damping ratio, and the window of the layer the blade leaves behind it."""
import math
import os
import sys

from lib.apps import ROOT, option_args, resolved_options

WINDOW_MARGIN = 0.1   # fraction of the travel left out at each end of the swept path


def read_scene(path, overrides=None):
    """The options deposit runs the scene with, `overrides` ({dotted name: text}) given on its
    command line: {dotted name: text}, every option deposit has a default for included."""
    return resolved_options("deposit", ["--config", path, *option_args(overrides or {})])


class Scene:
    """The numbers of a blade-spread scene the studies need, as deposit resolves them."""

    def __init__(self, path, overrides):
        self.path = path
        self.options = read_scene(path, overrides)
        o = self.options
        if o["recoater.tool"] != "blade":
            sys.exit(f"spread scene: {path}: recoater.tool = {o['recoater.tool']} (accepted: blade)")
        if o["periodic"].replace(" ", "") != "y":
            sys.exit(f"spread scene: {path}: periodic = {o['periodic']} (accepted: y, "
                     "what bench/liggghts/spread-blade.liggghts models)")
        self.lx, self.ly, self.lz = (float(v) for v in o["domain"].split(","))
        self.young = self.num("material.young")
        self.poisson = self.num("material.poisson")
        self.density = self.num("material.density")
        self.damping = self.num("material.damping")
        self.friction = self.num("material.friction")
        self.rolling = self.num("material.rolling")
        # LIGGGHTS's tangential law is deposit's: a spread's heap stands on the static friction
        # of the history law (issue 16), so a spread scene asks for it.
        self.tangential = "history" if o["friction.model"] == "history" else "no_history"
        self.wall_young = self.num("wall.young")
        self.wall_poisson = self.num("wall.poisson")
        self.young_scale = self.num("young-scale")
        self.drag = o["effects.drag"] == "true"  # --print-config writes a bool true or false
        self.gravity = self.num("gravity")
        self.gap = self.num("recoater.gap")
        self.speed = self.num("recoater.speed")
        self.start = self.num("recoater.start")
        self.end = self.num("recoater.end")
        self.thickness = self.num("recoater.thickness")
        self.delay = self.num("recoater.delay")
        self.settle = self.num("recoater.settle")
        if self.num("recoater.edge-radius") > 0:
            print("spread scene: recoater.edge-radius > 0: the STL blade has sharp edges", file=sys.stderr)

    def num(self, key):
        return float(self.options[key])

    def restitution(self):
        """The restitution of LIGGGHTS's Hertz damping gamma_n = 2 sqrt(5/6) |beta| sqrt(m* k_n)
        that equals deposit's c = 2 zeta sqrt(m* k_n): beta = zeta / sqrt(5/6), e = exp(pi beta /
        sqrt(1 - beta^2)) with beta < 0 (as bench/liggghts/gz2016-speed.liggghts)."""
        b = self.damping / math.sqrt(5.0 / 6.0)
        if not b < 1:
            sys.exit(f"spread scene: material.damping {self.damping} has no LIGGGHTS restitution "
                     "(accepted: < sqrt(5/6))")
        return math.exp(-math.pi * b / math.sqrt(1 - b * b))

    def nominal_layer(self, thickness=None):
        """The solid of a layer's nominal powder as deposit's supply.dosing counts it (m^3):
        phi_b (recoater.end - recoater.start) L_y t, phi_b the supply's bulk density
        (supply.bulk-density), t the gap unless given (docs/deposit-spread.md "Dosing"). A supply
        of d times this solid is a dosing factor d, whatever the particles' sizes."""
        t = self.gap if thickness is None else thickness
        return self.num("supply.bulk-density") * (self.end - self.start) * self.ly * t

    def window(self):
        """The layer the blade leaves behind it: from its front face at the start (where the
        supply begins), or the dosing platform's edge when the scene has one (the layer begins
        past the table: docs/deposit-spread.md "The dosing platform"), to its back face at the
        end, less WINDOW_MARGIN of that at each end."""
        lo, hi = self.start + self.thickness / 2, self.end - self.thickness / 2
        if self.options.get("supply.platform-edge"):
            lo = max(lo, self.num("supply.platform-edge"))
        if not hi > lo:
            sys.exit(f"spread scene: the blade travels {self.end - self.start} m, less than its thickness "
                     f"{self.thickness} m: it leaves no layer behind it (accepted: a longer travel or --window)")
        margin = WINDOW_MARGIN * (hi - lo)
        return lo + margin, hi - margin


def shown_path(path):
    """A path relative to the repository when it lies inside it (no machine's folders in results)."""
    full = os.path.abspath(path)
    return os.path.relpath(full, ROOT) if full.startswith(ROOT + os.sep) else os.path.basename(full)


def solid_volume(radii):
    """The solid volume of spheres of these radii (m^3): sum of 4/3 pi r^3."""
    return sum(4.0 / 3.0 * math.pi * float(r) ** 3 for r in radii)


def check_rows_keep_window(study, scene_path, rows):
    """Exits naming the first row (key, label, options, seeds) whose options move the scene's
    measuring window: its rows must be measured over the same strip to be compared."""
    window = Scene(scene_path, {}).window()
    for key, _, options, _ in rows:
        if Scene(scene_path, {k[2:]: v for k, v in zip(options[::2], options[1::2])}).window() != window:
            sys.exit(f"{study}: row {key} moves the scene's window")


def run_rows(rows, run):
    """run(key, label, options, seed) for every seed of every row (key, label, options, seeds),
    seed 1 of every row first, so that a study cut short has each row once: the results in row
    order, a row's seeds together."""
    done = {}
    for seed in sorted({s for row in rows for s in row[3]}):
        for key, label, options, seeds in rows:
            if seed in seeds:
                done[key, seed] = run(key, label, options, seed)
    return [done[key, seed] for key, _, _, seeds in rows for seed in seeds]
