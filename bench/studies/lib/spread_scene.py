"""A blade-spread scene as the spread studies read it (spread_peer, spread_layers, spread_accuracy):
deposit's INI options as dotted names, the numbers a study needs with deposit's defaults, the
LIGGGHTS restitution that matches the scene's damping ratio, and the window of the layer the blade
leaves behind it."""
import configparser
import math
import os
import sys

from lib.apps import ROOT

WINDOW_MARGIN = 0.1   # fraction of the travel left out at each end of the swept path


def read_scene(path):
    """The scene's options as {dotted name: text}, as deposit reads it (INI sections map to
    dotted names; keys before any section are top-level)."""
    parser = configparser.ConfigParser(interpolation=None, inline_comment_prefixes=("#", ";"),
                                       strict=False)
    parser.optionxform = str
    with open(path) as f:
        parser.read_string("[__top__]\n" + f.read())
    out = {}
    for section in parser.sections():
        for key, value in parser.items(section):
            out[key if section == "__top__" else f"{section}.{key}"] = value.strip()
    return out


class Scene:
    """The numbers of a blade-spread scene the studies need, with deposit's defaults where it has them."""

    def __init__(self, path, overrides):
        self.path = path
        self.options = read_scene(path)
        self.options.update(overrides)
        o = self.options
        if o.get("recoater.tool", "blade") != "blade":
            sys.exit(f"spread scene: {path}: recoater.tool = {o['recoater.tool']} (accepted: blade)")
        if o.get("periodic", "none").replace(" ", "") != "y":
            sys.exit(f"spread scene: {path}: periodic = {o.get('periodic', 'none')} (accepted: y, "
                     "what bench/liggghts/spread-blade.liggghts models)")
        self.lx, self.ly, self.lz = (float(v) for v in o["domain"].split(","))
        self.young = self.num("material.young", 193e9)
        self.poisson = self.num("material.poisson", 0.26)
        self.density = self.num("material.density", 7952)
        self.damping = self.num("material.damping", 0.1)
        self.friction = self.num("material.friction", 0.1)
        self.rolling = self.num("material.rolling", 0.0)
        # A spread needs static friction for its heap to stand (issue 16): history unless the
        # scene asks for the sliding law.
        self.tangential = "no_history" if o.get("friction.model") == "sliding" else "history"
        self.wall_young = self.num("wall.young", 193e9)
        self.wall_poisson = self.num("wall.poisson", 0.26)
        self.young_scale = self.num("young-scale", 1.0)
        # deposit's effects.drag defaults off; the blade scene switches it on (argon)
        self.drag = o.get("effects.drag", "false").lower() in ("true", "1", "yes", "on")
        self.gravity = self.num("gravity", 9.81)
        self.gap = self.num("recoater.gap")
        self.speed = self.num("recoater.speed")
        self.start = self.num("recoater.start")
        self.end = self.num("recoater.end")
        self.thickness = self.num("recoater.thickness", 500e-6)
        self.delay = self.num("recoater.delay", 0.0)
        self.settle = self.num("recoater.settle", 0.0)
        if self.num("recoater.edge-radius", 0.0) > 0:
            print("spread scene: recoater.edge-radius > 0: the STL blade has sharp edges", file=sys.stderr)

    def num(self, key, default=None):
        if key in self.options:
            return float(self.options[key])
        if default is None:
            sys.exit(f"spread scene: {self.path}: {key} missing (required)")
        return default

    def restitution(self):
        """The restitution of LIGGGHTS's Hertz damping gamma_n = 2 sqrt(5/6) |beta| sqrt(m* k_n)
        that equals deposit's c = 2 zeta sqrt(m* k_n): beta = zeta / sqrt(5/6), e = exp(pi beta /
        sqrt(1 - beta^2)) with beta < 0 (as bench/liggghts/gz2016-speed.liggghts)."""
        b = self.damping / math.sqrt(5.0 / 6.0)
        if not b < 1:
            sys.exit(f"spread scene: material.damping {self.damping} has no LIGGGHTS restitution "
                     "(accepted: < sqrt(5/6))")
        return math.exp(-math.pi * b / math.sqrt(1 - b * b))

    def window(self):
        """The layer the blade leaves behind it: from its front face at the start (where the
        supply begins) to its back face at the end, less WINDOW_MARGIN of that at each end."""
        lo, hi = self.start + self.thickness / 2, self.end - self.thickness / 2
        if not hi > lo:
            sys.exit(f"spread scene: the blade travels {self.end - self.start} m, less than its thickness "
                     f"{self.thickness} m: it leaves no layer behind it (accepted: a longer travel or --window)")
        margin = WINDOW_MARGIN * (hi - lo)
        return lo + margin, hi - margin


def shown_path(path):
    """A path relative to the repository when it lies inside it (no machine's folders in results)."""
    full = os.path.abspath(path)
    return os.path.relpath(full, ROOT) if full.startswith(ROOT + os.sep) else os.path.basename(full)


