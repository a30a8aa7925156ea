#!/usr/bin/python3
"""`glint serve --farm slurm` on a Slurm cluster of four nodes started here (cluster.sh): a job's
parts render on the nodes while the server streams their merged progress; the final image equals
a local render's bytes, for a preset and for a posted region of a scene with a mesh; cancelling leaves nothing in Slurm's queue; a node killed under a part
loses no sample and counts none twice; a restarted server (--store) finds its farm job again.

  farm_test.py GLINT SOURCE_DIR      (as root, with slurmctld slurmd slurm-client munge)
"""
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request

GLINT, SOURCE = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
CLUSTER = os.path.join(SOURCE, "tests", "slurm", "cluster.sh")
JOB = {"preset": "cornell", "width": 64, "height": 48, "spp": 1024}  # four parts of 256 spp: seconds each
failures = []


def check(what, ok):
    print(("ok: " if ok else "FAILED: ") + what, flush=True)
    if not ok:
        failures.append(what)


def cluster(action, *args):
    out = subprocess.run(["bash", "-c", f'source "{CLUSTER}"; cluster_{action} "$@" && echo "$SLURM_CONF"', "-", *args],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"cluster {action}: {out.stderr}")
    return out.stdout.strip()


class Server:
    def __init__(self, work):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.log = open(os.path.join(work, "server.log"), "a")
        self.process = subprocess.Popen(
            [GLINT, "serve", "--port", str(self.port), "--threads", "1", "--scenes", os.path.join(SOURCE, "scenes"),
             "--web", os.path.join(SOURCE, "web"), "--store", os.path.join(work, "store"), "--farm", "slurm",
             "--farm-dir", os.path.join(work, "farm"), "--farm-parts", "4", "--farm-glint", GLINT,
             "--farm-scripts", os.path.join(SOURCE, "docker", "slurm"), "--farm-checkpoint-interval", "0.3"],
            stdout=self.log, stderr=self.log)
        for _ in range(100):
            try:
                self.get("/jobs")
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("the server did not start")

    def request(self, method, path, body=None):
        data = json.dumps(body).encode() if body is not None else None
        with urllib.request.urlopen(urllib.request.Request(f"http://127.0.0.1:{self.port}{path}", data, method=method),
                                    timeout=30) as r:
            return r.read()

    def get(self, path):
        return self.request("GET", path)

    def status(self, job):
        return json.loads(self.get(f"/jobs/{job}"))

    def stop(self):
        self.process.terminate()
        self.process.wait(20)


def follow(server, job, seconds=150, on_status=None):
    """Polls the job until it ends: the spp values and part counts seen on the way."""
    seen, deadline = [], time.time() + seconds
    while time.time() < deadline:
        s = server.status(job)
        seen.append(s)
        if on_status:
            on_status(s)
        if s["state"] in ("done", "failed", "cancelled"):
            break
        time.sleep(0.1)
    return seen


def local_render(work):
    out = os.path.join(work, "local.png")
    subprocess.run([GLINT, "render", os.path.join(SOURCE, "scenes", "cornell.json"), "-o", out, "--hdr",
                    os.path.join(work, "local.pfm"), "--width", "64", "--height", "48", "--spp", "1024"],
                   check=True, capture_output=True)
    return open(out, "rb").read(), open(os.path.join(work, "local.pfm"), "rb").read()


def same_image(server, job, local, what):
    check(f"{what}: the PNG equals a local render's bytes", server.get(f"/jobs/{job}/image.png") == local[0])
    check(f"{what}: the PFM equals a local render's bytes", server.get(f"/jobs/{job}/image.pfm") == local[1])


def queue_empty():
    """Whether Slurm's queue empties. A cancelled task stays listed (state CG) until slurmd has
    ended its processes, which on a busy machine can take seconds, and up to KillWait (30 s)
    for a process that ignores SIGTERM; what is still listed after that is printed."""
    listed = ""
    for _ in range(200):
        listed = subprocess.run(["squeue", "-h", "-o", "%i %j %t %r"], capture_output=True, text=True).stdout.strip()
        if not listed:
            return True
        time.sleep(0.2)
    print("still in Slurm's queue:\n" + listed, flush=True)
    return False


def refines_and_matches(server, local):
    job = json.loads(server.request("POST", "/jobs", JOB))["id"]
    seen = follow(server, job)
    partway = sorted({s["spp_done"] for s in seen if s["state"] == "running" and 0 < s["spp_done"] < 1024})
    check("the job ends done", seen[-1]["state"] == "done")
    check(f"its image refines while the parts render (spp seen: {partway})", len(partway) >= 2)
    check("its status counts the parts", any(s.get("parts", {}).get("running", 0) > 0 for s in seen) and
          seen[-1]["parts"]["done"] == 4)
    same_image(server, job, local, "a farm job")


def posted_scene(server, work):
    """A scene posted whole (with a mesh, read from the scenes folder) rather than a preset, with a
    priority (the job's: the parts' scene file must not carry it) and a region (the parts render
    only the window)."""
    scene = json.load(open(os.path.join(SOURCE, "scenes", "mesh.json")))
    scene["film"].update({"width": 48, "height": 32, "spp": 64, "region": [5, 3, 41, 29]})
    path = os.path.join(work, "posted.json")
    json.dump(scene, open(path, "w"))
    local = os.path.join(work, "posted.png")
    subprocess.run([GLINT, "render", path, "-o", local, "--scenes", os.path.join(SOURCE, "scenes")], check=True,
                   capture_output=True)
    job = json.loads(server.request("POST", "/jobs", dict(scene, priority=2)))["id"]
    seen = follow(server, job)
    check("a posted region of a scene with a mesh and a priority ends done on the farm", seen[-1]["state"] == "done")
    check("its window is the region's", (seen[-1]["width"], seen[-1]["height"]) == (36, 26))
    check("and its PNG equals a local render's bytes", server.get(f"/jobs/{job}/image.png") == open(local, "rb").read())


def wait_for(condition, seconds=60):
    deadline = time.time() + seconds
    while time.time() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.1)
    return None


def cancel(server):
    job = json.loads(server.request("POST", "/jobs", dict(JOB, spp=65536)))["id"]
    check("a long job's parts start", wait_for(lambda: server.status(job).get("parts", {}).get("running", 0) > 0))
    server.request("DELETE", f"/jobs/{job}")
    check("DELETE cancels it", wait_for(lambda: server.status(job)["state"] == "cancelled", 10))
    check("and leaves nothing in Slurm's queue", queue_empty())


def killed_node(server, work, local):
    job = json.loads(server.request("POST", "/jobs", JOB))["id"]
    parts = os.path.join(work, "farm", job, "parts")

    def part_1_node():  # once part 1 has rendered a checkpoint
        if not os.path.exists(os.path.join(parts, "part-1.checkpoint")):
            return None
        for line in open(os.path.join(parts, "part-1.log")):
            if line.startswith("part 1: samples") and "attempt 1," in line:
                return line.split(" on ")[1].split(",")[0]
        return None

    node = wait_for(part_1_node)
    check(f"part 1 renders on {node}", node is not None)
    if node:
        cluster("kill_node", os.path.join(work, "cluster"), node)
    seen = follow(server, job)
    check("the job still ends done", seen[-1]["state"] == "done")
    check("its status showed the part requeued", max(s.get("parts", {}).get("requeued", 0) for s in seen) >= 1)
    check("and it has every sample once", seen[-1]["spp_done"] == 1024)
    same_image(server, job, local, "a job whose node was killed")
    if node:
        subprocess.run(["slurmd", "-f", os.environ["SLURM_CONF"], "-N", node], check=True)


def restarted(server, work, local):
    job = json.loads(server.request("POST", "/jobs", JOB))["id"]
    check("a job's parts start", wait_for(lambda: server.status(job).get("parts", {}).get("running", 0) > 0))
    server.stop()  # SIGTERM: the job is suspended in the store, its parts go on
    server = Server(work)
    seen = follow(server, job)
    check("the restarted server finds its farm job and ends it done", seen and seen[-1]["state"] == "done")
    same_image(server, job, local, "a farm job across a restart")
    return server


def main():
    work = tempfile.mkdtemp(prefix="glint-farm-test-")
    os.chmod(work, 0o755)
    server = None
    try:
        os.environ["SLURM_CONF"] = cluster("start", os.path.join(work, "cluster"))
        local = local_render(work)
        server = Server(work)
        refines_and_matches(server, local)
        posted_scene(server, work)
        cancel(server)
        killed_node(server, work, local)
        server = restarted(server, work, local)
    finally:
        if server:
            server.stop()
        cluster("stop", os.path.join(work, "cluster"))
        if failures:
            print(open(os.path.join(work, "server.log")).read()[-6000:])
        shutil.rmtree(work, ignore_errors=True)
    print(f"farm: {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
