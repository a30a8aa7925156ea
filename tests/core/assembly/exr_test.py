#!/usr/bin/python3
"""EXR files from `glint render --exr` and `glint merge --exr`, read back by an independent reader
(OpenImageIO's Python bindings, Debian's python3-openimageio): channel names, size, and values
equal to what glint wrote elsewhere (the PFM's floats) or what the scene decides exactly (the
albedo and normal of a plane seen in a mirror ball).

    exr_test.py GLINT PROJECT_DIR
"""
import os
import struct
import subprocess
import sys
import tempfile

import OpenImageIO as oiio

glint, project = sys.argv[1], sys.argv[2]
failures, passed = [], []


def check(what, ok):
    print(("ok   " if ok else "FAIL ") + what)
    (passed if ok else failures).append(what)


def run(*args):
    subprocess.run([glint, *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def read_exr(path):
    """(width, height, {channel name: [floats, rows top to bottom]})"""
    image = oiio.ImageInput.open(path)
    if image is None:
        raise RuntimeError(oiio.geterror())
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    names = list(spec.channelnames)
    channels = {name: [float(v) for v in pixels[:, :, c].reshape(-1)] for c, name in enumerate(names)}
    return spec.width, spec.height, channels, [spec.channelformat(c) for c in range(len(names))]


def read_pfm(path):
    """{R, G, B: [floats, rows top to bottom]} of a little-endian colour PFM (stored bottom row first)."""
    with open(path, "rb") as f:
        data = f.read()
    header, size, _scale, body = data.split(b"\n", 3)
    width, height = map(int, size.split())
    assert header == b"PF"
    values = struct.unpack("<%df" % (3 * width * height), body)
    rows = [values[y * 3 * width:(y + 1) * 3 * width] for y in range(height)][::-1]
    flat = [v for row in rows for v in row]
    return {c: flat[i::3] for i, c in enumerate("RGB")}


MIRROR_SCENE = """{"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 10},
  "film": {"width": 8, "height": 6, "spp": 8, "background": 0.5},
  "objects": [{"type": "mesh", "vertices": [[-40, -40, 6], [40, -40, 6], [40, 40, 6], [-40, 40, 6]],
               "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": [0.25, 0.5, 0.75]}},
              {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {"type": "mirror", "albedo": 0.9}}]}"""

with tempfile.TemporaryDirectory() as work:
    cornell = os.path.join(project, "scenes", "cornell.json")
    size = ["--width", "16", "--height", "12"]
    exr, pfm = os.path.join(work, "whole.exr"), os.path.join(work, "whole.pfm")
    run("render", cornell, *size, "--spp", "16", "--exr", exr, "--hdr", pfm, "-o", os.path.join(work, "whole.png"))
    width, height, channels, formats = read_exr(exr)
    check("the EXR is 16x12", (width, height) == (16, 12))
    expected = {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z", "sample_count.Y",
                "variance.R", "variance.G", "variance.B"}
    check("channels: " + ", ".join(sorted(channels)), set(channels) == expected)
    check("every channel is 32-bit float", all(str(f) == "float" for f in formats))
    image = read_pfm(pfm)
    check("R, G, B are the PFM's floats exactly", all(channels[c] == image[c] for c in "RGB"))
    check("sample_count.Y is 16 everywhere", all(v == 16 for v in channels["sample_count.Y"]))
    check("variance is finite and >= 0", all(0 <= v < float("inf") for c in "RGB" for v in channels["variance." + c]))
    check("some variance is > 0", any(v > 0 for v in channels["variance.R"]))
    check("albedo is in [0, 1]", all(0 <= v <= 1 for c in "RGB" for v in channels["albedo." + c]))
    lengths = [(x * x + y * y + z * z) ** 0.5 for x, y, z in zip(channels["N.X"], channels["N.Y"], channels["N.Z"])]
    check("normals average unit vectors (length <= 1, most 1)",
          all(v <= 1 + 1e-6 for v in lengths) and sum(abs(v - 1) < 1e-6 for v in lengths) > len(lengths) // 2)
    check("depth is finite and > 0", all(0 < v < 1e6 for v in channels["Z"]))

    # Two parts merged: the same values as the whole render.
    parts = []
    for first, end in ((0, 8), (8, 16)):
        parts.append(os.path.join(work, "part-%d" % first))
        run("render", cornell, *size, "--spp", "16", "--samples", "%d:%d" % (first, end), "--aovs",
            "--partial", parts[-1])
    merged = os.path.join(work, "merged.exr")
    run("merge", os.path.join(work, "merged.png"), "--exr", merged, *parts)
    _, _, merged_channels, _ = read_exr(merged)
    same = [c for c in expected if not c.startswith("variance") and merged_channels.get(c) == channels[c]]
    check("merge --exr: the whole render's image, counts and AOVs (%d of 11 channels)" % len(same), len(same) == 11)
    close = all(abs(a - b) <= 1e-6 * max(abs(a), 1e-30)
                for c in "RGB" for a, b in zip(merged_channels["variance." + c], channels["variance." + c]))
    check("merge --exr: the whole render's variance (to rounding)", close)

    # Without AOVs, a merge writes the image, counts and variance only.
    run("render", cornell, *size, "--spp", "8", "--samples", "0:8", "--partial", os.path.join(work, "plain"))
    run("merge", os.path.join(work, "plain.png"), "--exr", os.path.join(work, "plain.exr"), os.path.join(work, "plain"))
    _, _, plain, _ = read_exr(os.path.join(work, "plain.exr"))
    check("without AOVs: R, G, B, sample_count.Y, variance.R/G/B",
          set(plain) == {"R", "G", "B", "sample_count.Y", "variance.R", "variance.G", "variance.B"})

    # A plane seen in a mirror ball: its albedo and its normal, facing the reflected rays.
    scene = os.path.join(work, "mirror.json")
    with open(scene, "w") as f:
        f.write(MIRROR_SCENE)
    run("render", scene, "--exr", os.path.join(work, "mirror.exr"))
    _, _, mirror, _ = read_exr(os.path.join(work, "mirror.exr"))
    check("through the mirror: the plane's albedo exactly",
          all(mirror["albedo." + c] == [v] * 48 for c, v in zip("RGB", (0.25, 0.5, 0.75))))
    check("through the mirror: the plane's normal (0, 0, -1)",
          mirror["N.X"] == [0] * 48 and mirror["N.Y"] == [0] * 48 and mirror["N.Z"] == [-1] * 48)
    check("through the mirror: the ball's own depth, 3 to 3.2 (the plane lies 5 or more beyond)", all(3 <= v <= 3.2 for v in mirror["Z"]))

print("exr: %d passed, %d failed" % (len(passed), len(failures)))
sys.exit(1 if failures else 0)
