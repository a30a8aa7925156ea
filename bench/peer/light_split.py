#!/usr/bin/python3
"""Whose mean is off where glint and Cycles disagree by 0.2-0.4% on the quad-lit mesh scenes?

  /usr/bin/python3 bench/peer/light_split.py [--spp 1024] [--seeds 4] [--width 160 --height 120]

A closed box lit by a 2 × 2 quad light 1 cm below its ceiling, as scenes/mesh.json without the
knot, rendered by each estimator of each renderer: glint with light sampling (MIS) and without
(BSDF sampling alone), Cycles with light sampling and without (the emitter's Multiple Importance
off), and both again with the same light cut into 512 triangles (a 16 × 16 grid). Each is the
mean of --seeds renders of --spp samples, so its standard error comes from their spread. Prints
each image mean over glint's BSDF-only one, which is the estimate that depends on no light
sampling code at all. Blender is installed from Debian when missing (never in CI).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GLINT = os.path.join(ROOT, "build", "server", "glint")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_cycles import read_pfm  # noqa: E402


def quad(x0, x1, z0, z1, y, n):
    """The light's square as an n × n grid of quads, two triangles each, facing down."""
    vertices, indices = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            vertices.append([x0 + (x1 - x0) * i / n, y, z0 + (z1 - z0) * j / n])
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            indices += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return vertices, indices


def box(light_cells, integrator):
    with open(os.path.join(ROOT, "scenes", "mesh.json")) as f:
        scene = json.load(f)
    objects = scene["objects"][1:4]  # the box's walls, without the knot and the light
    vertices, indices = quad(-1, 1, -1, 1, 3.99, light_cells)
    objects.append({"type": "mesh", "material": {"albedo": 0}, "emission": 12, "vertices": vertices, "indices": indices})
    scene["objects"] = objects
    scene["film"] = {"filter": "box"}
    scene["integrator"] = integrator
    return scene


def glint_mean(path, a, seed):
    pfm = path + f".{seed}.pfm"
    subprocess.run([GLINT, "render", path, "-o", pfm[:-4] + ".png", "--hdr", pfm, "--width", str(a.width),
                    "--height", str(a.height), "--spp", str(a.spp), "--seed", str(seed), "--threads", "2"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return read_pfm(pfm).mean()


def cycles_mean(path, a, seed, bsdf_only):
    out = path + (".bsdf" if bsdf_only else ".ls")
    subprocess.run(["blender", "-b", "--factory-startup", "-noaudio", "-t", "2", "--python",
                    os.path.join(ROOT, "bench", "peer", "cycles_scene.py"), "--", path, "--width", str(a.width),
                    "--height", str(a.height), "--spp", str(a.spp), "--seeds", str(seed), "--out", out]
                   + (["--bsdf-only"] if bsdf_only else []),
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return read_pfm(f"{out}_{a.spp}_{seed}.pfm").mean()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    a = ap.parse_args()
    if not shutil.which("blender"):
        subprocess.run(["apt-get", "install", "-y", "--no-install-recommends", "blender"], check=True)
    work = tempfile.mkdtemp(prefix="light_split.")
    estimators = [
        ("glint, BSDF sampling only", 2, lambda p, s: glint_mean(p, a, s), {"light_sampling": False}),
        ("glint, light sampling", 2, lambda p, s: glint_mean(p, a, s), {}),
        ("Cycles, BSDF sampling only", 2, lambda p, s: cycles_mean(p, a, s, True), {}),
        ("Cycles, light sampling", 2, lambda p, s: cycles_mean(p, a, s, False), {}),
        ("glint, light sampling, light as 512 triangles", 16, lambda p, s: glint_mean(p, a, s), {}),
        ("Cycles, light sampling, light as 512 triangles", 16, lambda p, s: cycles_mean(p, a, s, False), {}),
    ]
    results = []
    for label, cells, mean_of, integrator in estimators:
        path = os.path.join(work, f"box{len(results)}.json")
        with open(path, "w") as f:
            json.dump(box(cells, integrator), f)
        means = np.array([mean_of(path, 1000 + s) for s in range(a.seeds)])
        results.append((label, means.mean(), means.std(ddof=1) / np.sqrt(a.seeds)))
        print(f"{label}: {results[-1][1]:.6f} ± {results[-1][2]:.6f}", flush=True)
    reference, reference_se = results[0][1], results[0][2]
    print(f"\n| estimator | image mean / glint's BSDF-only (± standard error) |\n|---|---|")
    for label, mean, se in results:
        ratio = mean / reference
        print(f"| {label} | {ratio:.4f} ± {ratio * np.hypot(se / mean, reference_se / reference):.4f} |")
    shutil.rmtree(work)


if __name__ == "__main__":
    sys.exit(main())
