#!/usr/bin/python3
"""Plots and tables from bench/run_speed_vs_error.sh's CSV.

Writes bench/plots/<scene>.svg (RMSE against wall time, log-log, one line per mode) and the
tables (every rung, and each mode's efficiency relative to smallpt) into bench/BENCHMARKS.md,
between its speed_vs_error markers.
Needs Debian's python3-matplotlib.
"""
import csv
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MODES = ["glint", "no-lt", "no-nee", "no-bvh", "smallpt"]
LABELS = {
    "glint": "glint (auto accelerator, light sampling + MIS, light tracing where caustics)",
    "no-lt": "glint without light tracing",
    "no-nee": "BVH, no light sampling",
    "no-bvh": "light sampling, no BVH",
    "smallpt": "smallpt-equivalent (neither)",
}


def load(path):
    runs = defaultdict(lambda: defaultdict(list))
    with open(path) as f:
        for row in csv.DictReader(f):
            runs[row["scene"]][row["mode"]].append(
                (int(row["spp"]), float(row["seconds"]), float(row["rmse"]), float(row["estimate"])))
    return runs


def plot(scene, modes, out):
    fig, ax = plt.subplots(figsize=(6, 4))
    for mode in MODES:
        if mode in modes:
            rows = modes[mode]
            ax.loglog([r[1] for r in rows], [r[2] for r in rows], marker="o", markersize=3, label=LABELS[mode])
    ax.set_xlabel("wall time (s), 2 threads")
    ax.set_ylabel("RMSE against reference")
    ax.set_title(f"{scene}: error against time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def efficiency(rows):
    """1 / (RMSE² · seconds) at the last rung: constant for an unbiased estimator."""
    spp, seconds, error, _ = rows[-1]
    return 1 / (error * error * seconds)


def tables(runs):
    lines = []
    for scene, modes in runs.items():
        base = efficiency(modes["smallpt"]) if "smallpt" in modes else None
        lines += [f"### {scene}", "", f"![{scene}: error against time](plots/{scene}.svg)", "",
                  "| mode | spp | seconds | RMSE | estimated | estimated / RMSE | efficiency vs smallpt |",
                  "|---|---|---|---|---|---|---|"]
        for mode in MODES:
            for i, (spp, seconds, error, estimate) in enumerate(modes.get(mode, [])):
                last = i == len(modes[mode]) - 1
                ratio = f"{efficiency(modes[mode]) / base:.2f}×" if last and base else ""
                lines.append(f"| {mode} | {spp} | {seconds:.3f} | {error:.4g} | {estimate:.4g} | "
                             f"{estimate / error:.2f} | {ratio} |")
        lines.append("")
    return "\n".join(lines)


def main():
    csv_path = Path(sys.argv[1])
    bench = csv_path.parent.parent
    runs = load(csv_path)
    (bench / "plots").mkdir(exist_ok=True)
    for scene, modes in runs.items():
        plot(scene, modes, bench / "plots" / f"{scene}.svg")
    doc = bench / "BENCHMARKS.md"
    text = doc.read_text()
    begin, end = "<!-- speed_vs_error:begin -->", "<!-- speed_vs_error:end -->"
    head, rest = text.split(begin)
    _, tail = rest.split(end)
    doc.write_text(head + begin + "\n" + tables(runs) + end + tail)


if __name__ == "__main__":
    main()
