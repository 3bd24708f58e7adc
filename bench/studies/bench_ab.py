#!/usr/bin/env python3
"""Before and after: one Google Benchmark program built at two commits, run in alternation.

A refactoring that must not slow a kernel down (e.g. the DEM effect masks of
bench/dem_effects.cpp when the force loop's dispatch changed) is shown by running the old and the
new binary of the same benchmark one after the other, ROUNDS times, each run reporting the median
of REPS repetitions; the page gives, per benchmark, the median over the rounds of each binary and
their ratio (new / old: > 1 is a slowdown), with the smallest and largest round. Alternating
the two puts both under the same load, which on a shared machine moves single runs by ±10 %.

    python3 bench/studies/bench_ab.py OLD_BINARY NEW_BINARY --old-label a29d637 --new-label HEAD \
        [--rounds 8] [--reps 3] [--filter REGEX] --page dem-effects.md [--title "..."]

Build the old binary in a worktree: `git worktree add /tmp/old COMMIT && cmake -S /tmp/old -B
/tmp/old/build -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/old/build --target bench_NAME`.
"""
import argparse
import json
import statistics
import subprocess

from lib.report import load_average, machine, table_head, table_row, write_page


def medians(binary, reps, pattern):
    """{benchmark name: median real time (its unit)} of one run of `binary`."""
    cmd = [binary, f"--benchmark_repetitions={reps}", "--benchmark_report_aggregates_only=true",
           "--benchmark_format=json"]
    if pattern:
        cmd.append(f"--benchmark_filter={pattern}")
    out = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    return {b["run_name"].split("/min_time")[0]: (b["real_time"], b["time_unit"])
            for b in out["benchmarks"] if b.get("aggregate_name") == "median"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--old-label", default="old")
    parser.add_argument("--new-label", default="new")
    parser.add_argument("--rounds", type=int, default=8)
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--filter", default="")
    parser.add_argument("--page", required=True, help="the page's name in docs/results")
    parser.add_argument("--title", default="Before and after")
    args = parser.parse_args()
    load_before = load_average()
    runs = {"old": {}, "new": {}}
    for _ in range(args.rounds):
        for side, binary in (("old", args.old), ("new", args.new)):
            for name, value in medians(binary, args.reps, args.filter).items():
                runs[side].setdefault(name, []).append(value)
    lines = [f"# {args.title}", "",
             f"`python3 bench/studies/bench_ab.py` (method in its docstring): {args.old} "
             f"({args.old_label}) and {args.new} ({args.new_label}) in alternation, "
             f"{args.rounds} rounds, each the median of {args.reps} repetitions.",
             machine(load_before), "",
             *table_head("benchmark", f"{args.old_label} (median)", f"{args.new_label} (median)",
                        "new / old", f"{args.old_label} min–max", f"{args.new_label} min–max")]
    ratios = []
    for name in runs["old"]:
        old = [v for v, _ in runs["old"][name]]
        new = [v for v, _ in runs["new"].get(name, [])]
        if not new:
            continue
        unit = runs["old"][name][0][1]
        ratio = statistics.median(new) / statistics.median(old)
        ratios.append(ratio)
        lines.append(table_row(name, f"{statistics.median(old):.0f} {unit}",
                               f"{statistics.median(new):.0f} {unit}", f"{ratio:.3f}",
                               f"{min(old):.0f}–{max(old):.0f}", f"{min(new):.0f}–{max(new):.0f}"))
    lines += ["", f"Ratios new / old: {min(ratios):.3f} to {max(ratios):.3f}, median "
              f"{statistics.median(ratios):.3f}."]
    print(write_page(args.page, "\n".join(lines) + "\n"))


if __name__ == "__main__":
    main()
