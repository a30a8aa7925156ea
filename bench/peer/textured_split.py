#!/usr/bin/python3
"""Where glint and Cycles differ on the textured scene: its sky and its sun apart, and whose mean is off.

  /usr/bin/python3 bench/peer/textured_split.py [--spp 1024] [--width 160 --height 120] [--glint PATH]

run_cycles.py's variant textured_diffuse (the scene's sun an icosphere of 1,280 triangles) with
the sun off (the sky alone) and with the sky black (the sun alone), each rendered twice (seeds 101
and 102, --spp) by each renderer: prints glint's image mean over Cycles' with its standard error
(from the pixels' spread between the two renders), and the ratio of their MSE per sample at 256
spp (seed 7; each against its own pair of renders, their noise taken off, as run_cycles.py).
Then a 12 × 12 floor of albedo 0.5 under the same
icosphere alone, seen from 8 units straight above: a pixel's exact radiance is albedo/π times the
sun's radiance times the projected solid angle of the icosphere's faces that face it (Lambert's
formula for each triangle; the others are hidden behind them), and each renderer's image mean is
printed over that exact one. The glint binary: --glint, else $GLINT, else build/server/glint.
"""
import argparse
import json
import os
import shutil
import sys
import tempfile
import types

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_cycles  # noqa: E402

ROOT = run_cycles.ROOT
SEEDS = (101, 102)


def renders(path, work, name, a, ladder=False):
    """Two renders (seeds 101, 102) by each renderer, and with `ladder` one of 256 spp (seed 7):
    {renderer: {(spp, seed): (image, cpu, wall)}}."""
    out = {"glint": {}, "cycles": {}}
    jobs = [(a.spp, seed) for seed in SEEDS] + ([(256, run_cycles.SEEDS["ladder"])] if ladder else [])
    for spp, seed in jobs:
        out["glint"][(spp, seed)] = run_cycles.run_glint(path, os.path.join(work, name + "_glint"), a, spp, seed)
        out["cycles"][(spp, seed)] = run_cycles.run_cycles(path, os.path.join(work, name + "_cycles"), a, spp, seed)
    return out


def mean_and_error(results, spp):
    """The mean of the two renders of `spp`, and its standard error from their pixels' spread."""
    first, second = (results[(spp, seed)][0].mean(axis=2) for seed in SEEDS)
    return (first.mean() + second.mean()) / 2, np.sqrt(np.mean((first - second) ** 2) / (4 * first.size))


def variant(name, change):
    """textured_diffuse as run_cycles writes it, changed, beside the scene (its files resolve)."""
    path, _ = run_cycles.box_filter_copies("textured_diffuse")
    with open(path) as f:
        scene = json.load(f)
    os.remove(path)
    change(scene)
    path = os.path.join(ROOT, "scenes", f".peer-{name}.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def sun_off(scene):
    scene["objects"][1]["emission"] = 0


def sky_off(scene):
    scene["film"]["background"] = 0


def floor_scene(sun):
    return {"camera": {"position": [0, 8, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 40},
            "film": {"filter": "box"},
            "objects": [{"type": "mesh", "material": {"albedo": 0.5}, "vertices": [[-6, 0, -6], [6, 0, -6], [6, 0, 6],
                                                                                   [-6, 0, 6]],
                         "indices": [[0, 2, 1], [0, 3, 2]]}, sun]}


def exact_floor(scene, width, height):
    """Each pixel centre's radiance on the floor: albedo/π · L · (projected solid angle of the sun)."""
    sun = scene["objects"][1]
    v = np.array(sun["vertices"], np.float32).astype(float)  # as both renderers keep them
    f = np.array(sun["indices"])
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    normals, centres = np.cross(b - a, c - a), (a + b + c) / 3
    half = np.tan(np.radians(scene["camera"]["fov"]) / 2)
    x = ((np.arange(width) + 0.5) / width * 2 - 1) * half * width / height
    y = (1 - (np.arange(height) + 0.5) / height * 2) * half
    xs, ys = np.meshgrid(x, y)  # camera right is +x, up is -z, forward -y, 8 above the floor
    points = np.stack([8 * xs, np.zeros_like(xs), -8 * ys], axis=-1).reshape(-1, 3)
    psa = np.zeros(len(points))
    for k in range(0, len(points), 2000):
        p = points[k:k + 2000, None, :]
        facing = np.einsum("tj,ptj->pt", normals, p - centres[None]) > 0
        corners = [a[None] - p, b[None] - p, c[None] - p]
        total = np.zeros(facing.shape)
        for i, j in ((0, 1), (1, 2), (2, 0)):
            cross = np.cross(corners[i], corners[j])
            norm = np.linalg.norm(cross, axis=-1)
            angle = np.arctan2(norm, np.einsum("ptk,ptk->pt", corners[i], corners[j]))
            total += angle * cross[..., 1] / norm  # the floor's normal is +y
        psa[k:k + 2000] = np.abs(np.where(facing, total / 2, 0)).sum(axis=1)
    radiance = 0.5 / np.pi * np.array(sun["emission"], float)
    return psa.reshape(height, width)[::-1, :, None] * radiance  # bottom row first, as the PFMs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--glint", default=run_cycles.GLINT)
    a = ap.parse_args()
    run_cycles.GLINT = a.glint
    work = tempfile.mkdtemp(prefix="textured_split.")
    print("| textured_diffuse lit by | glint / Cycles, image mean (± standard error) | MSE per sample at 256 spp, "
          "glint / Cycles |\n|---|---|---|")
    ladder = types.SimpleNamespace(ladder=[256], reference_spp=a.spp)
    for name, change in (("sky alone", sun_off), ("sun alone", sky_off)):
        path = variant(name.replace(" ", "_"), change)
        try:
            images = renders(path, work, name.replace(" ", "_"), a, ladder=True)
        finally:
            os.remove(path)
        (g, g_se), (c, c_se) = mean_and_error(images["glint"], a.spp), mean_and_error(images["cycles"], a.spp)
        mse = [run_cycles.measure(images[r], ladder)[2][0]["mse"] for r in ("glint", "cycles")]
        print(f"| the {name} | {g / c:.5f} ± {g / c * np.hypot(g_se / g, c_se / c):.5f} | {mse[0] / mse[1]:.2f} |",
              flush=True)
    with open(os.path.join(ROOT, "scenes", "textured.json")) as f:
        sun = json.load(f)["objects"][1]
    sun = {"type": "mesh", "material": {"albedo": 0}, "emission": sun["emission"],
           **run_cycles.icosphere(sun["center"], sun["radius"], 3)}
    scene = floor_scene(sun)
    path = os.path.join(work, "floor.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    exact = exact_floor(scene, a.width, a.height).mean()
    images = renders(path, work, "floor", a)
    print("\n| the floor under the sun alone | image mean / exact (± standard error) |\n|---|---|")
    for renderer in ("glint", "cycles"):
        m, se = mean_and_error(images[renderer], a.spp)
        print(f"| {renderer} | {m / exact:.5f} ± {se / exact:.5f} |")
    shutil.rmtree(work)


if __name__ == "__main__":
    sys.exit(main())
