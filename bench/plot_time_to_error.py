#!/usr/bin/python3
"""Time to a given error from bench/run_time_to_error.sh's CSV.

The target error of a scene is the RMSE the smallpt-equivalent mode reaches at its last rung
(1024 spp on the Cornell box); where that mode cannot get past a few samples per pixel in the
time allowed (brute force over the mesh scene's 8,204 triangles), the RMSE the previous version
reaches at its last rung. For every version and mode, the time to reach it is read off its
ladder (log-log interpolation between the rungs around it; past the last rung, extrapolated with
RMSE²·time constant, as for an unbiased estimator, and marked *). Medians over repeats.
Writes bench/plots/tte-<scene>.svg and the table between the time_to_error markers of
bench/BENCHMARKS.md. Needs Debian's python3-matplotlib.
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

LABELS = {
    ("glint", "glint"): "glint (auto: cap light sampling + MIS, Sobol' film, light paths splatted and connected)",
    ("glint", "no-lt"): "glint without light paths",
    ("c02a220", "glint"): "glint before connections (c02a220: light-traced caustics seen directly)",
    ("glint", "smallpt"): "smallpt-equivalent mode (baseline)",
    ("d505f08", "glint"): "previous glint (d505f08)",
}


def load(path):
    runs = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    with open(path) as f:
        for row in csv.DictReader(f):
            runs[row["scene"]][(row["version"], row["mode"])][row["repeat"]].append(
                (int(row["spp"]), float(row["seconds"]), float(row["rmse"])))
    return runs


def time_to(rungs, target):
    """Seconds to reach RMSE `target`, and whether it was extrapolated."""
    previous = None
    for spp, t, e in rungs:
        if e <= target:
            if previous is None:
                return t * (e / target) ** 2, True
            t0, e0 = previous
            f = math.log(e0 / target) / math.log(e0 / e)
            return math.exp(math.log(t0) + f * math.log(t / t0)), False
        previous = (t, e)
    spp, t, e = rungs[-1]
    return t * (e / target) ** 2, True


def plot(scene, modes, target, out):
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, repeats in modes.items():
        rungs = repeats[sorted(repeats)[0]]
        ax.plot([r[1] for r in rungs], [r[2] for r in rungs], marker="o", ms=3, label=LABELS.get(key, str(key)))
    ax.axhline(target, color="grey", ls=":", lw=1, label="target RMSE")
    save_error_plot(fig, ax, f"{scene}: error against time (256x192)", "RMSE against reference", out)


def save_error_plot(fig, ax, title, ylabel, out):
    """Log-log axes of error against wall time, saved to `out`."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time, 2 threads (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def main():
    runs = load(sys.argv[1])
    root = Path(__file__).resolve().parent
    lines = []
    for scene, modes in runs.items():
        baseline = modes[("glint", "smallpt")]
        reference = baseline
        if baseline[sorted(baseline)[0]][-1][0] < 256:
            reference = modes[("d505f08", "glint")]
        target = statistics.median(rungs[-1][2] for rungs in reference.values())
        target_spp = reference[sorted(reference)[0]][-1][0]
        target_mode = "smallpt mode" if reference is baseline else "d505f08"
        plot(scene, modes, target, root / "plots" / f"tte-{scene}.svg")
        times = {}
        for key, repeats in modes.items():
            results = [time_to(rungs, target) for rungs in repeats.values()]
            times[key] = (statistics.median(r[0] for r in results), any(r[1] for r in results), len(results))
        lines += [f"### {scene}", "", f"![{scene}: error against time](plots/tte-{scene}.svg)", "",
                  f"Target RMSE {target:.4g} ({target_mode} at {target_spp} spp).", "",
                  "| version, mode | time to target (s) | vs smallpt mode | vs d505f08 | repeats |",
                  "|---|---|---|---|---|"]
        old = times.get(("d505f08", "glint"))
        for key, (t, extrapolated, n) in times.items():
            star = "*" if extrapolated else ""
            vs_old = f"{old[0] / t:.2f}×" if old else ""
            lines.append(f"| {LABELS.get(key, key)} | {t:.2f}{star} | {times[('glint', 'smallpt')][0] / t:.2f}× | "
                         f"{vs_old} | {n} |")
        lines.append("")
    md = root / "BENCHMARKS.md"
    text = md.read_text()
    begin, end = "<!-- time_to_error:begin -->", "<!-- time_to_error:end -->"
    head, rest = text.split(begin)
    _, tail = rest.split(end)
    md.write_text(head + begin + "\n" + "\n".join(lines) + end + tail)


if __name__ == "__main__":
    main()
