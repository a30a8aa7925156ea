#!/usr/bin/env python3
"""glint's estimated RMSE against the measured one for one scene, size and SPP.

    bench/estimate_ratio.py GLINT SCENE WIDTH HEIGHT SPP [REFERENCE_MULTIPLE]

Renders a reference with REFERENCE_MULTIPLE (default 32) times the samples and seed 1000 (kept in
bench/out/estimate/, reused), then the image with seed 1, both with `glint render --hdr` on 2
threads, and prints the image's estimated RMSE (from glint's last line), the RMSE of its PFM
against the reference's and their ratio. Like tests/core/render/test_error_estimate.cpp, at any size.
"""
import os
import re
import struct
import subprocess
import sys


def read_pfm(path):
    with open(path, "rb") as f:
        _kind, _size, _scale, data = f.read().split(b"\n", 3)
    return struct.unpack("<%df" % (len(data) // 4), data)


def render(glint, scene, width, height, spp, seed, out):
    result = subprocess.run([glint, "render", scene, "--width", width, "--height", height, "--spp", str(spp),
                             "--seed", str(seed), "--threads", "2", "-o", out + ".png", "--hdr", out + ".pfm"],
                            capture_output=True, text=True, check=True)
    return float(re.search(r"estimated RMSE (\S+),", result.stdout).group(1))


def main():
    glint, scene, width, height, spp = sys.argv[1:6]
    spp = int(spp)
    multiple = int(sys.argv[6]) if len(sys.argv) > 6 else 32
    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "out", "estimate")
    os.makedirs(folder, exist_ok=True)
    name = os.path.splitext(os.path.basename(scene))[0]
    reference = os.path.join(folder, "%s-%sx%s-%dspp" % (name, width, height, spp * multiple))
    if not os.path.exists(reference + ".pfm"):
        render(glint, scene, width, height, spp * multiple, 1000, reference)
    image = os.path.join(folder, "image")
    estimated = render(glint, scene, width, height, spp, 1, image)
    a, b = read_pfm(image + ".pfm"), read_pfm(reference + ".pfm")
    measured = (sum((x - y) ** 2 for x, y in zip(a, b)) / len(a)) ** 0.5
    print("%s %sx%s %d spp (reference %d spp): estimated %.5g, measured %.5g, ratio %.3f"
          % (name, width, height, spp, spp * multiple, estimated, measured, estimated / measured))


if __name__ == "__main__":
    main()
