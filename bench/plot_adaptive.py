#!/usr/bin/python3
"""Adaptive against plain sampling from bench/run_adaptive.sh's CSV.

RMSEs are against a reference, its own noise taken out (bench/adaptive_vs_plain.cpp); the RMSE
measured by pairs of seeds, blind to a bias, is shown beside it. For each adaptive render, the
target is
the RMSE it reached; the plain renders' CPU time to that RMSE is read off their ladder (log-log
interpolation between rungs; past the ladder, extrapolated with RMSE²·time constant, as for an
unbiased estimator, and marked *). Medians over repeats. Writes bench/plots/adaptive.svg and
the table between the adaptive markers of bench/BENCHMARKS.md. Needs python3-matplotlib.
"""
import csv
import math
import statistics
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    """scene -> (mode, threshold, spp) -> [(cpu, rmse, mean_spp)]"""
    runs = defaultdict(lambda: defaultdict(list))
    with open(path) as f:
        for row in csv.DictReader(f):
            key = (row["mode"], float(row["threshold"]), int(row["spp"]))
            runs[row["scene"]][key].append((float(row["cpu"]), float(row["rmse"]), float(row["mean_spp"]),
                                            float(row["rmse_pairs"])))
    return runs


def median_point(samples):
    return tuple(statistics.median(s[i] for s in samples) for i in range(4))


def time_to(ladder, target):
    """CPU seconds for the plain ladder [(cpu, rmse)] (by spp) to reach `target`; extrapolated?"""
    for (t0, e0), (t1, e1) in zip(ladder, ladder[1:]):
        if e1 <= target <= e0:
            f = math.log(e0 / target) / math.log(e0 / e1)
            return math.exp(math.log(t0) + f * math.log(t1 / t0)), False
    t, e = ladder[-1] if target < ladder[-1][1] else ladder[0]
    return t * (e / target) ** 2, True


def main(path):
    runs = load(path)
    rows, scenes = [], sorted(runs)
    fig, axes = plt.subplots(1, len(scenes), figsize=(3.2 * len(scenes), 3.2), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        plain = sorted((k[2], median_point(v)) for k, v in runs[scene].items() if k[0] == "plain")
        ladder = [(p[0], p[1]) for _, p in plain]
        ax.loglog([p[0] for p in ladder], [p[1] for p in ladder], "o-", label="plain")
        for (mode, threshold, spp), samples in sorted(runs[scene].items()):
            if mode != "adaptive":
                continue
            cpu, err, mean_spp, pairs = median_point(samples)
            plain_cpu, extrapolated = time_to(ladder, err)
            ax.loglog([cpu], [err], "s", label=f"adaptive {threshold:g}")
            rows.append((scene, threshold, spp, err, pairs, plain_cpu, extrapolated, cpu, mean_spp, plain_cpu / cpu))
        ax.set_title(scene)
        ax.set_xlabel("CPU seconds")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("RMSE against the reference")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    Path("bench/plots").mkdir(parents=True, exist_ok=True)
    fig.savefig("bench/plots/adaptive.svg")
    table = ["| scene | threshold (max spp) | RMSE reached (by pairs) | CPU s, plain | CPU s, adaptive | mean spp | "
             "plain / adaptive |",
             "|---|---|---|---|---|---|---|"]
    for scene, threshold, spp, err, pairs, plain_cpu, extra, cpu, mean_spp, ratio in rows:
        table.append(f"| {scene} | {threshold:g} ({spp}) | {err:.4g} ({pairs:.4g}) | "
                     f"{plain_cpu:.2f}{'*' if extra else ''} | {cpu:.2f} | {mean_spp:.0f} | {ratio:.2f}× |")
    print("\n".join(table))
    md = Path("bench/BENCHMARKS.md")
    text = md.read_text()
    begin, end = "<!-- adaptive:begin -->", "<!-- adaptive:end -->"
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        md.write_text(head + begin + "\n" + "\n".join(table) + "\n" + end + rest.split(end, 1)[1])


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/results/adaptive.csv")
