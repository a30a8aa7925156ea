#!/usr/bin/python3
"""glint against Blender Cycles on every mesh scene in scenes/, on variants of them with rough
mirrors and glass, and on the textured scene as Cycles 3.4 can hold it (VARIANTS): do they
converge to the same image, and how long does each take to reach the same error?
(bench/BENCHMARKS.md, "Against Blender Cycles"; the scene translation is bench/peer/cycles_scene.py.)

  /usr/bin/python3 bench/peer/run_cycles.py [--scenes mesh,cornell_box] [--width 160 --height 120]
                                            [--ladder 4,16,64,256] [--reference-spp 1024]
                                            [--repeat N] [--glint PATH] [--results NAME] [--update]

Installs Blender from Debian when it is missing (about 400 MB: never in CI). Both renderers run
at 2 threads with a box pixel filter of width 1. For each scene and renderer: a ladder of renders
(one per spp) and a reference made of two renders with other seeds; each render by glint is
followed at once by the same by Cycles. A renderer's error is measured
against its own reference, and the reference's own noise, (A - B)²/4 from its two halves, is taken
off, so that neither is charged for the other's conventions; whether the two references agree is
reported beside it. CPU seconds are the process's user + sys over the render (Cycles: the render
call, scene sync included; glint: the whole command, scene load and BVH build included).
Writes bench/results/peer_cycles.csv (and _summary.json) and bench/plots/peer_cycles.svg, or with
--results NAME bench/results/NAME.csv and bench/plots/NAME.svg (--update keeps the other scenes'
rows there), and prints a table. The glint binary: --glint, else $GLINT, else build/server/glint.
"""
import argparse
import csv
import json
import os
import resource
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GLINT = os.environ.get("GLINT", os.path.join(ROOT, "build", "server", "glint"))
SEEDS = {"ladder": 7, "reference": (101, 102)}


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise ValueError(f"{path}: not a colour PFM")
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3).astype(np.float64)


def mesh_scenes():
    names = []
    for file in sorted(os.listdir(os.path.join(ROOT, "scenes"))):
        if file.endswith(".json") and not file.startswith("."):
            with open(os.path.join(ROOT, "scenes", file)) as f:
                objects = json.load(f).get("objects", [])
            if all(o.get("type") == "mesh" for o in objects):
                names.append(file[:-5])
    return names


ENVIRONMENT_EDITS = ({0: {"type": "diffuse", "albedo": 0.45},
                      1: {"type": "mirror", "albedo": [0.95, 0.64, 0.37], "roughness": 0.2},
                      2: {"type": "diffuse", "albedo": [0.7, 0.08, 0.05]},
                      3: {"type": "mirror", "albedo": 0.9}},
                     {2: {"as_mesh": 4}, 3: {"as_mesh": 4}, 4: {"as_mesh": 4}})

CYCLES_BALLS = {2: {"as_mesh": 5, "smooth": True}, 3: {"as_mesh": 5, "smooth": True},
                4: {"as_mesh": 5, "smooth": True}}

# Variants of the scenes: a base scene, the materials that replace its objects' (`material`),
# optionally edits of its objects (fields set, None: removed; `as_mesh`: a sphere made an
# icosphere of that many subdivisions, its material and emission kept, smooth-shaded with
# `smooth`), and optionally edits made for Cycles alone.
# Rough glass is left out: Cycles 3.4's rough Glass BSDF takes its Fresnel term at the shading
# normal, not the microfacet's, so it is another surface.
VARIANTS = {
    "mesh_rough": ("mesh", {0: {"type": "mirror", "roughness": 0.3, "albedo": [0.8, 0.55, 0.2]}}),
    "bunny_box_rough": ("bunny_box", {0: {"type": "mirror", "roughness": 0.25, "albedo": [0.8, 0.75, 0.65]},
                                      4: {"type": "mirror", "roughness": 0.15, "albedo": 0.9}}),
    "mesh_glass": ("mesh", {0: {"type": "glass", "fresnel": "exact", "ior": 1.5}}),
    # The textured scene as Cycles 3.4 can hold it: its wood knot and glazed tiles are glint's
    # plastic (glTF's dielectric), which no Cycles 3.4 BSDF is, so they become diffuse with the
    # same colour textures (the tiles' roughness map goes); the leaf card keeps its map_d cut-out;
    # the sphere sun becomes an icosphere of 1,280 triangles (Cycles has no sphere light in 3.4)
    # with the sphere's emission. UVs, vertex normals and the sky are the scene's own.
    "textured_diffuse": ("textured", {}, {
        0: {"materials": {"wood": {"type": "diffuse", "albedo": {"texture": "textured/wood.png"}},
                          "tiles": {"type": "diffuse", "albedo": {"texture": "textured/tiles.png"}}}},
        1: {"as_mesh": 3}}),
    # The same with the tiles a rough mirror (Glossy GGX) whose roughness is the tiles' map_Pr
    # texture and whose colour is their colour texture: textured roughness in both renderers.
    "textured_glossy": ("textured", {}, {
        0: {"materials": {"wood": {"type": "diffuse", "albedo": {"texture": "textured/wood.png"}},
                          "tiles": {"type": "mirror", "albedo": {"texture": "textured/tiles.png"},
                                    "roughness": {"texture": "textured/tiles_rough.png"}}}},
        1: {"as_mesh": 3}}),
    # The environment-lit scenes as Cycles 3.4 can hold them: the plastic floor and red ball
    # diffuse, the rough gold metal a rough mirror (Glossy GGX) of its colour, the silver metal
    # a smooth mirror; the spheres icospheres of 5,120 triangles, glass ball included. The
    # courtyard's sky, rotated, and the sun are the scenes' own.
    "environment_cycles": ("environment", *ENVIRONMENT_EDITS),
    "environment_sun_cycles": ("environment_sun", *ENVIRONMENT_EDITS),
    # The same with glint's balls true spheres and Cycles' smooth-shaded icospheres of 20,480
    # triangles (vertex normals the sphere's): each renderer's own way to hold a ball. Whether
    # the images still agree is in the table.
    "environment_spheres": ("environment", ENVIRONMENT_EDITS[0], {}, CYCLES_BALLS),
    "environment_sun_spheres": ("environment_sun", ENVIRONMENT_EDITS[0], {}, CYCLES_BALLS),
}


def icosphere(center, radius, subdivisions, smooth=False):
    """An icosahedron subdivided `subdivisions` times, its vertices on the sphere, faces outward."""
    t = (1 + 5 ** 0.5) / 2
    vertices = [np.array(v, float) for v in ((-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                                              (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1))]
    vertices = [v / np.linalg.norm(v) for v in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle, finer = {}, []

        def mid(a, b):
            if (b, a) in middle:
                return middle[(b, a)]
            v = vertices[a] + vertices[b]
            vertices.append(v / np.linalg.norm(v))
            middle[(a, b)] = len(vertices) - 1
            return middle[(a, b)]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    mesh = {"vertices": [[float(x) for x in np.asarray(center) + radius * v] for v in vertices],
            "indices": [list(f) for f in faces]}
    if smooth:
        mesh["normals"] = [[float(x) for x in v] for v in vertices]
    return mesh


def edited(obj, fields):
    """The object with `fields` set (None: removed; `as_mesh`: a sphere made an icosphere of that
    many subdivisions, smooth-shaded with `smooth`)."""
    for key, value in fields.items():
        if key == "smooth":
            continue
        if key == "as_mesh":
            sphere = {k: obj.pop(k) for k in ("center", "radius")}
            obj.update(type="mesh", **icosphere(sphere["center"], sphere["radius"], value, fields.get("smooth", False)))
        elif value is None:
            obj.pop(key, None)
        else:
            obj[key] = value
    return obj


def box_filter_copies(name):
    """The scene (or variant) with film.filter "box", beside the original so its mesh files
    resolve: glint's copy and Cycles' (the same file unless the variant edits Cycles' alone)."""
    base, materials, *edits = VARIANTS.get(name, (name, {}))
    with open(os.path.join(ROOT, "scenes", base + ".json")) as f:
        scene = json.load(f)
    for index, material in materials.items():
        scene["objects"][index]["material"] = material
    for index, fields in (edits[0] if edits else {}).items():
        edited(scene["objects"][index], fields)
    scene.setdefault("film", {})["filter"] = "box"
    paths = [os.path.join(ROOT, "scenes", f".peer-{name}.json")]
    with open(paths[0], "w") as f:
        json.dump(scene, f)
    if len(edits) < 2:
        return paths[0], paths[0]
    for index, fields in edits[1].items():
        edited(scene["objects"][index], fields)
    paths.append(os.path.join(ROOT, "scenes", f".peer-{name}-cycles.json"))
    with open(paths[1], "w") as f:
        json.dump(scene, f)
    return paths[0], paths[1]


def timed(command):
    """Runs command; returns (CPU seconds of the child, user + sys; wall seconds)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime, wall


def run_glint(scene, out, a, spp, seed):
    """One render: (image, cpu, wall)."""
    pfm = f"{out}_{spp}_{seed}.pfm"
    cpu, wall = timed([GLINT, "render", scene, "-o", pfm[:-4] + ".png", "--hdr", pfm, "--width", str(a.width),
                       "--height", str(a.height), "--spp", str(spp), "--seed", str(seed), "--threads", "2"])
    return read_pfm(pfm), cpu, wall


def run_cycles(scene, out, a, spp, seed):
    """One render in a Blender of its own, so that each timing is alone in its process."""
    subprocess.run(["blender", "-b", "--factory-startup", "-noaudio", "-t", "2", "--python",
                    os.path.join(ROOT, "bench", "peer", "cycles_scene.py"), "--", scene, "--width", str(a.width),
                    "--height", str(a.height), "--spp", str(spp), "--seeds", str(seed), "--out", out],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out + ".jsonl") as f:
        r = json.loads(f.readlines()[-1])
    return read_pfm(f"{out}_{spp}_{seed}.pfm"), r["cpu"], r["wall"]


def run_both(scenes, out, a, jobs):
    """Each job by glint, then at once by Cycles: the machine's speed drifts by 10-20% over
    minutes, and renders side by side see the same machine. With --repeat N each ladder render
    is made N times over, alternating, and its times are the medians (the images are the same
    bits every time; the references' times are not used)."""
    glint, cycles = {}, {}
    for spp, seed in jobs:
        runs = {"glint": [], "cycles": []}
        for _ in range(a.repeat if seed == SEEDS["ladder"] else 1):
            runs["glint"].append(run_glint(scenes[0], out + "_glint", a, spp, seed))
            runs["cycles"].append(run_cycles(scenes[1], out + "_cycles", a, spp, seed))
        for results, renders in ((glint, runs["glint"]), (cycles, runs["cycles"])):
            results[(spp, seed)] = (renders[0][0], float(np.median([r[1] for r in renders])),
                                    float(np.median([r[2] for r in renders])))
    return glint, cycles


def measure(results, a):
    """Per rung: spp, cpu, wall, MSE and relMSE against the renderer's own reference, noise removed."""
    ra, rb = (results[(a.reference_spp, s)][0] for s in SEEDS["reference"])
    reference = (ra + rb) / 2
    ref_mse = np.mean((ra - rb) ** 2) / 4
    ref_rel = np.mean((ra - rb) ** 2 / (reference ** 2 + 1e-2)) / 4
    rows = []
    for spp in a.ladder:
        image, cpu, wall = results[(spp, SEEDS["ladder"])]
        mse = np.mean((image - reference) ** 2) - ref_mse
        rel = np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)) - ref_rel
        rows.append({"spp": spp, "cpu": cpu, "wall": wall, "mse": mse, "relmse": rel})
    return reference, ref_mse, rows


def time_to(rows, mse, key):
    """Seconds (key: cpu or wall) to reach `mse`, interpolated in log-log between rungs (MSE ∝ 1/t
    beyond the ends)."""
    pts = sorted((r[key], r["mse"]) for r in rows if r["mse"] > 0)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= mse <= e0:
            f = np.log(e0 / mse) / np.log(e0 / e1)
            return float(np.exp(np.log(t0) + f * np.log(t1 / t0)))
    t, e = pts[-1] if mse < pts[-1][1] else pts[0]
    return t * e / mse


def compare(name, g, c, a):
    g_ref, g_ref_mse, g_rows = measure(g, a)
    c_ref, c_ref_mse, c_rows = measure(c, a)
    ratio = g_ref.mean(axis=(0, 1)) / c_ref.mean(axis=(0, 1))
    between = float(np.sqrt(np.mean((g_ref - c_ref) ** 2)))
    noise = float(np.sqrt(g_ref_mse + c_ref_mse))
    # Equal error: the error Cycles reaches at its top rung.
    target = c_rows[-1]["mse"]
    summary = {"scene": name, "mean_ratio": [round(float(x), 4) for x in ratio],
               "refs_rmse": between, "refs_noise": noise,
               "cpu_ratio": time_to(c_rows, target, "cpu") / time_to(g_rows, target, "cpu"),
               "wall_ratio": time_to(c_rows, target, "wall") / time_to(g_rows, target, "wall"),
               "mse_per_spp_ratio": (g_rows[-1]["mse"] * g_rows[-1]["spp"]) / (c_rows[-1]["mse"] * c_rows[-1]["spp"]),
               "cpu_per_spp_ratio": (g_rows[-1]["cpu"] / g_rows[-1]["spp"]) / (c_rows[-1]["cpu"] / c_rows[-1]["spp"])}
    return summary, g_rows, c_rows


def plot(curves, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(curves), figsize=(4.2 * len(curves), 3.6), squeeze=False)
    for ax, (name, g_rows, c_rows) in zip(axes[0], curves):
        for rows, label, style in ((g_rows, "glint", "o-"), (c_rows, "Cycles", "s--")):
            ax.loglog([r["cpu"] for r in rows], [np.sqrt(max(r["mse"], 1e-30)) for r in rows], style, label=label)
        ax.set_title(name)
        ax.set_xlabel("CPU seconds (2 threads)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("RMSE against own reference")
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(path)


def kept_results(replaced, results):
    """The summaries, curves and table rows already in bench/results, less those of `replaced`."""
    with open(os.path.join(ROOT, "bench", "results", results + "_summary.json")) as f:
        summaries = [s for s in json.load(f) if s["scene"] not in replaced]
    with open(os.path.join(ROOT, "bench", "results", results + ".csv"), newline="") as f:
        table = [{k: (v if k in ("scene", "renderer") else float(v)) for k, v in r.items()}
                 for r in csv.DictReader(f) if r["scene"] not in replaced]
    curves = [(s["scene"], [r for r in table if r["scene"] == s["scene"] and r["renderer"] == "glint"],
               [r for r in table if r["scene"] == s["scene"] and r["renderer"] == "cycles"]) for s in summaries]
    return summaries, curves, table


def main():
    global GLINT
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default=",".join(mesh_scenes() + list(VARIANTS)))
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--ladder", default="4,16,64,256")
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "out", "peer"))
    ap.add_argument("--update", action="store_true",
                    help="keep the other scenes' results in bench/results and replace only these scenes'")
    ap.add_argument("--results", default="peer_cycles",
                    help="bench/results/RESULTS.csv and RESULTS_summary.json, bench/plots/RESULTS.svg")
    ap.add_argument("--repeat", type=int, default=1, help="make each ladder render this many times; times are medians")
    ap.add_argument("--glint", default=GLINT, help="the glint binary (default: $GLINT, else build/server/glint)")
    a = ap.parse_args()
    GLINT = a.glint
    a.ladder = [int(s) for s in a.ladder.split(",")]
    if not shutil.which("blender"):
        subprocess.run(["apt-get", "install", "-y", "--no-install-recommends", "blender"], check=True)
    os.makedirs(a.out, exist_ok=True)
    jobs = [(s, SEEDS["ladder"]) for s in a.ladder] + [(a.reference_spp, s) for s in SEEDS["reference"]]
    summaries, curves, table = kept_results(a.scenes.split(","), a.results) if a.update else ([], [], [])
    for name in a.scenes.split(","):
        copies = box_filter_copies(name)
        try:
            g, c = run_both(copies, os.path.join(a.out, name), a, jobs)
        finally:
            for copy in set(copies):
                os.remove(copy)
        summary, g_rows, c_rows = compare(name, g, c, a)
        summaries.append(summary)
        curves.append((name, g_rows, c_rows))
        for renderer, rows in (("glint", g_rows), ("cycles", c_rows)):
            table += [{"scene": name, "renderer": renderer, **r} for r in rows]
        print(json.dumps(summary), flush=True)
    with open(os.path.join(ROOT, "bench", "results", a.results + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["scene", "renderer", "spp", "cpu", "wall", "mse", "relmse"])
        w.writeheader()
        w.writerows(table)
    with open(os.path.join(ROOT, "bench", "results", a.results + "_summary.json"), "w") as f:
        json.dump(summaries, f, indent=1)
    plot(curves, os.path.join(ROOT, "bench", "plots", a.results + ".svg"))
    print("| scene | glint/Cycles mean (R, G, B) | RMSE between references (noise) | Cycles/glint time to equal MSE, CPU (wall) | MSE per spp, glint/Cycles | CPU per spp, glint/Cycles |")
    print("|---|---|---|---|---|---|")
    for s in summaries:
        print(f"| {s['scene']} | {', '.join(f'{x:.4f}' for x in s['mean_ratio'])} | {s['refs_rmse']:.4f} ({s['refs_noise']:.4f}) "
              f"| {s['cpu_ratio']:.2f}× ({s['wall_ratio']:.2f}×) | {s['mse_per_spp_ratio']:.2f} | {s['cpu_per_spp_ratio']:.2f} |")


if __name__ == "__main__":
    sys.exit(main())
