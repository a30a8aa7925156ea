#!/usr/bin/python3
"""The denoised preview against the unbiased image, from bench/run_denoise.sh's CSV.

Plots relMSE and RMSE against CPU time (user + sys: the render's so far; the denoised image adds
the denoiser's) per scene to bench/plots/denoise.svg, and prints the table for
bench/BENCHMARKS.md: per scene and rung, both images' RMSE and relMSE, their ratio and the
denoiser's CPU time. Needs Debian's python3-matplotlib.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    rows = defaultdict(list)
    with open(path) as f:
        for row in csv.DictReader(f):
            rows[row["scene"]].append({k: (v if k == "scene" else float(v)) for k, v in row.items()})
    return rows


def plot(rows, out):
    fig, axes = plt.subplots(2, len(rows), figsize=(3.2 * len(rows), 6.4), squeeze=False)
    for col, (scene, ladder) in enumerate(rows.items()):
        t = [r["render_cpu"] for r in ladder]
        td = [r["render_cpu"] + r["denoise_cpu"] for r in ladder]
        for row, metric in enumerate(["relmse", "rmse"]):
            ax = axes[row][col]
            ax.loglog(t, [r[metric] for r in ladder], "o-", label="unbiased")
            ax.loglog(td, [r[metric + "_denoised"] for r in ladder], "s-", label="denoised")
            ax.set_title(f"{scene}: {metric}" if row == 0 else "", fontsize=9)
            ax.set_xlabel("CPU s (user + sys)", fontsize=8)
            ax.set_ylabel(metric if col == 0 else "", fontsize=8)
            ax.grid(True, which="both", alpha=0.3)
            if row == 0 and col == 0:
                ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)


def montage(folder, out, scenes=("caustic", "cornell", "mesh")):
    """The 16 spp rung, unbiased and denoised, beside the reference: the caustic under the glass
    ball, the mirror ball's reflections, the torus knot's edges."""
    import matplotlib.image as mpimg
    fig, axes = plt.subplots(len(scenes), 3, figsize=(12, 2.4 * len(scenes)), squeeze=False)
    for r, scene in enumerate(scenes):
        for c, (name, title) in enumerate([(f"{scene}-16spp.png", "16 spp unbiased"),
                                           (f"{scene}-16spp.denoised.png", "16 spp denoised"),
                                           ("reference.png", "reference")]):
            axes[r][c].imshow(mpimg.imread(f"{folder}/{scene}/{name}"), interpolation="nearest")
            axes[r][c].set_title(f"{scene}: {title}", fontsize=8)
            axes[r][c].axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def table(rows):
    print("| scene | spp | render CPU s | RMSE unbiased | RMSE denoised | relMSE unbiased | relMSE denoised | relMSE ratio | denoiser CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, ladder in rows.items():
        for r in ladder:
            ratio = r["relmse_denoised"] / r["relmse"] if r["relmse"] > 0 else float("nan")
            print(f"| {scene} | {int(r['spp'])} | {r['render_cpu']:.2f} | {r['rmse']:.4g} | {r['rmse_denoised']:.4g} | "
                  f"{r['relmse']:.4g} | {r['relmse_denoised']:.4g} | {ratio:.3f} | {r['denoise_cpu']:.2f} |")


if __name__ == "__main__":
    data = load(sys.argv[1] if len(sys.argv) > 1 else "bench/results/denoise.csv")
    plot(data, "bench/plots/denoise.svg")
    montage("bench/out/denoise", "bench/plots/denoise_16spp.png")
    table(data)
