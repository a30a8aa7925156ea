#!/usr/bin/python3
"""Time to first pixel on a mesh of about a million triangles, glint against Blender Cycles
(bench/BENCHMARKS.md, "Time to first pixel").

  /usr/bin/python3 bench/peer/first_pixel.py [--segments 8192 --sides 64] [--runs 3]

Writes a torus knot of segments × sides × 2 triangles (8192 × 64 × 2 = 1,048,576; made as
scenes/meshes/make_torus_knot.py makes scenes/mesh.json's) into a temporary scene folder, lit and framed as scenes/mesh.json, and renders one sample per pixel at
256×192 with 2 threads. glint: the whole `glint render` command (OBJ parse, BVH build, one pass,
PNG), and the same at 1×1 pixel, which is load and build alone. Cycles: the render call (scene
sync and BVH build, then one sample), beside the time cycles_scene.py took to hand Blender the
mesh. Medians of --runs, wall seconds, and CPU seconds (user + sys).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

from run_cycles import GLINT, ROOT, timed

sys.path.insert(0, os.path.join(ROOT, "scenes", "meshes"))
import make_torus_knot  # noqa: E402  (found through the path above)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--segments", type=int, default=8192)
    ap.add_argument("--sides", type=int, default=64)
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    folder = tempfile.mkdtemp(prefix="glint-first-pixel-")
    try:
        os.makedirs(os.path.join(folder, "meshes"))
        with open(os.path.join(folder, "meshes", "knot.obj"), "w") as f:
            make_torus_knot.write(f, a.segments, a.sides)
        with open(os.path.join(ROOT, "scenes", "mesh.json")) as f:
            scene = json.load(f)
        scene["objects"][0]["file"] = "meshes/knot.obj"
        scene["film"]["filter"] = "box"
        path = os.path.join(folder, "knot.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        out = os.path.join(folder, "out")
        size = ["--width", "256", "--height", "192", "--spp", "1", "--threads", "2"]
        rows = {"glint, load and build (1x1 pixel)": [], "glint, load, build and 1 spp": [],
                "Cycles, render call (sync, BVH, 1 spp)": [], "Cycles, mesh handed to Blender (script)": []}
        for _ in range(a.runs):
            rows["glint, load and build (1x1 pixel)"].append(
                timed([GLINT, "render", path, "-o", out + ".png", "--width", "1", "--height", "1", "--spp", "1", "--threads", "2"]))
            rows["glint, load, build and 1 spp"].append(timed([GLINT, "render", path, "-o", out + ".png"] + size))
            log = out + ".jsonl"
            if os.path.exists(log):
                os.remove(log)
            subprocess.run(["blender", "-b", "--factory-startup", "-noaudio", "-t", "2", "--python",
                            os.path.join(ROOT, "bench", "peer", "cycles_scene.py"), "--", path, "--width", "256",
                            "--height", "192", "--spp", "1", "--seeds", "1", "--out", out],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            with open(log) as f:
                r = json.loads(f.readline())
            rows["Cycles, render call (sync, BVH, 1 spp)"].append((r["cpu"], r["wall"]))
            rows["Cycles, mesh handed to Blender (script)"].append((float("nan"), r["import"]))
        print(f"{a.segments * a.sides * 2:,} triangles, 256x192, 1 spp, 2 threads; median of {a.runs}")
        print("| step | wall s | CPU s |\n|---|---|---|")
        for name, values in rows.items():
            print(f"| {name} | {statistics.median(v[1] for v in values):.2f} | {statistics.median(v[0] for v in values):.2f} |")
    finally:
        shutil.rmtree(folder)


if __name__ == "__main__":
    main()
