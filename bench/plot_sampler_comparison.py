#!/usr/bin/python3
"""Time to error before and after a sampler change, from bench/run_sampler_comparison.sh's CSV.

Arguments: the ladders' CSV, the seeds' CSV, the folder of the references, the previous
version's name, and the references' size-and-spp suffix. Errors are RMSE against the reference
with the reference's own estimated error taken out (for independent unbiased images the squared
RMSE between them is the sum of their MSEs; the estimate is honest for this version's
references).

High target: this version's error at 4096 spp. Each version's time to it is read off its ladder
(log-log interpolation between rungs); a version whose ladder never gets there is reported as
not reaching it, since its error need not keep falling. Low target: at 64 spp one seed's error
is too noisy to compare, so each version's MSE there is the mean over the seeds' renders, and
its time to this version's MSE is its mean time scaled by its MSE over this version's (time to
an error scales with the MSE where the MSE falls as 1/spp).
Writes bench/plots/sampler-<scene>.svg and the table between the sampler_comparison markers of
bench/BENCHMARKS.md. Needs Debian's python3-matplotlib.
"""
import array
import csv
import math
import statistics
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_time_to_error import save_error_plot, time_to  # noqa: E402


def load(path, references, suffix):
    ladders = defaultdict(dict)
    for row in csv.DictReader(open(path)):
        ladders[row["scene"]].setdefault(row["version"], []).append(
            (int(row["spp"]), float(row["seconds"]), float(row["rmse"]), float(row["estimate"])))
    noise = {}
    for scene in ladders:
        estimate = Path(references) / scene / f"reference-{suffix}.pfm.estimate"
        noise[scene] = float(estimate.read_text()) if estimate.exists() else 0.0
    return ladders, noise


def read_pfm(path):
    data = Path(path).read_bytes()
    _, size, _, pixels = data.split(b"\n", 3)
    width, height = map(int, size.split())
    values = array.array("f")
    values.frombytes(pixels[:width * height * 12])
    return values


def seed_errors(path, references, suffix, noise):
    """Per scene and version: the mean MSE over the seeds, its standard error, and the mean time."""
    renders = defaultdict(lambda: defaultdict(list))
    for row in csv.DictReader(open(path)):
        renders[row["scene"]][row["version"]].append((float(row["seconds"]), row["image"]))
    result = defaultdict(dict)
    for scene, versions in renders.items():
        reference = read_pfm(Path(references) / scene / f"reference-{suffix}.pfm")
        for version, runs in versions.items():
            mse = []
            for _, image in runs:
                values = read_pfm(image)
                mse.append(sum((a - b) ** 2 for a, b in zip(values, reference)) / len(values) - noise[scene] ** 2)
            result[scene][version] = (statistics.mean(mse), statistics.stdev(mse) / math.sqrt(len(mse)),
                                      statistics.mean(t for t, _ in runs), len(runs))
    return result


def true_error(rungs, reference_noise):
    return [(spp, t, math.sqrt(max(1e-24, e * e - reference_noise ** 2)), est) for spp, t, e, est in rungs]


def reached(rungs, target):
    """Seconds to reach `target`, or None where the ladder never gets there."""
    if min(r[2] for r in rungs) > target:
        return None
    return time_to([(spp, t, e) for spp, t, e, _ in rungs], target)[0]


def at_spp(rungs, spp):
    return next(r for r in rungs if r[0] == spp)


def plot(scene, ladders, targets, previous, out):
    fig, ax = plt.subplots(figsize=(6, 4))
    for version, rungs in ladders.items():
        label = "this version" if version == "after" else previous
        line, = ax.plot([r[1] for r in rungs], [r[2] for r in rungs], marker="o", ms=3, label=f"{label}: RMSE")
        ax.plot([r[1] for r in rungs], [r[3] for r in rungs], ls="--", lw=1, color=line.get_color(),
                label=f"{label}: its own estimate")
    for name, target in targets.items():
        ax.axhline(target, color="grey", ls=":", lw=1, label=f"{name} target")
    save_error_plot(fig, ax, f"{scene}: error against time, 4 to 4096 spp", "RMSE against the converged image", out)


def seconds(t):
    return f"{t:.2f}" if t is not None else "not reached"


def main():
    ladder_csv, seeds_csv, references, previous, suffix = sys.argv[1:6]
    ladders, noise = load(ladder_csv, references, suffix)
    seeds = seed_errors(seeds_csv, references, suffix, noise)
    root = Path(__file__).resolve().parent
    lines = [f"| scene | target | RMSE | this version (s) | {previous} (s) | sooner |", "|---|---|---|---|---|---|"]
    errors = [f"| scene | spp | RMSE, this version | its estimate | RMSE, {previous} | its estimate |",
              "|---|---|---|---|---|---|"]
    for scene in ladders:
        versions = {v: true_error(r, noise[scene]) for v, r in ladders[scene].items()}
        after = versions["after"]
        new_mse, new_se, new_t, n = seeds[scene]["after"]
        old_mse, old_se, old_t, _ = seeds[scene]["before"]
        old_to_new = old_t * old_mse / new_mse
        lines.append(f"| {scene} | low (64 spp, {n} seeds) | {math.sqrt(new_mse):.4g} | {new_t:.2f} | "
                     f"{old_to_new:.2f} | {old_to_new / new_t:.2f}× (MSE {old_mse:.3g} ± {old_se:.2g} against "
                     f"{new_mse:.3g} ± {new_se:.2g}) |")
        high = at_spp(after, 4096)[2]
        plot(scene, versions, {"high (4096 spp)": high}, previous, root / "plots" / f"sampler-{scene}.svg")
        new, old = reached(after, high), reached(versions["before"], high)
        ratio = f"{old / new:.2f}×" if old is not None else "—"
        lines.append(f"| {scene} | high (4096 spp) | {high:.4g} | {seconds(new)} | {seconds(old)} | {ratio} |")
        for spp in (64, 4096):
            a, b = at_spp(after, spp), at_spp(versions["before"], spp)
            errors.append(f"| {scene} | {spp} | {a[2]:.4g} | {a[3]:.4g} | {b[2]:.4g} | {b[3]:.4g} |")
    plots = " ".join(f"![{s}](plots/sampler-{s}.svg)" for s in ladders)
    md = root / "BENCHMARKS.md"
    text = md.read_text()
    begin, end = "<!-- sampler_comparison:begin -->", "<!-- sampler_comparison:end -->"
    head, rest = text.split(begin)
    _, tail = rest.split(end)
    md.write_text(head + begin + "\n" + "\n".join(lines) + "\n\nOne seed's ladder, for the plots:\n\n" +
                  "\n".join(errors) + "\n\n" + plots + "\n" + end + tail)


if __name__ == "__main__":
    main()
