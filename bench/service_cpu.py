#!/usr/bin/python3
"""The CPU time (user + sys, from /proc) a `glint serve` process spends on one job, for two glint
binaries alternated, medians: what the service pays per pass beyond the render (the frames it
keeps for the EXR and denoiser routes, say). Run from the source folder (the presets).

  bench/service_cpu.py OLD_GLINT NEW_GLINT [ROUNDS] [JOB_JSON]
"""
import json
import os
import socket
import statistics
import subprocess
import sys
import time
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def cpu_seconds(pid):
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def job_cpu(glint, job):
    port = free_port()
    server = subprocess.Popen([glint, "serve", "--port", str(port), "--threads", "2"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{port}"
    try:
        for _ in range(200):
            try:
                urllib.request.urlopen(base + "/health")
                break
            except OSError:
                time.sleep(0.05)
        before = cpu_seconds(server.pid)
        post = urllib.request.Request(base + "/jobs", data=json.dumps(job).encode(), method="POST",
                                      headers={"Content-Type": "application/json"})
        job_id = json.load(urllib.request.urlopen(post))["id"]
        while json.load(urllib.request.urlopen(f"{base}/jobs/{job_id}"))["state"] in ("queued", "running"):
            time.sleep(0.2)
        return cpu_seconds(server.pid) - before
    finally:
        server.terminate()
        server.wait()


def main():
    old, new = sys.argv[1], sys.argv[2]
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    job = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {"preset": "cornell", "width": 1024, "height": 768, "spp": 16}
    times = {"old": [], "new": []}
    for _ in range(rounds):
        times["old"].append(job_cpu(old, job))
        times["new"].append(job_cpu(new, job))
    for name, values in times.items():
        print(f"{name}: median {statistics.median(values):.2f} CPU s of {', '.join(f'{v:.2f}' for v in values)}")


if __name__ == "__main__":
    main()
