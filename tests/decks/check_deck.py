#!/usr/bin/env python3
"""ctest decks.<engine>.<ranks>: the deck `bedconv --deck ENGINE` writes runs with the engine
(serially or under mpirun -np 2, as a study goes to a cluster), and its dump reads back
losslessly: the step-0 snapshot holds the bed's ids, radii, centres, velocities and materials
bit for bit, the domain and periodic axes are the bed's; the engine moves the particles where
deposit does, in free fall and in a pressed lattice of Hertz contacts.

usage: check_deck.py APPS_DIR ENGINE RANKS
Exits 77 (ctest: skipped) with a message when the engine or mpirun is missing."""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

APPS, ENGINE, RANKS = sys.argv[1], sys.argv[2], int(sys.argv[3])
EXE = {"lammps": "lmp", "liggghts": "liggghts"}[ENGINE]
STEPS = 50


def run(cmd, cwd, env=None):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout[-3000:]}\n{p.stderr[-3000:]}")
    return p


def read_bed(path):
    with h5py.File(path, "r") as f:
        p = f["particles"]
        bed = {k: p[k][()] for k in ("position", "radius", "id", "velocity") if k in p}
        bed["material"] = p["material"][()] if "material" in p else np.zeros(len(bed["id"]), np.uint16)
        d = f["domain"]
        bed["lower"], bed["upper"] = d.attrs["lower"], d.attrs["upper"]
        bed["periodic"] = np.asarray(d.attrs["periodic"], bool)
    return bed


CONTACT_STEPS = 2000


def contact_run(work, launcher, env, linear=False):
    """A pressed lattice: 4 x 4 x 2 spheres of r = 20 um overlapping their neighbours and the floor
    by 2e-8 m (1e-3 r), periodic in x and y, with small shuffled velocities, given as a LAMMPS data
    file (bedconv and deposit read it). 2000 steps (~30 contact periods) of Hertz contact,
    damping, walls, gravity and drag in the engine and in deposit (friction off: the engines'
    tangential laws differ from deposit's, docs/decks.md); `linear`: the linear law with k_n =
    1e3 N/m instead (equal spheres: LIGGGHTS's one dashpot per type pair is exact). Returns
    (largest centre difference, largest motion)."""
    r, overlap, nx, nz = 20e-6, 2e-8, 4, 2
    s = 2 * r - overlap
    atoms, vel = [], []
    for k in range(nx * nx * nz):
        i, j, l = k % nx, k // nx % nx, k // (nx * nx)
        atoms.append(f"{k + 1} 1 {2 * r!r} 7952 {(i + 0.5) * s!r} {(j + 0.5) * s!r} {r - overlap / 2 + l * s!r}")
        vel.append(f"{k + 1} {1e-3 * np.sin(k)!r} {1e-3 * np.cos(3 * k)!r} {-1e-3 * np.sin(7 * k) ** 2!r} 0 0 0")
    with open(os.path.join(work, "lattice.data"), "w") as f:
        f.write(f"pressed lattice\n\n# boundary p p f\n{len(atoms)} atoms\n1 atom types\n\n0 {nx * s!r} xlo xhi\n"
                f"0 {nx * s!r} ylo yhi\n0 4e-4 zlo zhi\n\nAtoms # sphere\n\n" + "\n".join(atoms) +
                "\n\nVelocities\n\n" + "\n".join(vel) + "\n")
    law = ["--contact.law", "linear", "--contact.stiffness", "1e3"] if linear else []
    with open(os.path.join(work, "nofriction.ini"), "w") as f:
        f.write("effects.friction = false\n" + ("contact.law = linear\ncontact.stiffness = 1e3\n" if linear else ""))
    run([os.path.join(APPS, "bedconv"), "lattice.data", "lat.data", "--deck", ENGINE, "--deck-scene",
         "nofriction.ini", "--deck-steps", str(CONTACT_STEPS)], work)
    run(launcher + [EXE, "-in", f"in.lat.{ENGINE}", "-log", "none"], work, env)
    run([os.path.join(APPS, "bedconv"), f"lat.{ENGINE}.lammpstrj", "lat_last.h5"], work)
    dt = float(next(l.split()[1] for l in open(os.path.join(work, f"in.lat.{ENGINE}")) if l.startswith("timestep")))
    run([os.path.join(APPS, "deposit"), "--in", "lattice.data", "--dt", repr(dt), "--t-end", repr(CONTACT_STEPS * dt),
         "--effects.friction", "false", "--seed", "1", "--out", "lat_ours.h5"] + law, work)
    engine = read_bed(os.path.join(work, "lat_last.h5"))  # sorted by id (dump_modify sort id)
    ours = read_bed(os.path.join(work, "lat_ours.h5"))
    order = np.argsort(ours["id"])
    first = np.array([[float(v) for v in a.split()[4:7]] for a in atoms])
    gap = np.abs(engine["position"] - ours["position"][order]).max()
    moved = np.abs(ours["position"][order] - first).max()
    # The same forces summed in another order differ by ulps that 30 contact periods amplify;
    # 1e-6 of the motion is far below a wrong stiffness, damping or wall (each shifts the phase
    # of every oscillation). Measured: 2e-18 (LAMMPS), 2e-17 m (LIGGGHTS) on 2e-6 m.
    assert moved > 1e-10, f"the lattice did not move ({moved} m)"
    assert gap <= 1e-6 * moved, f"engine and deposit differ by {gap} m after moving {moved} m"
    return gap, moved


def main():
    if shutil.which(EXE) is None:
        print(f"skipped: {EXE} not on PATH (Debian package {ENGINE})")
        return 77
    if RANKS > 1 and shutil.which("mpirun") is None:
        print("skipped: mpirun not on PATH (Debian package mpi-default-bin)")
        return 77
    work = tempfile.mkdtemp(prefix=f"powderbed_deck_{ENGINE}_")
    try:
        # A falling bed of 60 particles with velocities, periodic in x and y, Ti-6Al-4V density.
        run([os.path.join(APPS, "deposit"), "--psd", "gauss:mean=27e-6,sd=4e-6,min=15e-6,max=40e-6,on=diameter",
             "--count", "60", "--domain", "2.5e-4,2e-4,3e-4", "--periodic", "x,y", "--t-end", "3e-5",
             "--seed", "5", "--material.density", "4430", "--out", "dep.h5"], work)
        # Two materials (every third particle the second), so the deck needs two atom types.
        shutil.copy(os.path.join(work, "dep.h5"), os.path.join(work, "bed.h5"))
        with h5py.File(os.path.join(work, "bed.h5"), "r+") as f:
            n = len(f["particles/id"])
            m = f["particles"].create_dataset("material", data=(np.arange(n) % 3 == 2).astype(np.uint16))
            m.attrs["units"] = "1"
        run([os.path.join(APPS, "bedconv"), "bed.h5", "bed.data", "--deck", ENGINE, "--density", "4430,8190",
             "--deck-steps", str(STEPS)], work)
        deck = f"in.bed.{ENGINE}"
        launcher = []
        env = dict(os.environ)
        if RANKS > 1:
            # Open MPI refuses root without these, and 2 ranks on a 1-core runner without
            # --oversubscribe.
            env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                       OMPI_MCA_rmaps_base_oversubscribe="1")
            launcher = ["mpirun", "-np", str(RANKS)]
        out = run(launcher + [EXE, "-in", deck, "-log", "none"], work, env).stdout
        if RANKS > 1 and f"on {RANKS} procs" not in out:
            sys.exit(f"{EXE} did not run on {RANKS} ranks:\n{out[-2000:]}")
        dump = f"bed.{ENGINE}.lammpstrj"
        # No --dt: the snapshots' times come from the deck (LAMMPS: ITEM: TIME in the dump;
        # LIGGGHTS: the deck's timestep, found beside the dump).
        run([os.path.join(APPS, "bedconv"), dump, "traj.h5", "--all-snapshots"], work)
        run([os.path.join(APPS, "bedconv"), dump, "last.h5"], work)
        run([os.path.join(APPS, "bedconv"), f"bed.{ENGINE}.final.data", "final.h5"], work)

        bed = read_bed(os.path.join(work, "bed.h5"))
        order = np.argsort(bed["id"])
        with h5py.File(os.path.join(work, "traj.h5"), "r") as t:
            steps = sorted(t["steps"].keys())
            assert [t["steps"][s].attrs["step"] for s in steps] == [0, STEPS], steps
            deck_dt = float(next(l.split()[1] for l in open(os.path.join(work, deck)) if l.startswith("timestep")))
            times = [t["steps"][s].attrs["time"] for s in steps]
            # LAMMPS prints ITEM: TIME with 16 digits; LIGGGHTS's are step x the deck's step.
            assert times[0] == 0 and abs(times[-1] - STEPS * deck_dt) <= 1e-15 * STEPS * deck_dt, times
            # Every value bit for bit: the deck's data file and dump both print %.17g.
            assert np.array_equal(t["id"][()], bed["id"][order]), "ids"
            assert np.array_equal(t["radius"][()], bed["radius"][order]), "radii"
            first = t["steps"][steps[0]]
            assert np.array_equal(first["position"][()], bed["position"][order]), "centres at step 0"
            assert np.array_equal(first["velocity"][()], bed["velocity"][order]), "velocities at step 0"
            moved = np.abs(t["steps"][steps[-1]]["position"][()] - first["position"][()]).max()
        # 50 steps of ~1.5 ns at the bed's fall speed (~0.3 mm/s after 3e-5 s) move it by ~2e-11
        # m, far above the ~1e-20 m of one ulp of a centre: a deck that did not run fails here.
        assert moved > 1e-15, f"the particles did not move ({moved} m)"
        # The same 50 steps in deposit (gravity and Stokes drag; the packing left no contacts):
        # the engine's last centres are deposit's, for the particles of deposit's one density.
        dt = float(next(l.split()[1] for l in open(os.path.join(work, deck)) if l.startswith("timestep")))
        cont = run([os.path.join(APPS, "deposit"), "--in", "dep.h5", "--dt", repr(dt), "--t-end", repr(STEPS * dt),
                    "--material.density", "4430", "--periodic", "x,y", "--seed", "5", "--out", "cont.h5", "--json"],
                   work).stdout
        assert '"steps":50' in cont.replace(" ", ""), cont
        with h5py.File(os.path.join(work, "traj.h5"), "r") as t:
            engine_last = t["steps"][steps[-1]]["position"][()]
        ours = read_bed(os.path.join(work, "cont.h5"))
        ours_last = ours["position"][np.argsort(ours["id"])]
        light = bed["material"][order] == 0
        gap = np.abs(engine_last[light] - ours_last[light]).max()
        # Both integrate the same forces with velocity Verlet (bit-identical here: 0 m measured);
        # 1e-6 of the displacement leaves room for another rounding order and is far below a
        # wrong sign or factor of either force (drag is ~1e-4 of the motion's change here).
        assert gap <= 1e-6 * moved, f"engine and deposit differ by {gap} m after moving {moved} m"
        last = read_bed(os.path.join(work, "last.h5"))
        final = read_bed(os.path.join(work, "final.h5"))
        by_id = np.argsort(final["id"])  # write_data lists atoms rank by rank
        final = {k: (v[by_id] if k in ("position", "radius", "id", "velocity", "material") else v)
                 for k, v in final.items()}
        assert np.array_equal(last["material"], bed["material"][order]), "materials (atom types)"
        assert np.array_equal(last["periodic"], bed["periodic"]), "periodic axes"
        assert np.array_equal(final["material"], bed["material"][order]), "materials of write_data"
        if ENGINE == "lammps":
            # LAMMPS prints a dump's box bounds with %.16e: exact.
            assert np.array_equal(last["lower"], bed["lower"]) and np.array_equal(last["upper"], bed["upper"]), "domain"
        else:
            # LIGGGHTS 3.8 prints them with %g (6 digits): the box to 5e-6 of its size; the deck's
            # final write_data file has it exactly.
            size = bed["upper"] - bed["lower"]
            assert np.all(np.abs(last["upper"] - bed["upper"]) <= 5e-6 * size), "domain (%g)"
        assert np.array_equal(final["lower"], bed["lower"]) and np.array_equal(final["upper"], bed["upper"]), \
            "domain of write_data"
        assert np.array_equal(final["radius"], bed["radius"][order]), "radii of write_data"
        contact_gap, contact_moved = contact_run(work, launcher, env)
        linear_gap, linear_moved = contact_run(work, launcher, env, linear=True)
        print(f"{ENGINE} x{RANKS}: {len(bed['id'])} particles, 2 materials, periodic x y; step 0 exact, "
              f"moved {moved:.3g} m in {STEPS} steps, {gap:.3g} m from deposit's; pressed lattice: "
              f"moved {contact_moved:.3g} m in {CONTACT_STEPS} steps, {contact_gap:.3g} m from deposit's; "
              f"linear law: moved {linear_moved:.3g} m, {linear_gap:.3g} m from deposit's")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
