#!/usr/bin/env python3
"""Draws keff temperature profiles (the RUN-profile.csv that `keff --out RUN.h5` writes beside the
bed) to a PNG: the mean particle temperature of each bin along the axis with its min–max band,
and the straight line a uniform conductor between the same walls would have. Several profiles
share the axes, each normalised to (T − T_cold) / (T_hot − T_cold) so that runs at different
temperatures compare.
Usage: scripts/plot_keff_profile.py PROFILE.csv [PROFILE.csv ...] OUT.png [--label TEXT ...]
"""
import argparse
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    """(axis name, T_cold, T_hot, rows) of a profile CSV; rows: position, mean, min, max, count."""
    with open(path) as f:
        comment = f.readline()
        header = f.readline()
    walls = re.search(r"cold wall ([0-9.eE+-]+) K .* hot wall ([0-9.eE+-]+) K", comment)
    if not comment.startswith("# keff temperature profile") or walls is None:
        raise SystemExit(f"plot_keff_profile: {path}: not a keff profile (no '# keff temperature "
                         "profile' line naming the walls)")
    rows = np.atleast_2d(np.genfromtxt(path, delimiter=",", skip_header=2))
    return header.split("_")[0], float(walls.group(1)), float(walls.group(2)), rows


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("profiles", nargs="+")
    parser.add_argument("out")
    parser.add_argument("--label", action="append", default=None)
    args = parser.parse_args()
    labels = args.label or args.profiles
    if len(labels) != len(args.profiles):
        raise SystemExit("plot_keff_profile: give one --label per profile, or none")
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for n, (path, label) in enumerate(zip(args.profiles, labels)):
        axis, t_cold, t_hot, rows = load(path)
        # Equal bins tile the walls' span: it starts half a bin below the first centre.
        width = rows[1, 0] - rows[0, 0] if len(rows) > 1 else 2 * rows[0, 0]
        z = (rows[:, 0] - (rows[0, 0] - width / 2)) / (width * len(rows))
        theta = (rows[:, 1:4] - t_cold) / (t_hot - t_cold)
        ax.fill_between(z, theta[:, 1], theta[:, 2], color=f"C{n}", alpha=0.2, lw=0)
        ax.plot(z, theta[:, 0], "o-", ms=3, color=f"C{n}",
                label=f"{label} ({t_cold:g}–{t_hot:g} K)")
    ax.plot([0, 1], [0, 1], "k:", lw=1, label="uniform conductor")
    ax.set_xlabel(f"{axis} / H (cold wall at 0, hot wall at 1)")
    ax.set_ylabel("(T − T_cold) / (T_hot − T_cold)")
    ax.set_title("keff: particle temperatures by bin (mean, min–max band)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"plot_keff_profile: wrote {args.out}")


if __name__ == "__main__":
    main()
