#!/usr/bin/env python3
"""Checkpoint cost of `glint serve --store`, measured against a real server on a free loopback port.

For each film size, one job runs with --checkpoint-interval 0 (a checkpoint after every pass) on a
scene whose samples are cheap (a small sphere: most camera rays miss), so passes are short and the
checkpoints many. The server logs each checkpoint's time on the render thread (film copy, encoding,
write, fsync, rename, folder fsync, state file); this reports their median, min and max over RUNS
checkpoints, the checkpoint file's size, and how long a restart on that store takes to answer
/health (reading and checking the checkpoint).

Usage (from the repository root, after building): python3 bench/checkpoint_bench.py [runs] [store-dir]
The store goes to a temporary folder under store-dir (default /tmp: on a tmpfs fsync is free, so
point it at a real disk for figures that mean something). Prints a markdown table on stdout.
"""
import json
import os
import re
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

GLINT = "build/server/glint"
RUNS = int(sys.argv[1]) if len(sys.argv) > 1 else 9
ROOT = sys.argv[2] if len(sys.argv) > 2 else "/tmp"
SIZES = [(256, 192), (1024, 768)]


def scene(width, height):
    return {"camera": {"position": [0, 0, 30], "look_at": [0, 0, 0]},
            "film": {"width": width, "height": height, "spp": 65536},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "emission": 1}]}


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start(store, log):
    port = free_port()
    began = time.monotonic()
    proc = subprocess.Popen([GLINT, "serve", "--port", str(port), "--threads", "2", "--store", store,
                             "--checkpoint-interval", "0"], stdout=log, stderr=log)
    while True:
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/health", timeout=1).read()
            return proc, port, time.monotonic() - began
        except OSError:
            time.sleep(0.005)


def checkpoint_times(log_path):
    with open(log_path) as f:
        return [float(m.group(1)) for m in re.finditer(r"checkpoint at \d+ spp in ([0-9.]+) ms", f.read())]


def measure(width, height):
    folder = tempfile.mkdtemp(dir=ROOT, prefix="glint-checkpoint-bench-")
    store, log_path = os.path.join(folder, "store"), os.path.join(folder, "server.log")
    with open(log_path, "w") as log:
        proc, port, _ = start(store, log)
        body = json.dumps(scene(width, height)).encode()
        job = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/jobs", data=body))["id"]
        while len(checkpoint_times(log_path)) < RUNS:
            time.sleep(0.05)
        proc.kill()
        proc.wait()
        size = os.path.getsize(os.path.join(store, job, "checkpoint.glntpart"))
        times = checkpoint_times(log_path)[:RUNS]
        proc, _, restart = start(store, log)
        proc.kill()
        proc.wait()
    shutil.rmtree(folder)
    return size, times, restart


def main():
    print(f"| film | checkpoint file | write time, median (min–max) of {RUNS} | restart to /health |")
    print("|---|---|---|---|")
    for width, height in SIZES:
        size, times, restart = measure(width, height)
        print(f"| {width}×{height} | {size / 2**20:.2f} MiB | {statistics.median(times):.1f} ms "
              f"({min(times):.1f}–{max(times):.1f}) | {restart * 1000:.0f} ms |")


if __name__ == "__main__":
    main()
