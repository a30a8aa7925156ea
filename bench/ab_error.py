#!/usr/bin/python3
"""Two glint binaries on the same scenes: which reaches a given error sooner? For a change that
alters the estimator (a sampling distribution, a strategy) but not the image it converges to.

  /usr/bin/python3 bench/ab_error.py --old OLD_GLINT --new NEW_GLINT [--scenes environment,PATH.json,...]
        [--width 160 --height 120] [--spp 64] [--seeds 8] [--reference-spp 4096]
        [--old-set integrator.guiding=off] [--new-set integrator.guiding=on]

--old-set and --new-set (repeatable) set a field of each side's scene, its value read as JSON
where it parses as JSON: one binary against itself with another setting. Each side's scene is
then written beside the scene file, as a hidden file removed afterwards, so its meshes are found.

For each scene: a reference made of one render by each binary at --reference-spp (other seeds),
so that neither is charged for the other's noise, and its own noise, (A - B)²/4, taken off each
error; then --seeds renders by each binary at --spp, alternating old and new so that both see the
same machine. Reports each binary's MSE (mean over the seeds) and CPU seconds (median, user +
sys of the whole command), and how much sooner the new binary reaches equal error:
(MSE_old · CPU_old) / (MSE_new · CPU_new), MSE falling as 1/time.
"""
import argparse
import contextlib
import json
import os
import resource
import statistics
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench", "peer"))
from run_cycles import read_pfm  # noqa: E402


def render(glint, scene, a, spp, seed, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([glint, "render", scene, "-o", out + ".png", "--hdr", out + ".pfm", "--width", str(a.width),
                    "--height", str(a.height), "--spp", str(spp), "--seed", str(seed), "--threads", "2"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return read_pfm(out + ".pfm"), after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


@contextlib.contextmanager
def scene_with(scene, settings, tag):
    """The scene file, or a hidden copy beside it with `settings` (["a.b=value", ...]) applied."""
    if not settings:
        yield scene
        return
    with open(scene) as f:
        root = json.load(f)
    for setting in settings:
        path, value = setting.split("=", 1)
        try:
            value = json.loads(value)
        except json.JSONDecodeError:
            pass
        node = root
        *parents, key = path.split(".")
        for part in parents:
            node = node.setdefault(part, {})
        node[key] = value
    copy = os.path.join(os.path.dirname(scene), f".ab_{tag}_{os.getpid()}_{os.path.basename(scene)}")
    with open(copy, "w") as f:
        json.dump(root, f)
    try:
        yield copy
    finally:
        os.remove(copy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--scenes", default="environment,environment_sun")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--reference-spp", type=int, default=4096)
    ap.add_argument("--out", default="/tmp/ab_error")
    ap.add_argument("--old-set", action="append", default=[])
    ap.add_argument("--new-set", action="append", default=[])
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print("| scene | MSE old | MSE new | CPU s old | CPU s new | new reaches equal error |")
    print("|---|---|---|---|---|---|")
    for name in a.scenes.split(","):
        scene = name if name.endswith(".json") else os.path.join(ROOT, "scenes", name + ".json")
        name = os.path.basename(name).removesuffix(".json")
        with scene_with(scene, a.old_set, "old") as old, scene_with(scene, a.new_set, "new") as new:
            runs = compare(a, name, {"old": old, "new": new})
        mse = {k: statistics.mean(r[0] for r in v) for k, v in runs.items()}
        cpu = {k: statistics.median(r[1] for r in v) for k, v in runs.items()}
        sooner = mse["old"] * cpu["old"] / (mse["new"] * cpu["new"])
        print(f"| {name} | {mse['old']:.3g} | {mse['new']:.3g} | {cpu['old']:.2f} | {cpu['new']:.2f} | {sooner:.2f}× |",
              flush=True)


def compare(a, name, scenes):
    """Each side's (error, CPU seconds) per seed, against a reference made of one render by each."""
    ra, _ = render(a.old, scenes["old"], a, a.reference_spp, 1001, os.path.join(a.out, name + "_ref_old"))
    rb, _ = render(a.new, scenes["new"], a, a.reference_spp, 1002, os.path.join(a.out, name + "_ref_new"))
    reference, ref_mse = (ra + rb) / 2, float(np.mean((ra - rb) ** 2) / 4)
    runs = {"old": [], "new": []}
    for seed in range(1, a.seeds + 1):
        for which in ("old", "new"):
            image, cpu = render(getattr(a, which), scenes[which], a, a.spp, seed, os.path.join(a.out, f"{name}_{which}"))
            runs[which].append((float(np.mean((image - reference) ** 2)) - ref_mse, cpu))
    return runs


if __name__ == "__main__":
    sys.exit(main())
