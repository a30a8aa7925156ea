#!/usr/bin/env python3
"""Soak test: many clients against one real `glint serve` process on a free loopback port.

For DURATION seconds, CLIENTS threads pick actions at random: submit jobs (POST /jobs), render and
hang up (POST /render), poll, list, fetch images, read streams and event streams for a while and
disconnect, cancel, send malformed bodies, and open connections that send half a request and
close. The server runs with a store (checkpoints every half second), so that is exercised too.

At the end it asserts: no response had a 5xx status and no connection failed; every accepted job
reached a final state (or was forgotten, which only happens to finished jobs); the server's threads
(/proc/PID/task) and file descriptors (/proc/PID/fd) are back to what they were after start; its
peak RSS stayed under MAX_RSS_MIB; it stops on SIGTERM with exit status 0. Prints the load held.

Usage: soak_test.py GLINT_BINARY SOURCE_DIR [--seconds 120] [--clients 16] [--max-rss-mib 256]
Python standard library only; loopback only.
"""
import argparse
import http.client
import json
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def proc_counts(pid):
    threads = len(os.listdir(f"/proc/{pid}/task"))
    fds = len(os.listdir(f"/proc/{pid}/fd"))
    with open(f"/proc/{pid}/status") as f:
        rss_kib = next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
    return threads, fds, rss_kib / 1024


class Tally:
    """What the clients saw, shared between their threads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.statuses = {}
        self.failures = []
        self.accepted = []
        self.requests = 0
        self.disconnects = 0

    def status(self, route, status):
        with self.lock:
            self.requests += 1
            self.statuses[status] = self.statuses.get(status, 0) + 1
            if status >= 500:
                self.failures.append(f"{route}: HTTP {status}")

    def disconnect(self):
        with self.lock:
            self.disconnects += 1

    def failure(self, what):
        with self.lock:
            self.failures.append(what)

    def recent_job(self, rng):
        """Mostly one of the last jobs (older ones are forgotten once 64 newer have finished)."""
        with self.lock:
            if not self.accepted:
                return "0000000000000000"
            return rng.choice(self.accepted[-32:] if rng.random() < 0.8 else self.accepted)


class Client:
    def __init__(self, port, tally, rng):
        self.port, self.tally, self.rng = port, tally, rng

    def connect(self, timeout=30):
        return http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)

    def request(self, method, path, body=None, expect=()):
        conn = self.connect()
        try:
            conn.request(method, path, body=body, headers={"Content-Type": "application/json"} if body else {})
            res = conn.getresponse()
            data = res.read()
            self.tally.status(f"{method} {path}", res.status)
            if expect and res.status not in expect:
                self.tally.failure(f"{method} {path}: HTTP {res.status}, expected {expect}: {data[:200]!r}")
            return res.status, data
        finally:
            conn.close()

    def job_body(self):
        return json.dumps({"preset": self.rng.choice(["cornell", "spheres", "caustic", "mesh"]),
                           "width": self.rng.randint(8, 64), "height": self.rng.randint(8, 48),
                           "spp": self.rng.choice([4, 8, 16, 32])})

    def some_job(self):
        return self.tally.recent_job(self.rng)

    # The actions, picked at random.
    def submit(self):
        status, data = self.request("POST", "/jobs", self.job_body(), expect=(202, 429))
        if status == 202:
            with self.tally.lock:
                self.tally.accepted.append(json.loads(data)["id"])

    def render_and_maybe_hang_up(self):
        # The PNG comes once the job has waited its turn: behind a full queue on an instrumented
        # (sanitizer) build that can take minutes.
        wait_for_it = self.rng.random() < 0.5
        conn = self.connect(timeout=240 if wait_for_it else 30)
        try:
            conn.request("POST", "/render", body=self.job_body())
            res = conn.getresponse()
            self.tally.status("POST /render", res.status)
            if res.status == 200 and wait_for_it:
                res.read()
            else:
                self.tally.disconnect()
        finally:
            conn.close()

    def read_for_a_while(self, path):
        conn = self.connect()
        try:
            conn.request("GET", path)
            res = conn.getresponse()
            self.tally.status("GET " + path.rsplit("/", 1)[-1], res.status)
            if res.status != 200:
                res.read()
                return
            # A queued job's stream is silent until its first pass: stop reading when time is up.
            deadline = time.monotonic() + self.rng.uniform(0, 3)
            try:
                while time.monotonic() < deadline:
                    conn.sock.settimeout(max(0.05, deadline - time.monotonic()))
                    if not res.read1(65536):
                        return
            except TimeoutError:
                pass
            self.tally.disconnect()
        finally:
            conn.close()

    def stream(self):
        self.read_for_a_while(f"/jobs/{self.some_job()}/stream")

    def events(self):
        self.read_for_a_while(f"/jobs/{self.some_job()}/events")

    def poll(self):
        self.request("GET", f"/jobs/{self.some_job()}", expect=(200, 404))

    def list_and_health(self):
        self.request("GET", "/jobs", expect=(200,))
        self.request("GET", "/health", expect=(200,))

    def image(self):
        self.request("GET", f"/jobs/{self.some_job()}/image.{self.rng.choice(['png', 'pfm'])}", expect=(200, 404, 409))

    def cancel(self):
        self.request("DELETE", f"/jobs/{self.some_job()}", expect=(200, 404))

    def bad_body(self):
        self.request("POST", "/jobs", self.rng.choice(['{"preset": ', '[1, 2', '{"preset": "nope"}', '{"width": -1}']),
                     expect=(400, 404, 422))

    def half_request(self):
        with socket.create_connection(("127.0.0.1", self.port), timeout=5) as s:
            s.sendall(b"GET /jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        self.tally.disconnect()

    def run(self, deadline):
        actions = [(self.submit, 4), (self.render_and_maybe_hang_up, 1), (self.stream, 2), (self.events, 2),
                   (self.poll, 6), (self.list_and_health, 2), (self.image, 3), (self.cancel, 1), (self.bad_body, 1),
                   (self.half_request, 1)]
        weighted = [a for a, w in actions for _ in range(w)]
        while time.monotonic() < deadline:
            action = self.rng.choice(weighted)
            try:
                action()
            except (OSError, http.client.HTTPException) as e:
                self.tally.failure(f"{action.__name__}: {type(e).__name__}: {e}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("glint")
    parser.add_argument("source")
    parser.add_argument("--seconds", type=float, default=float(os.environ.get("GLINT_SOAK_SECONDS", 120)))
    parser.add_argument("--clients", type=int, default=16)
    parser.add_argument("--max-rss-mib", type=float, default=256)
    args = parser.parse_args()

    work = tempfile.mkdtemp(prefix="glint-soak-")
    port = free_port()
    log = open(os.path.join(work, "server.log"), "w")
    server = subprocess.Popen([args.glint, "serve", "--port", str(port), "--threads", "2",
                               "--scenes", os.path.join(args.source, "scenes"), "--web", os.path.join(args.source, "web"),
                               "--store", os.path.join(work, "store"), "--checkpoint-interval", "0.5"],
                              stdout=log, stderr=log)
    failures = []
    try:
        for _ in range(1000):
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.02)
        time.sleep(0.5)
        threads0, fds0, rss0 = proc_counts(server.pid)

        tally = Tally()
        peak = {"rss": rss0, "jobs": 0}
        start = time.monotonic()
        deadline = start + args.seconds
        stop_watching = threading.Event()

        def watch():
            monitor = Client(port, Tally(), random.Random(0))
            while not stop_watching.wait(0.5):
                peak["rss"] = max(peak["rss"], proc_counts(server.pid)[2])
                try:
                    health = json.loads(monitor.request("GET", "/health")[1])
                    peak["jobs"] = max(peak["jobs"], health["jobs_running"])
                except (OSError, ValueError, http.client.HTTPException):
                    pass

        watcher = threading.Thread(target=watch)
        watcher.start()
        clients = [threading.Thread(target=Client(port, tally, random.Random(seed)).run, args=(deadline,))
                   for seed in range(args.clients)]
        for c in clients:
            c.start()
        for c in clients:
            c.join()
        elapsed = time.monotonic() - start
        failures += tally.failures

        # Every accepted job ends (the jobs are small); a forgotten job (404) had finished.
        checker = Client(port, Tally(), random.Random(1))
        unfinished = set(tally.accepted)
        states = {}
        settle = time.monotonic() + 120
        while unfinished and time.monotonic() < settle:
            for job in list(unfinished):
                status, data = checker.request("GET", f"/jobs/{job}")
                state = json.loads(data)["state"] if status == 200 else "forgotten"
                if state not in ("queued", "running"):
                    states[state] = states.get(state, 0) + 1
                    unfinished.discard(job)
            time.sleep(0.2)
        if unfinished:
            failures.append(f"{len(unfinished)} accepted jobs never ended: {sorted(unfinished)[:5]}")
        stop_watching.set()
        watcher.join()

        # Idle connections close after the keep-alive and read timeouts (5 s and 10 s).
        threads = fds = None
        for _ in range(60):
            threads, fds, _ = proc_counts(server.pid)
            if threads <= threads0 and fds <= fds0:
                break
            time.sleep(0.5)
        if threads > threads0:
            failures.append(f"threads: {threads0} after start, {threads} at the end")
        if fds > fds0:
            failures.append(f"file descriptors: {fds0} after start, {fds} at the end")
        if peak["rss"] > args.max_rss_mib:
            failures.append(f"peak RSS {peak['rss']:.0f} MiB over the bound of {args.max_rss_mib:.0f} MiB")

        server.send_signal(signal.SIGTERM)
        code = server.wait(timeout=60)
        if code != 0:
            failures.append(f"the server exited with status {code} on SIGTERM")

        print(f"soak: {args.clients} clients for {elapsed:.0f} s: {tally.requests} requests "
              f"({tally.requests / elapsed:.0f}/s), statuses {dict(sorted(tally.statuses.items()))}, "
              f"{tally.disconnects} deliberate disconnects")
        print(f"soak: {len(tally.accepted)} jobs accepted, ended {dict(sorted(states.items()))}, "
              f"at most {peak['jobs']} rendering at once")
        print(f"soak: threads {threads0} -> {threads}, fds {fds0} -> {fds}, RSS {rss0:.0f} MiB after start, "
              f"peak {peak['rss']:.0f} MiB (bound {args.max_rss_mib:.0f})")
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()
        log.close()
    if failures:
        print(f"soak: FAILED ({len(failures)}); server log in {work}", file=sys.stderr)
        for f in failures[:30]:
            print("  " + f, file=sys.stderr)
        return 1
    shutil.rmtree(work)
    print("soak: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
