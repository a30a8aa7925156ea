#!/usr/bin/python3
"""What a job split over a Slurm cluster costs beyond its samples (bench/BENCHMARKS.md, "Split
over a Slurm cluster"), and the model T(N) = start-up + work / N + merge(N) built from it.

  /usr/bin/python3 bench/slurm_costs.py [--runs 3] [--parts 8]   (as root; needs slurmctld slurmd
                                                                   slurm-client munge)

Two cores cannot show a speed-up over four nodes, so this measures the fixed costs instead:
- Slurm's own latencies, on the four-node cluster tests/slurm/cluster.sh starts here (its
  scheduler wakes every second): submit to the first and last part's start, last part's end to
  the merge's start, the merge job, and submit --wait's return; parts of a tiny render, medians of
  --runs; and, on the same cluster, glint serve --farm slurm's looks at a 1024x768 job's parts
  (reading the checkpoints that changed and merging every part's film);
- a part's start-up at 1024x768 on this machine: the process, scene load and BVH build (a 1x1
  render), and the film's partial file written at the end (the rest of a 4-spp part's time beyond
  its render);
- glint merge of 1 .. --parts partial files at 1024x768 (its time against the number of parts);
- samples per second of both threads (a 64-spp render at 256x192), for each scene.
Prints the constants and, for the Cornell box at 1024x768 and 16k spp and for scenes/mesh.json,
the node count that minimises T(N) and the one at which the fixed costs equal the rendering.
"""
import argparse
import datetime
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GLINT = os.path.join(ROOT, "build", "server", "glint")
SUBMIT = os.path.join(ROOT, "docker", "slurm", "submit")
CLUSTER = os.path.join(ROOT, "tests", "slurm", "cluster.sh")
SCENES = {"cornell": os.path.join(ROOT, "scenes", "cornell.json"), "mesh": os.path.join(ROOT, "scenes", "mesh.json")}
WIDTH, HEIGHT = 1024, 768


def stamp(text):
    return datetime.datetime.strptime(text, "%Y-%m-%dT%H:%M:%S.%fZ").replace(tzinfo=datetime.timezone.utc).timestamp()


def cluster(action, folder):
    out = subprocess.run(["bash", "-c", f'source "{CLUSTER}"; cluster_{action} "$1" && echo "$SLURM_CONF"', "-", folder],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"cluster {action} failed: {out.stderr}")
    return out.stdout.strip()


def slurm_latencies(work, runs):
    """Slurm's latencies around one split job of four tiny parts, medians of `runs`."""
    rows = []
    for run in range(runs):
        out = os.path.join(work, f"latency{run}.png")
        start = time.time()
        subprocess.run([SUBMIT, SCENES["cornell"], "-o", out, "--parts", "4", "--spp", "16", "--glint", GLINT, "--wait",
                        "--", "--width", "32", "--height", "24"], check=True, capture_output=True)
        returned = time.time() - start
        logs = "".join(open(os.path.join(work, f"latency{run}.parts", f"part-{i}.log")).read() for i in range(4))
        starts = [stamp(t) for t in re.findall(r"started (\S+Z)", logs)]
        ends = [stamp(t) for t in re.findall(r"done (\S+Z)", logs)]
        merge = open(os.path.join(work, f"latency{run}.parts", "merge.log")).read()
        merge_start = stamp(re.search(r"merge: started (\S+Z)", merge).group(1))
        merge_end = stamp(re.search(r"merge: wrote \S+ (\S+Z)", merge).group(1))
        rows.append({"submit to first part": min(starts) - start, "submit to last part": max(starts) - start,
                     "last part's end to merge": merge_start - max(ends), "merge job (tiny)": merge_end - merge_start,
                     "submit --wait returns": returned})
    return {k: statistics.median(r[k] for r in rows) for k in rows[0]}


def server_merges(work):
    """glint serve --farm slurm on a job of 4 parts at 1024x768: the time of each look that found
    a new checkpoint or partial file (reading the changed files and merging every part's film)."""
    import socket
    import urllib.request
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    log = os.path.join(work, "server.log")
    server = subprocess.Popen([GLINT, "serve", "--port", str(port), "--scenes", os.path.join(ROOT, "scenes"),
                               "--web", os.path.join(ROOT, "web"), "--farm", "slurm", "--farm-dir", os.path.join(work, "farm"),
                               "--farm-parts", "4", "--farm-glint", GLINT, "--farm-scripts", os.path.dirname(SUBMIT),
                               "--farm-checkpoint-interval", "1"], stdout=open(log, "w"), stderr=subprocess.STDOUT)
    try:
        url = f"http://127.0.0.1:{port}/jobs"
        for _ in range(100):
            try:
                urllib.request.urlopen(url, timeout=2).read()
                break
            except OSError:
                time.sleep(0.1)
        body = json.dumps({"preset": "cornell", "width": WIDTH, "height": HEIGHT, "spp": 32}).encode()
        job = json.loads(urllib.request.urlopen(urllib.request.Request(url, body, method="POST")).read())["id"]
        for _ in range(1200):
            if json.loads(urllib.request.urlopen(f"{url}/{job}").read())["state"] != "running":
                break
            time.sleep(0.25)
    finally:
        server.terminate()
        server.wait(20)
    return [float(m) for m in re.findall(r"parts read and merged in ([0-9.]+) ms", open(log).read())]


def timed(command):
    start = time.time()
    out = subprocess.run(command, check=True, capture_output=True, text=True)
    return time.time() - start, out.stdout


def render_seconds(stdout):
    return float(re.search(r" in ([0-9.]+) s, ([0-9.e+]+) samples/s", stdout).group(1))


def part_costs(work, scene, runs):
    """A part's start-up: load and build (a 1x1 render), and the partial file of a 1024x768 film."""
    load = statistics.median(timed([GLINT, "render", SCENES[scene], "-o", os.path.join(work, "x.png"), "--width", "1",
                                    "--height", "1", "--spp", "4", "--threads", "2"])[0] for _ in range(runs))
    rest, rate = [], []
    for _ in range(runs):
        wall, stdout = timed([GLINT, "render", SCENES[scene], "--samples", "0:4", "--partial", os.path.join(work, "p"),
                              "--width", str(WIDTH), "--height", str(HEIGHT), "--threads", "2"])
        rest.append(wall - render_seconds(stdout) - load)
        # The rate of a longer render (the first passes also trace the light paths' set-up).
        _, stdout = timed([GLINT, "render", SCENES[scene], "-o", os.path.join(work, "x.png"), "--width", "256",
                           "--height", "192", "--spp", "64", "--threads", "2"])
        rate.append(256 * 192 * 64 / render_seconds(stdout))
    return load, statistics.median(rest), statistics.median(rate)


def merge_costs(work, parts, runs):
    """glint merge of 1 .. parts files at 1024x768: seconds against the number of parts."""
    files = []
    for i in range(parts):
        files.append(os.path.join(work, f"part{i}.partial"))
        subprocess.run([GLINT, "render", SCENES["cornell"], "--samples", f"{4 * i}:{4 * i + 4}", "--partial", files[-1],
                        "--width", str(WIDTH), "--height", str(HEIGHT), "--threads", "2"], check=True, capture_output=True)
    counts = sorted({1, 2, parts // 2, parts})
    seconds = {n: statistics.median(timed([GLINT, "merge", os.path.join(work, "m.png"), *files[:n]])[0] for _ in range(runs))
               for n in counts}
    slope = (seconds[counts[-1]] - seconds[counts[0]]) / (counts[-1] - counts[0])
    return seconds, seconds[counts[0]] - slope * counts[0], slope


def model(name, samples, rate, fixed, per_part):
    """T(N) = fixed + samples / (N rate) + per_part N: its best N, and where the fixed costs equal the work."""
    work = samples / rate
    best = math.sqrt(work / per_part)
    # fixed + per_part N = work / N  <=>  per_part N^2 + fixed N - work = 0
    even = (-fixed + math.sqrt(fixed * fixed + 4 * per_part * work)) / (2 * per_part)
    t = lambda n: fixed + work / n + per_part * n  # noqa: E731
    print(f"| {name} | {samples:.3g} | {work:,.0f} s | {best:,.0f} ({t(best):,.0f} s) | {even:,.0f} ({t(even):,.0f} s) | "
          f"{t(16):,.0f} s | {t(64):,.0f} s |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--parts", type=int, default=8)
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="glint-slurm-costs-")
    os.chmod(work, 0o755)
    try:
        os.environ["SLURM_CONF"] = cluster("start", os.path.join(work, "cluster"))
        latency = slurm_latencies(work, a.runs)
        merges = server_merges(work)
    finally:
        cluster("stop", os.path.join(work, "cluster"))
    try:
        print(f"Slurm, four nodes on this machine, medians of {a.runs}:")
        for k, v in latency.items():
            print(f"  {k}: {v:.2f} s")
        print(f"glint serve --farm slurm, 4 parts at {WIDTH}x{HEIGHT}: {len(merges)} looks found new films; "
              f"reading them and merging took {min(merges):.0f}-{max(merges):.0f} ms, median {statistics.median(merges):.0f} ms")
        costs = {s: part_costs(work, s, a.runs) for s in SCENES}
        print(f"A part at {WIDTH}x{HEIGHT}, 2 threads, medians of {a.runs}:")
        for s, (load, rest, rate) in costs.items():
            print(f"  {s}: start-up (process, load, build) {load:.3f} s; partial file {rest:.3f} s; "
                  f"renders {rate / 1e6:.2f} M samples/s")
        seconds, merge_fixed, merge_per_part = merge_costs(work, a.parts, a.runs)
        print(f"glint merge at {WIDTH}x{HEIGHT}: " + ", ".join(f"{n} parts {s:.2f} s" for n, s in seconds.items()) +
              f"; {merge_fixed:.3f} s + {merge_per_part:.3f} s a part ({merge_per_part / (WIDTH * HEIGHT) * 1e9:.0f} ns a pixel)")
        fixed_slurm = latency["submit to last part"] + latency["last part's end to merge"]
        print("\nT(N) = start-up + work / N + merge(N), nodes of 2 threads like this machine:")
        print("| job | samples | work on one node | best N (T) | N where fixed costs = work (T) | T(16) | T(64) |")
        print("|---|---|---|---|---|---|---|")
        for name, scene, spp in (("Cornell box (spheres), 1024x768, 16384 spp", "cornell", 16384),
                                 ("mesh scene, 1024x768, 4096 spp", "mesh", 4096)):
            load, rest, rate = costs[scene]
            model(name, WIDTH * HEIGHT * spp, rate, fixed_slurm + load + rest + merge_fixed, merge_per_part)
        json.dump({"latency": latency, "server_merges_ms": merges, "parts": costs,
                   "merge": {str(k): v for k, v in seconds.items()}},
                  open(os.path.join(ROOT, "bench", "results", "slurm_costs.json"), "w"), indent=1)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
