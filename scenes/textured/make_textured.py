#!/usr/bin/env python3
"""Writes the textured demo scene's files into this folder (Python's standard library only).

    python3 scenes/textured/make_textured.py     (from anywhere; it writes beside itself)

- knot.obj: a (2,3) torus knot tube, deliberately coarse (SEGMENTS x SIDES quads) with a vertex
  normal (vn) per vertex and UVs (vt) running along the tube (u) and around it (v); a floor quad
  whose UVs run 0..FLOOR_UV so its tiles repeat; a vertical card with a leafy sprig cut out of it.
- textured.mtl: the three materials, as Blender's OBJ importer reads them.
- wood.png (sRGB), tiles.png (sRGB), tiles_rough.png (linear grey roughness) and leaf.png (sRGB
  colour, alpha the cut-out: one RGBA file for map_Kd and map_d), each 256 x 256 and tileable.

Everything is procedural and deterministic (no random module, no clock): running it again writes
the same bytes.
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE = 256                      # every texture is SIZE x SIZE

# The knot: (P, Q) torus knot on a torus of radii R (core) and r (tube path), swept by a circle.
P, Q = 2, 3
R_CORE, R_PATH, TUBE = 2.0, 1.0, 0.36
SEGMENTS, SIDES = 96, 12        # coarse on purpose: smooth shading has work to do
KNOT_SCALE = 0.36
KNOT_AT = (-0.2, 0.0, 0.35)     # centre on the floor; lifted so the tube's lowest point touches it
KNOT_TILT = math.radians(18)    # about the x axis: the far side raised, so the camera sees into the knot
U_REPEAT = 6                    # the wood texture repeats this many times along the tube

FLOOR_HALF = 6.0                # the floor is 12 x 12 units...
FLOOR_UV = 12                   # ...with UVs 0..12: 2 x 2 tiles a repeat, tiles of 0.5 units

CARD_BASE = (1.75, 0.0, -0.35)  # bottom middle of the leaf card, on the floor
CARD_SIZE = 2.3                 # square, as its texture
CARD_FACING = math.radians(-35)  # its front faces +z turned this far toward -x (the light's side)


# ---------------------------------------------------------------- PNG writing (zlib + struct)

def _chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def _filter_rows(rows, bpp):
    """Each row with the PNG filter whose output has the least sum of |signed bytes| (libpng's heuristic)."""
    out = bytearray()
    prev = bytes(len(rows[0]))
    for row in rows:
        n = len(row)
        left = bytes(bpp) + row[:-bpp]
        upleft = bytes(bpp) + prev[:-bpp]
        candidates = [
            bytes(row),
            bytes((row[i] - left[i]) & 255 for i in range(n)),
            bytes((row[i] - prev[i]) & 255 for i in range(n)),
            bytes((row[i] - ((left[i] + prev[i]) >> 1)) & 255 for i in range(n)),
            bytes((row[i] - _paeth(left[i], prev[i], upleft[i])) & 255 for i in range(n)),
        ]
        cost = [sum(b if b < 128 else 256 - b for b in c) for c in candidates]
        best = cost.index(min(cost))
        out.append(best)
        out += candidates[best]
        prev = row
    return bytes(out)


def write_png(name, pixels, channels, srgb):
    """pixels[y][x] (y = 0 the top row) of tuples of `channels` floats in [0, 1], already encoded."""
    colour_type = {1: 0, 3: 2, 4: 6}[channels]
    rows = [bytes(max(0, min(255, int(round(c * 255)))) for px in row for c in px) for row in pixels]
    png = b"\x89PNG\r\n\x1a\n"
    png += _chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, colour_type, 0, 0, 0))
    if srgb:
        png += _chunk(b"sRGB", b"\x00")          # perceptual intent: the colours are sRGB-encoded
    png += _chunk(b"IDAT", zlib.compress(_filter_rows(rows, channels), 9))
    png += _chunk(b"IEND", b"")
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(png)


# ---------------------------------------------------------------- noise that tiles

def _hash(ix, iy, seed):
    h = (ix * 374761393 + iy * 668265263 + seed * 2147483647) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65535.0


def value_noise(x, y, px, py, seed):
    """Smooth value noise in [0, 1], periodic with px along x and py along y (whole lattice cells)."""
    ix, iy = math.floor(x), math.floor(y)
    fx, fy = x - ix, y - iy
    sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)
    x0, x1, y0, y1 = ix % px, (ix + 1) % px, iy % py, (iy + 1) % py
    a = _hash(x0, y0, seed) + (_hash(x1, y0, seed) - _hash(x0, y0, seed)) * sx
    b = _hash(x0, y1, seed) + (_hash(x1, y1, seed) - _hash(x0, y1, seed)) * sx
    return a + (b - a) * sy


def fbm(u, v, fx, fy, seed, octaves=3):
    """Fractal sum over (u, v) in [0, 1)^2, tiling that square; fx, fy: cells of the first octave."""
    total, amp, norm = 0.0, 1.0, 0.0
    for o in range(octaves):
        k = 1 << o
        total += amp * value_noise(u * fx * k, v * fy * k, fx * k, fy * k, seed + o)
        norm += amp
        amp *= 0.5
    return total / norm


def smoothstep(a, b, x):
    t = min(1.0, max(0.0, (x - a) / (b - a)))
    return t * t * (3 - 2 * t)


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def texel_uv(col, row):
    """The UV of a texel's centre: u to the right, v up (v = 0 is the image's bottom row)."""
    return (col + 0.5) / SIZE, 1 - (row + 0.5) / SIZE


def srgb_bytes(rgb255):
    return tuple(c / 255 for c in rgb255)


# ---------------------------------------------------------------- the textures

def wood():
    """Grain along u (the tube's length): growth rings as stripes, warped, with fine streaks."""
    light, dark = srgb_bytes((226, 176, 116)), srgb_bytes((139, 82, 41))
    img = []
    for row in range(SIZE):
        line = []
        for col in range(SIZE):
            u, v = texel_uv(col, row)
            warp = fbm(u, v, 2, 3, 11) - 0.5
            f = 5 * v + 1.1 * warp + 0.12 * math.sin(2 * math.pi * u)
            ring = f - math.floor(f)
            late = smoothstep(0.55, 0.85, ring) * (1 - smoothstep(0.9, 1.0, ring))
            streak = value_noise(u * 6, v * 96, 6, 96, 23) - 0.5
            c = mix(light, dark, 0.85 * late)
            line.append(tuple(x * (1 + 0.16 * streak) for x in c))
        img.append(line)
    write_png("wood.png", img, 3, srgb=True)


GROUT = 5 / SIZE                 # half the grout line's width, in UV units of one repeat


def tile_cell(u, v):
    """Which of the 2 x 2 tiles a point is in, and how far it is from the tile's nearest edge."""
    i, j = int(u * 2) % 2, int(v * 2) % 2
    lu, lv = u * 2 - math.floor(u * 2), v * 2 - math.floor(v * 2)
    edge = min(lu, 1 - lu, lv, 1 - lv) / 2      # in UV units of the whole image
    return i, j, edge


def texel_image(texel):
    """SIZE x SIZE texels, rows top first: texel(u, v) at each texel's centre."""
    return [[texel(*texel_uv(col, row)) for col in range(SIZE)] for row in range(SIZE)]


def tiles():
    """Terracotta and cream tiles in a checker, 2 x 2 to a repeat, with grout lines."""
    terracotta, cream, grout = srgb_bytes((176, 88, 58)), srgb_bytes((228, 214, 186)), srgb_bytes((112, 108, 100))

    def texel(u, v):
        i, j, edge = tile_cell(u, v)
        base = terracotta if (i + j) % 2 else cream
        jitter = 0.94 + 0.1 * _hash(i, j, 5)
        mottle = 0.92 + 0.16 * fbm(u, v, 4, 4, 31)
        bevel = 0.85 + 0.15 * smoothstep(GROUT, GROUT + 5 / SIZE, edge)
        c = tuple(x * jitter * mottle * bevel for x in base)
        t = smoothstep(GROUT - 0.7 / SIZE, GROUT + 0.7 / SIZE, edge)
        return mix(grout, c, t)
    write_png("tiles.png", texel_image(texel), 3, srgb=True)


def tiles_rough():
    """Roughness, linear: the glazed tiles glossy, the grout rough."""
    def texel(u, v):
        _, _, edge = tile_cell(u, v)
        glaze = 0.28 + 0.14 * fbm(u, v, 8, 8, 41)
        t = smoothstep(GROUT - 0.7 / SIZE, GROUT + 0.7 / SIZE, edge)
        return (0.9 + (glaze - 0.9) * t,)
    write_png("tiles_rough.png", texel_image(texel), 1, srgb=False)


def stem_x(v):
    return 0.5 + 0.035 * math.sin(math.pi * 1.3 * v)


# The sprig's leaves: height on the stem, side (-1 left, 1 right), angle from the vertical, length.
LEAVES = [(0.12, -1, 58, 0.34), (0.25, 1, 55, 0.34), (0.39, -1, 50, 0.32),
          (0.52, 1, 45, 0.30), (0.64, -1, 40, 0.27), (0.74, 1, 34, 0.23)]
STEM_TOP = 0.78
TOP_LEAF = (STEM_TOP, 0, 4, 0.21)
HOLES = [(2, 0.55, 0.35, 0.018), (3, 0.45, -0.3, 0.014), (0, 0.7, 0.2, 0.012)]   # leaf, s, t/w, radius


def leaf_frames():
    frames = []
    for k, (h, side, angle, length) in enumerate(LEAVES + [TOP_LEAF]):
        a = math.radians(angle) * (side if side else 1)
        d = (math.sin(a), math.cos(a))               # along the leaf, from its base
        n = (-d[1], d[0])                            # across it
        base = (stem_x(h) + d[0] * 0.02, h + d[1] * 0.02)
        frames.append((base, d, n, length, 0.21 * length, side))
    return frames


def leaf():
    """A sprig of seven leaves on a stem, the stem's foot at the bottom middle (v = 0); RGBA, the
    alpha the cut-out (antialiased over about a texel), the colour kept green where the alpha is 0
    so that lookups between texels fade to leaf colour, not black."""
    frames = leaf_frames()
    px = 1 / SIZE
    dark, mid, vein, edge_col = (srgb_bytes(c) for c in ((58, 104, 34), (96, 152, 52), (170, 206, 104), (48, 86, 30)))
    stem_col = srgb_bytes((104, 122, 52))
    img = []
    for row in range(SIZE):
        line = []
        for col in range(SIZE):
            u, v = texel_uv(col, row)
            colour, alpha = mid, 0.0
            # the stem: tapering, from the bottom edge to the top leaf
            if v <= STEM_TOP + 0.01:
                half = 0.011 - 0.006 * v / STEM_TOP
                dist = abs(u - stem_x(v)) - half
                a = min(1.0, max(0.0, 0.5 - dist / px))
                if a > 0:
                    colour, alpha = stem_col, a
            for k, (base, d, n, length, width, side) in enumerate(frames):
                x, y = u - base[0], v - base[1]
                s = (x * d[0] + y * d[1]) / length
                if s < -0.05 or s > 1.05:
                    continue
                t = x * n[0] + y * n[1]
                t -= 0.12 * length * s * s * (side or 1)       # a slight curl
                sc = min(1.0, max(0.0, s))
                w = width * math.sin(math.pi * sc ** 0.8) ** 0.85
                dist = abs(t) - w
                if s < 0 or s > 1:
                    dist = max(dist, (-s if s < 0 else s - 1) * length)
                a = min(1.0, max(0.0, 0.5 - dist / px))
                for hk, hs, ht, hr in HOLES:
                    if hk == k:
                        hd = math.hypot((s - hs) * length, t - ht * width) - hr
                        a = min(a, min(1.0, max(0.0, 0.5 + hd / px)))
                if a <= alpha:
                    continue
                rel = abs(t) / width if width else 0
                c = mix(dark, mid, smoothstep(0.0, 0.6, sc) * (1 - 0.4 * smoothstep(0.7, 1.0, sc)))
                c = mix(edge_col, c, smoothstep(0.0, 0.012, w - abs(t)))
                rib = max(0.0, 1 - abs(t) / (0.004 * (1.2 - sc) + 0.0015))
                phase = s * 7.0 - rel * 1.6
                side_vein = max(0.0, 1 - abs(phase - round(phase)) / 0.07) * (rel < 0.85) * (s > 0.05)
                c = mix(c, vein, max(rib, 0.6 * side_vein))
                tone = 0.93 + 0.14 * fbm(u, v, 8, 8, 53)
                colour, alpha = tuple(x * tone for x in c), a
            line.append(colour + (alpha,))
        img.append(line)
    write_png("leaf.png", img, 4, srgb=True)


# ---------------------------------------------------------------- the geometry

def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def scale(a, k): return tuple(x * k for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def unit(a): return scale(a, 1 / math.sqrt(dot(a, a)))


def tilt(p):
    """The knot's own frame (y up) to the world: turned by KNOT_TILT about x."""
    c, s = math.cos(KNOT_TILT), math.sin(KNOT_TILT)
    return (p[0], c * p[1] - s * p[2], s * p[1] + c * p[2])


def knot_point(t):
    """The knot on its torus (axis y): longitude P t, latitude Q t; also the torus's normal there,
    which is perpendicular to the knot's tangent, so it starts a frame that closes on itself."""
    lon, lat = P * t, Q * t
    radial = R_CORE + R_PATH * math.cos(lat)
    point = (radial * math.cos(lon), R_PATH * math.sin(lat), radial * math.sin(lon))
    normal = (math.cos(lat) * math.cos(lon), math.sin(lat), math.cos(lat) * math.sin(lon))
    return point, normal


def knot_geometry():
    ring_points, ring_normals = [], []
    for i in range(SEGMENTS):
        t = 2 * math.pi * i / SEGMENTS
        c, n = knot_point(t)
        ahead, _ = knot_point(t + 1e-5)
        behind, _ = knot_point(t - 1e-5)
        tangent = unit(sub(ahead, behind))
        n = unit(sub(n, scale(tangent, dot(n, tangent))))
        b = cross(tangent, n)
        for j in range(SIDES):
            a = 2 * math.pi * j / SIDES
            radial = add(scale(n, math.cos(a)), scale(b, math.sin(a)))
            ring_points.append(tilt(add(c, scale(radial, TUBE))))
            ring_normals.append(tilt(radial))
    low = min(p[1] for p in ring_points)
    positions = [add(scale(p, KNOT_SCALE), (KNOT_AT[0], KNOT_AT[1] - low * KNOT_SCALE, KNOT_AT[2]))
                 for p in ring_points]
    uvs = [(U_REPEAT * i / SEGMENTS, j / SIDES) for i in range(SEGMENTS + 1) for j in range(SIDES + 1)]
    faces = []
    for i in range(SEGMENTS):
        for j in range(SIDES):
            corners = [(i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)]
            faces.append([((ci % SEGMENTS) * SIDES + cj % SIDES, ci * (SIDES + 1) + cj) for ci, cj in corners])
    # winding: counter-clockwise seen from outside (the first corner's normal agrees with the face's)
    (p0, _), (p1, _), (p2, _) = faces[0][:3]
    face_n = cross(sub(positions[p1], positions[p0]), sub(positions[p2], positions[p0]))
    if dot(face_n, ring_normals[p0]) < 0:
        faces = [list(reversed(f)) for f in faces]
    return positions, ring_normals, uvs, faces


def closest_strands(positions):
    """Smallest distance between ring centres far apart along the knot (a self-intersection check)."""
    centres = []
    for i in range(SEGMENTS):
        ring = positions[i * SIDES:(i + 1) * SIDES]
        centres.append(scale(tuple(map(sum, zip(*ring))), 1 / SIDES))
    best = float("inf")
    for i in range(SEGMENTS):
        for j in range(i + SEGMENTS // 8, i + SEGMENTS - SEGMENTS // 8):
            d = sub(centres[i], centres[j % SEGMENTS])
            best = min(best, math.sqrt(dot(d, d)))
    return best


def fmt(x):
    s = "%.5f" % x
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def write_obj():
    positions, normals, uvs, faces = knot_geometry()
    gap = closest_strands(positions)
    assert gap > 2.2 * TUBE * KNOT_SCALE, "the tube meets itself: %.3f" % gap
    lines = ["# glint's textured demo scene, written by make_textured.py: a (%d,%d) torus knot of %d x %d quads "
             "with vertex normals and UVs, a tiled floor and a leaf card with a cut-out" % (P, Q, SEGMENTS, SIDES),
             "mtllib textured.mtl", "", "o knot", "s 1"]
    lines += ["v %s %s %s" % tuple(map(fmt, p)) for p in positions]
    lines += ["vt %s %s" % tuple(map(fmt, t)) for t in uvs]
    lines += ["vn %s %s %s" % tuple(map(fmt, n)) for n in normals]
    lines.append("usemtl wood")
    lines += ["f " + " ".join("%d/%d/%d" % (p + 1, t + 1, p + 1) for p, t in f) for f in faces]
    v0, t0, n0 = len(positions), len(uvs), len(normals)

    # the floor: y = 0, u along +x, v along -z (away from the camera)
    h, k = FLOOR_HALF, FLOOR_UV
    lines += ["", "o floor", "s off"]
    lines += ["v %s 0 %s" % (fmt(x), fmt(z)) for x, z in ((-h, h), (h, h), (h, -h), (-h, -h))]
    lines += ["vt %d %d" % uv for uv in ((0, 0), (k, 0), (k, k), (0, k))]
    lines.append("vn 0 1 0")
    lines.append("usemtl tiles")
    lines.append("f " + " ".join("%d/%d/%d" % (v0 + i, t0 + i, n0 + 1) for i in (1, 2, 3, 4)))
    v0, t0, n0 = v0 + 4, t0 + 4, n0 + 1

    # the card: a vertical square standing on the floor, its front turned toward the light
    right = (math.cos(CARD_FACING), 0.0, -math.sin(CARD_FACING))
    front = (math.sin(CARD_FACING), 0.0, math.cos(CARD_FACING))
    half = CARD_SIZE / 2
    corners = [add(CARD_BASE, add(scale(right, sx * half), (0, y, 0)))
               for sx, y in ((-1, 0), (1, 0), (1, CARD_SIZE), (-1, CARD_SIZE))]
    lines += ["", "o leaf_card", "s off"]
    lines += ["v %s %s %s" % tuple(map(fmt, p)) for p in corners]
    lines += ["vt %d %d" % uv for uv in ((0, 0), (1, 0), (1, 1), (0, 1))]
    lines.append("vn %s %s %s" % tuple(map(fmt, front)))
    lines.append("usemtl leaf")
    lines.append("f " + " ".join("%d/%d/%d" % (v0 + i, t0 + i, n0 + 1) for i in (1, 2, 3, 4)))
    with open(os.path.join(HERE, "knot.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")


MTL = """\
# glint's textured demo scene, written by make_textured.py; read as Blender's OBJ importer reads it

# glossy plastic: map_Kd replaces Kd as the base colour; Ks makes it plastic, Ns 200 roughness 0.553
newmtl wood
Kd 1 1 1
Ks 0.5 0.5 0.5
Ns 200
illum 2
map_Kd wood.png

# glazed tiles: map_Pr (linear grey) gives the roughness and makes it plastic
newmtl tiles
Kd 1 1 1
Ks 0.5 0.5 0.5
illum 2
map_Kd tiles.png
map_Pr tiles_rough.png

# a leaf card: diffuse, its colour and its cut-out from one RGBA file (map_d reads the alpha)
newmtl leaf
Kd 0.3 0.6 0.2
illum 1
map_Kd leaf.png
map_d leaf.png
"""


def main():
    write_obj()
    with open(os.path.join(HERE, "textured.mtl"), "w") as f:
        f.write(MTL)
    wood()
    tiles()
    tiles_rough()
    leaf()


if __name__ == "__main__":
    main()
