#!/usr/bin/env python3
"""Figures for the render service, measured against a real `glint serve` on a free loopback port.

1. Time from POST /jobs to the first complete PNG part of /jobs/{id}/stream (256x192 Cornell box).
2. Server overhead: wall time of POST /render against `glint render` for the same job, alternated.
3. Requests/s that GET /jobs/{id} holds while a render runs (wrk, 10 s, loopback only).
4. What the page's jobs panel costs: GET /jobs with 64 jobs listed (the server keeps 64 finished
   jobs by default), its time and size; the page asks once a second.

Usage (from the repository root, after building):
    python3 bench/server_bench.py [runs] [--glint PATH] [--first-only]
--first-only measures figure 1 alone (to compare two builds side by side).
Prints a markdown report on stdout.
"""
import http.client
import json
import re
import socket
import statistics
import subprocess
import sys
import time

ARGS = sys.argv[1:]
GLINT = ARGS[ARGS.index("--glint") + 1] if "--glint" in ARGS else "build/server/glint"
FIRST_ONLY = "--first-only" in ARGS
RUNS = int(ARGS[0]) if ARGS and ARGS[0].isdigit() else 7
JOB = {"preset": "cornell", "width": 256, "height": 192}


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def request(port, method, path, body=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=300)
    c.request(method, path, body=json.dumps(body) if body is not None else None)
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, data


def first_png_seconds(port):
    start = time.perf_counter()
    _, data = request(port, "POST", "/jobs", dict(JOB, spp=1024))
    job = json.loads(data)["id"]
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    c.request("GET", f"/jobs/{job}/stream")
    r = c.getresponse()
    buffer = b""
    while True:  # until one whole part (headers + Content-Length bytes) has arrived
        buffer += r.read1(65536)
        m = re.search(rb"Content-Length: (\d+)\r\n\r\n", buffer)
        if m and len(buffer) >= m.end() + int(m.group(1)):
            break
    elapsed = time.perf_counter() - start
    c.close()
    request(port, "DELETE", f"/jobs/{job}")
    return elapsed


def overhead(port, spp):
    http_times, cli_times = [], []
    for _ in range(RUNS):
        start = time.perf_counter()
        status, png = request(port, "POST", "/render", dict(JOB, spp=spp))
        http_times.append(time.perf_counter() - start)
        assert status == 200 and png.startswith(b"\x89PNG")
        start = time.perf_counter()
        subprocess.run([GLINT, "render", "scenes/cornell.json", "-o", "/tmp/glint-bench.png", "--width", "256",
                        "--height", "192", "--spp", str(spp), "--threads", "2"], check=True, capture_output=True)
        cli_times.append(time.perf_counter() - start)
    return statistics.median(http_times), statistics.median(cli_times)


def wrk_status(port):
    _, data = request(port, "POST", "/jobs", dict(JOB, spp=65536))
    job = json.loads(data)["id"]
    time.sleep(1)
    out = subprocess.run(["wrk", "-t2", "-c16", "-d10s", f"http://127.0.0.1:{port}/jobs/{job}"],
                         check=True, capture_output=True, text=True).stdout
    request(port, "DELETE", f"/jobs/{job}")
    rate = re.search(r"Requests/sec:\s+([\d.]+)", out).group(1)
    latency = re.search(r"Latency\s+(\S+)", out).group(1)
    return float(rate), latency


def job_list(port):
    """Median time, size and length of GET /jobs once 64 more jobs have finished."""
    for _ in range(64):
        status, _ = request(port, "POST", "/render", dict(JOB, width=16, height=12, spp=4))
        assert status == 200
    times, size, listed = [], 0, 0
    for _ in range(max(RUNS, 20)):
        start = time.perf_counter()
        status, data = request(port, "GET", "/jobs")
        times.append(time.perf_counter() - start)
        size, listed = len(data), len(json.loads(data))
        assert status == 200
    return statistics.median(times), size, listed


def main():
    port = free_port()
    server = subprocess.Popen([GLINT, "serve", "--port", str(port), "--threads", "2"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(100):
            try:
                if request(port, "GET", "/health")[0] == 200:
                    break
            except OSError:
                time.sleep(0.05)
        firsts = sorted(first_png_seconds(port) for _ in range(RUNS))
        if not FIRST_ONLY:
            http_s, cli_s = overhead(port, 64)
            rate, latency = wrk_status(port)
            list_s, list_bytes, listed = job_list(port)
    finally:
        server.terminate()
        server.wait()
    print(f"| figure | value |\n|---|---|")
    print(f"| POST /jobs to first streamed PNG, 256x192 (median of {RUNS}) | {1e3 * statistics.median(firsts):.0f} ms "
          f"(min {1e3 * firsts[0]:.0f}, max {1e3 * firsts[-1]:.0f}) |")
    if FIRST_ONLY:
        return
    print(f"| 256x192, 64 spp: POST /render / glint render (medians of {RUNS}, alternated) | "
          f"{http_s:.2f} s / {cli_s:.2f} s = {http_s / cli_s:.3f} |")
    print(f"| GET /jobs/{{id}} during a render, wrk -t2 -c16 -d10s | {rate:.0f} requests/s, mean latency {latency} |")
    print(f"| GET /jobs with {listed} jobs listed (the page's poll, once a second) | {1e3 * list_s:.1f} ms, "
          f"{list_bytes / 1024:.0f} KiB |")


if __name__ == "__main__":
    main()
