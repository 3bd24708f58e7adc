#!/usr/bin/env python3
"""The zeta -> damping-input mapping of the exported decks (docs/decks.md), measured: for each
damping ratio zeta, a head-on impact of two equal 316L spheres and a sphere's impact on the floor
run in deposit, in LAMMPS and in LIGGGHTS through the decks `bedconv --deck` writes, and the
coefficient of restitution e = separation speed / approach speed each gives. The reference is
deposit's law itself (tests/data/hertz_restitution.csv, an independent RK4 solution of the
dimensionless Hertz + zeta ODE). Also run: LAMMPS's damping tsuji fed the restitution that
deposit's zeta gives, the naive mapping a user writes by hand.

Writes docs/results/deck-damping.md (its prose: bench/studies/templates/deck-damping.md.in).
Needs the build's deposit and bedconv, lmp and liggghts.
usage: python3 bench/studies/deck_damping.py"""
import argparse
import csv
import os
import re
import subprocess
import tempfile

from lib import report
from lib.apps import ROOT, app

ZETAS = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5]
R = 15e-6          # sphere radius, m (a 30 um powder particle)
V = 0.1            # impact speed of each sphere, m/s (a drop of ~0.5 mm)
DT = 1e-10         # s: ~1100 steps per contact (Hertz contact time ~1.1e-7 s here)
STEPS = 6000       # 6e-7 s: approach over the 2e-8 m gap (1e-7 s), contact, separation
GAP = 2e-8         # initial surface gap, m
BOX = 2e-4         # box side, m


def data_file(path, kind):
    """A two-sphere (pair) or one-sphere (wall) bed as a LAMMPS data file with velocities,
    written the way write_lammps_data writes one (bedconv reads it)."""
    if kind == "pair":
        atoms = [(1, 0.5 * BOX - R - GAP / 2, V), (2, 0.5 * BOX + R + GAP / 2, -V)]
        rows = [f"{i} 1 {2 * R!r} 7952 {x!r} {0.5 * BOX!r} {0.5 * BOX!r}" for i, x, _ in atoms]
        vel = [f"{i} {v!r} 0 0 0 0 0" for i, _, v in atoms]
    else:
        rows = [f"1 1 {2 * R!r} 7952 {0.5 * BOX!r} {0.5 * BOX!r} {R + GAP!r}"]
        vel = [f"1 0 0 {-V!r} 0 0 0"]
    n = len(rows)
    text = (f"impact\n\n# boundary f f f\n{n} atoms\n1 atom types\n\n0 {BOX!r} xlo xhi\n0 {BOX!r} ylo yhi\n"
            f"0 {BOX!r} zlo zhi\n\nAtoms # sphere\n\n" + "\n".join(rows) + "\n\nVelocities\n\n" + "\n".join(vel) + "\n")
    with open(path, "w") as f:
        f.write(text)


def scene_file(path, zeta):
    with open(path, "w") as f:
        f.write(f"material.damping = {zeta!r}\nmaterial.density = 7952\ndt = {DT!r}\n"
                "effects.gravity = false\neffects.drag = false\neffects.friction = false\n")


def restitution(velocities, kind):
    if kind == "pair":
        return (velocities[1][0] - velocities[0][0]) / (2 * V)
    return velocities[0][2] / V


def last_velocities(dump):
    """vx vy vz of each atom (by id) in the last snapshot of a dump with columns id type x y z vx
    vy vz radius."""
    lines = open(dump).read().split("ITEM: TIMESTEP")[-1].splitlines()
    start = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS")) + 1
    rows = sorted((int(l.split()[0]), [float(v) for v in l.split()[5:8]]) for l in lines[start:] if l.strip())
    return [v for _, v in rows]


def engine(work, kind, zeta, name, tsuji_input=None):
    """e of one impact in LAMMPS or LIGGGHTS through the exported deck; with `tsuji_input` the
    deck's tsuji e is replaced by that value (the naive mapping)."""
    data_file(os.path.join(work, "in.data"), kind)
    scene_file(os.path.join(work, "scene.ini"), zeta)
    subprocess.run([app("bedconv"), "in.data", "imp.data", "--deck", name, "--deck-scene", "scene.ini",
                    "--deck-steps", str(STEPS)], cwd=work, check=True, capture_output=True)
    deck = os.path.join(work, f"in.imp.{name}")
    if tsuji_input is not None:
        text = open(deck).read()
        text = re.sub(r"(hertz \S+ )\S+ damping \w+", rf"\g<1>{tsuji_input!r} damping tsuji", text)
        open(deck, "w").write(text)
    exe = {"lammps": "lmp", "liggghts": "liggghts"}[name]
    subprocess.run([exe, "-in", f"in.imp.{name}", "-log", "none"], cwd=work, check=True, capture_output=True)
    return restitution(last_velocities(os.path.join(work, f"imp.{name}.lammpstrj")), kind)


def deck_input(work, name):
    """The damping input the last exported deck of `name` carries (tsuji e or restitution)."""
    text = open(os.path.join(work, f"in.imp.{name}")).read()
    if name == "lammps":
        m = re.search(r"pair_coeff\s+\* \* hertz \S+ (\S+) damping (\w+)", text)
        return float(m.group(1)) if m.group(2) == "tsuji" else float("nan")
    return float(re.search(r"coefficientRestitution peratomtypepair \d+ (\S+)", text).group(1))


def ours(work, kind, zeta):
    """e of one impact in deposit (the same bed, scene and step)."""
    data_file(os.path.join(work, "in.data"), kind)
    out = os.path.join(work, "ours.h5")
    subprocess.run([app("deposit"), "--in", "in.data", "--t-end", repr(STEPS * DT), "--dt", repr(DT),
                    "--material.damping", repr(zeta), "--effects.gravity", "false", "--effects.drag", "false",
                    "--effects.friction", "false", "--seed", "1", "--out", out], cwd=work, check=True,
                   capture_output=True)
    import h5py
    with h5py.File(out, "r") as f:
        order = f["particles/id"][()].argsort()
        v = f["particles/velocity"][()][order]
    return restitution(v, kind)


BED_STEPS = 2000  # steps of the settled bed in each engine and in deposit


def settled_bed(work):
    """150 particles deposited until rest (Hertz, E softened 1000 x, periodic in x and y)."""
    subprocess.run([app("deposit"), "--psd", "gauss:mean=27e-6,sd=4e-6,min=15e-6,max=40e-6,on=diameter",
                    "--count", "150", "--domain", "2e-4,2e-4,4e-4", "--periodic", "x,y", "--until-rest",
                    "--t-end", "0.05", "--young-scale", "1000", "--seed", "2", "--out", "settled.h5"],
                   cwd=work, check=True, capture_output=True)


def centres(path):
    import h5py
    with h5py.File(path, "r") as f:
        return f["particles/position"][()][f["particles/id"][()].argsort()]


def bed_case(work, name, scene, deposit_args):
    """Largest centre difference between each engine and deposit after BED_STEPS steps of the
    settled bed with `scene` (deck keys) / `deposit_args` (the same for deposit), and the
    largest motion in deposit."""
    import numpy as np
    with open(os.path.join(work, "case.ini"), "w") as f:
        f.write(scene)
    gaps = {}
    for engine_name, exe in (("lammps", "lmp"), ("liggghts", "liggghts")):
        subprocess.run([app("bedconv"), "settled.h5", "case.data", "--deck", engine_name, "--deck-scene", "case.ini",
                        "--deck-steps", str(BED_STEPS)], cwd=work, check=True, capture_output=True)
        subprocess.run([exe, "-in", f"in.case.{engine_name}", "-log", "none"], cwd=work, check=True,
                       capture_output=True)
        subprocess.run([app("bedconv"), f"case.{engine_name}.lammpstrj", f"case_{engine_name}.h5"], cwd=work,
                       check=True, capture_output=True)
        gaps[engine_name] = centres(os.path.join(work, f"case_{engine_name}.h5"))
    dt = float(next(l.split()[1] for l in open(os.path.join(work, "in.case.lammps")) if l.startswith("timestep")))
    subprocess.run([app("deposit"), "--in", "settled.h5", "--dt", repr(dt), "--t-end", repr(BED_STEPS * dt),
                    "--periodic", "x,y", "--seed", "1", "--out", "case_ours.h5"] + deposit_args, cwd=work,
                   check=True, capture_output=True)
    ours = centres(os.path.join(work, "case_ours.h5"))
    moved = np.abs(ours - centres(os.path.join(work, "settled.h5"))).max()
    return {e: np.abs(c - ours).max() for e, c in gaps.items()}, moved


BED_CASES = [
    ("Hertz (S = 1000), damping, walls, gravity, drag; friction off", "effects.friction = false\n",
     ["--young-scale", "1000", "--effects.friction", "false"]),
    ("the same with friction mu_d = 0.1", "", ["--young-scale", "1000"]),
    ("linear law k_n = 100 N/m, friction off",
     "contact.law = linear\ncontact.stiffness = 100\nyoung-scale = 1\neffects.friction = false\n",
     ["--contact.law", "linear", "--contact.stiffness", "100", "--effects.friction", "false"]),
]


def reference():
    with open(os.path.join(ROOT, "tests", "data", "hertz_restitution.csv")) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        next(rows)
        return {round(float(z), 2): float(e) for z, e, _ in rows}


def impacts(work, ref):
    """Per zeta: the law's e (`ref`), deposit's and each engine's e on both impacts, the inputs
    the decks carry, and LAMMPS fed the law's own e (the naive mapping; none at zeta = 0, where
    the deck writes no tsuji)."""
    rows = []
    for zeta in ZETAS:
        row = {"zeta": zeta, "ref": ref[round(zeta, 2)]}
        for kind in ("pair", "wall"):
            row[f"ours_{kind}"] = ours(work, kind, zeta)
            row[f"lmp_{kind}"] = engine(work, kind, zeta, "lammps")
            row["lmp_in"] = deck_input(work, "lammps")
            row[f"lig_{kind}"] = engine(work, kind, zeta, "liggghts")
            row["lig_in"] = deck_input(work, "liggghts")
        row["naive"] = engine(work, "pair", zeta, "lammps", tsuji_input=row["ref"]) if zeta > 0 else float("nan")
        rows.append(row)
        print(row, flush=True)
    return rows


def beds(work):
    """Each BED_CASES scene on the settled bed: (label, {engine: largest centre difference from
    deposit}, deposit's largest motion)."""
    settled_bed(work)
    bed_rows = []
    for label, scene, args in BED_CASES:
        gaps, moved = bed_case(work, label, scene, args)
        bed_rows.append((label, gaps, moved))
        print(label, gaps, moved, flush=True)
    return bed_rows


def impact_table(rows):
    """Per zeta: the law's e, each code's on both impacts and the decks' inputs."""
    def tsuji(value):
        return "velocity 0" if value != value else f"{value:.5f}"  # nan: zeta = 0

    lines = report.table_head("zeta", "e of the law (RK4)", "deposit pair", "deposit wall",
                              "LAMMPS tsuji input", "LAMMPS pair", "LAMMPS wall",
                              "LIGGGHTS coefficientRestitution", "LIGGGHTS pair", "LIGGGHTS wall",
                              "LAMMPS fed e of the law")
    for r in rows:
        lines.append(report.table_row(
            f"{r['zeta']:.2f}", f"{r['ref']:.5f}", f"{r['ours_pair']:.5f}", f"{r['ours_wall']:.5f}",
            tsuji(r["lmp_in"]), f"{r['lmp_pair']:.5f}", f"{r['lmp_wall']:.5f}", f"{r['lig_in']:.5f}",
            f"{r['lig_pair']:.5f}", f"{r['lig_wall']:.5f}",
            "-" if r["naive"] != r["naive"] else format(r["naive"], ".5f")))
    return "\n".join(lines)


def bed_table(bed_rows):
    """Per scene: deposit's largest motion and each engine's largest difference from it."""
    lines = report.table_head("scene", "motion (m)", "LAMMPS - deposit (m)", "LIGGGHTS - deposit (m)")
    lines += [report.table_row(label, f"{moved:.2e}", f"{gaps['lammps']:.2e}", f"{gaps['liggghts']:.2e}")
              for label, gaps, moved in bed_rows]
    return "\n".join(lines)


def page(rows, bed_rows, machine):
    """The page: templates/deck-damping.md.in filled with the impacts' and the beds' results."""
    worst = max(abs(r[k] - r["ref"]) for r in rows for k in ("ours_pair", "ours_wall", "lmp_pair", "lmp_wall",
                                                             "lig_pair", "lig_wall"))
    engines = max(abs(r[f"{e}_{k}"] - r[f"ours_{k}"]) for r in rows for e in ("lmp", "lig") for k in ("pair", "wall"))
    tenth = next(r for r in rows if r["zeta"] == 0.1)
    return report.fill_template("deck-damping.md.in", {
        "machine": machine, "radius": f"{R * 1e6:g}", "speed": f"{V:g}", "dt": f"{DT:g}",
        "impact_table": impact_table(rows), "engines": f"{engines:.1e}", "worst": f"{worst:.1e}",
        "naive_e": f"{tenth['naive']:.3f}", "law_e": f"{tenth['ref']:.3f}",
        "liggghts_in": f"{tenth['lig_in']:.3f}", "liggghts_out": f"{tenth['lig_pair']:.3f}",
        "bed_steps": BED_STEPS, "bed_table": bed_table(bed_rows)})


def main():
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    load = report.load_average()
    ref = reference()
    with tempfile.TemporaryDirectory(prefix="powderbed_deck_damping_") as work:
        rows = impacts(work, ref)
        bed_rows = beds(work)
    print(report.write_page("deck-damping.md", page(rows, bed_rows, report.machine(load))))


if __name__ == "__main__":
    main()
