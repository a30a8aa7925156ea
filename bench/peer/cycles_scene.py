"""Renders a glint scene in Blender Cycles, for the peer benchmark (bench/peer/run_cycles.py).

Run inside Blender:
  blender -b --factory-startup -noaudio -t 2 --python bench/peer/cycles_scene.py -- \
      SCENE.json --width W --height H --spp 4,16,64 --seeds 1,2,3 --out PREFIX

Builds the scene as glint reads it (y up in glint, z up in Blender): triangle meshes from inline
vertices or OBJ files (their MTL materials mapped as glint maps them, docs/obj_materials.md, with
the scene's `materials` overrides by name), Diffuse BSDF for diffuse, a Glossy BSDF for mirrors
(Sharp when smooth, GGX of the same Roughness when rough: glint's mirror is that surface), a Sharp
Glass BSDF for smooth glass with `fresnel: "exact"` (the same surface; Cycles 3.4's rough Glass
BSDF takes its Fresnel term at the shading normal, not the microfacet's, so rough glass is
refused, as are metal, plastic and Schlick's glass), an Emission shader of strength 1 whose
colour is glint's radiance, a world of glint's film.background (black by default), a pinhole
camera with glint's vertical field of view and a box pixel filter of width 1 (glint's
film.filter "box"). No clamping, denoising, adaptive sampling or light threshold; caustics on;
128 bounces of every kind.

Surface maps as glint reads them (README.md, "Scene format"): the OBJ's `vt` (or inline `uvs`) as
the mesh's UV map; its `vn` (or inline `normals`) as custom split normals of smooth faces, a face
without a normal on every corner flat; the shadow terminator's shading and geometry offsets 0
(glint moves no shading point). Textures (JSON `{"texture": ...}`; MTL map_Kd, map_Pr/map_Ns,
map_Ke, map_d, with -s/-o) are Image Texture nodes (Linear, Repeat) at the UV map through a
Mapping node (uv·uv_scale + uv_offset), their `channel` a Separate Color output or the Alpha,
their `scale` a Multiply. Each image is handed to Cycles already decoded to linear floats as glint
decodes it (an sRGB byte by the exact sRGB curve, a linear one as byte/255, alpha never sRGB), so
that Cycles' bilinear lookup interpolates the same linear values as glint's: for an 8-bit sRGB
image Cycles 3.4 interpolates the encoded bytes and decodes the result (halfway between a black
and a white texel 0.214 instead of 0.5). A roughness texture is clamped to [0.032, 1] as glint
clamps it. A cut-out is a Mix Shader between a Transparent BSDF and the surface whose factor is
alpha >= cutoff (Math Greater Than against the float just below the cutoff): the surface is there
or not, as in glint. Normal maps are refused (Cycles' diffuse BSDF under one applies its bump
shadowing term, and its Normal Map strength blends where glint's scales).

With --bsdf-only, emitters are not sampled as lights (their materials' Multiple Importance off):
Cycles' BSDF-only estimator. For each (spp, seed) it writes PREFIX_SPP_SEED.pfm (linear RGB) and
one JSON line to PREFIX.jsonl with the render's CPU seconds (the process's user + sys over the
render call, all threads, Cycles' scene sync and BVH build included), its wall seconds, and the
seconds this script took to build the scene in Blender before (`import`).
"""
import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy as np


def to_blender(v):
    """glint's (x, y, z), y up, as Blender's (x, -z, y), z up."""
    return (v[0], -v[2], v[1])


def fail(message):
    sys.exit(f"cycles_scene.py: {message}")


# --- OBJ and MTL, read as glint reads them (tinyobjloader's rules) -------------------------------

def parse_obj(path):
    """Positions, texture coordinates, normals, fan-triangulated faces in file order (each corner
    (v, vt, vn), -1 where the face gives none or names one the file lacks), each face's usemtl
    name and the libraries (glint's rules, core/io/obj_loader.cpp)."""
    positions, uvs, normals, faces, names, current, libraries = [], [], [], [], [], None, []

    def index(text, count):
        if not text:
            return -1
        i = int(text)
        return i - 1 if i > 0 else count + i

    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                positions.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "vt":
                uvs.append((float(parts[1]), float(parts[2]) if len(parts) > 2 else 0.0))
            elif parts[0] == "vn":
                normals.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "usemtl":
                current = parts[1] if len(parts) > 1 else None
            elif parts[0] == "mtllib":
                libraries += parts[1:]
            elif parts[0] == "f":
                corners = []
                for p in parts[1:]:
                    fields = (p.split("/") + ["", ""])[:3]
                    corners.append((index(fields[0], len(positions)), index(fields[1], len(uvs)),
                                    index(fields[2], len(normals))))
                for k in range(2, len(corners)):
                    faces.append((corners[0], corners[k - 1], corners[k]))
                    names.append(current)

    def valid(i, count):
        return i if 0 <= i < count else -1

    faces = [tuple((c[0], valid(c[1], len(uvs)), valid(c[2], len(normals))) for c in face) for face in faces]
    return positions, uvs, normals, faces, names, libraries


# Texture options tinyobjloader knows and how many values each takes (it takes that many words
# whether or not they are numbers); the first other word starts the file name, the rest of the line.
TEXTURE_OPTIONS = {"-blendu": 1, "-blendv": 1, "-clamp": 1, "-boost": 1, "-bm": 1, "-o": 3, "-s": 3, "-t": 3,
                   "-type": 1, "-texres": 1, "-imfchan": 1, "-mm": 2, "-colorspace": 1}
TEXTURE_KEYS = ("map_Ka", "map_Kd", "map_Ks", "map_Ns", "map_bump", "map_Bump", "bump", "map_d", "map_disp",
                "map_Disp", "disp", "refl", "map_Pr", "map_Pm", "map_Ps", "map_Ke", "norm")


def number(text, default):
    try:
        return float(text)
    except ValueError:
        return default


def texture_option(text):
    """An MTL texture line after its key: {file, uv_scale, uv_offset, bm}, or None without a file."""
    out = {"file": None, "uv_scale": [1.0, 1.0], "uv_offset": [0.0, 0.0], "bm": 1.0}
    pos, n = 0, len(text)

    def word():
        nonlocal pos
        while pos < n and text[pos] in " \t":
            pos += 1
        start = pos
        while pos < n and text[pos] not in " \t\r":
            pos += 1
        return text[start:pos]

    while True:
        while pos < n and text[pos] in " \t":
            pos += 1
        if pos >= n:
            break
        start = pos
        option = word()
        if option in TEXTURE_OPTIONS and pos < n:  # an option is followed by a space
            values = [word() for _ in range(TEXTURE_OPTIONS[option])]
            if option == "-s":
                out["uv_scale"] = [number(v, 1.0) for v in values[:2]]
            elif option == "-o":
                out["uv_offset"] = [number(v, 0.0) for v in values[:2]]
            elif option == "-bm":
                out["bm"] = number(values[0], 1.0)
        else:
            out["file"] = text[start:]
            break
    return out if out["file"] else None


def parse_mtl(path):
    """Each material's values as tinyobjloader reads them (its defaults where absent)."""
    materials, current = {}, None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            line = line.strip()
            parts = line.split()
            if not parts:
                continue
            key = parts[0]
            if key == "newmtl":
                current = materials.setdefault(parts[1] if len(parts) > 1 else "", {
                    "Kd": [0.0] * 3, "Ks": [0.0] * 3, "Tf": [0.0] * 3, "Ke": [0.0] * 3, "Ni": 1.0, "Ns": 1.0,
                    "illum": 0, "d": 1.0, "Pr": 0.0, "Pm": 0.0, "Ps": 0.0, "Pc": 0.0, "maps": {}, "has_d": False})
            elif current is None:
                continue
            elif key in ("Kd", "Ks", "Ke", "Tf", "Kt"):
                current["Tf" if key == "Kt" else key] = [number(x, 0.0) for x in (parts[1:4] + ["", "", ""])[:3]]
            elif key in ("Ni", "Ns", "Pr", "Pm", "Ps", "Pc"):
                current[key] = number(parts[1] if len(parts) > 1 else "", 0.0)
            elif key == "illum":
                current["illum"] = int(number(parts[1], 0)) if len(parts) > 1 else 0
            elif key == "d":
                current["d"], current["has_d"] = number(parts[1] if len(parts) > 1 else "", 0.0), True
            elif key == "Tr" and not current["has_d"]:
                current["d"] = 1.0 - number(parts[1] if len(parts) > 1 else "", 0.0)
            elif key in TEXTURE_KEYS:
                option = texture_option(line[len(key):])
                if option:
                    current["maps"]["bump" if key in ("map_bump", "map_Bump") else key] = option
    return materials


def black(c):
    return not any(c)


def mtl_roughness(m):
    if m["Pr"] > 0:
        return min(1.0, m["Pr"])
    if m["Ns"] == 1:
        return 0.0
    return 1 - math.sqrt(min(max(m["Ns"], 0.0), 1000.0) / 1000)


def mtl_material(m, obj_folder):
    """glint's material for an MTL material (core/io/mtl_material.cpp), its textures as lookups."""
    maps = m["maps"]
    clamp = lambda c: [min(1.0, x) for x in c]
    if m["illum"] in (4, 6, 7, 9) or m["d"] < 1:
        g = default_material("glass")
        g["roughness"] = mtl_roughness(m)
        g["albedo"] = [1.0] * 3 if black(m["Tf"]) else clamp(m["Tf"])
        if m["Ni"] > 1 or 0 < m["Ni"] < 1:
            g["ior"] = m["Ni"]
    elif m["illum"] == 3 or (black(m["Kd"]) and not black(m["Ks"])):
        g = default_material("mirror")
        g["roughness"] = mtl_roughness(m)
        g["albedo"] = [1.0] * 3 if black(m["Ks"]) else clamp(m["Ks"])
    elif not black(m["Ks"]) or m["Pr"] > 0 or m["Pm"] > 0 or "map_Pr" in maps or "map_Pm" in maps:
        g = default_material("plastic")
        g["albedo"], g["roughness"], g["metallic"] = clamp(m["Kd"]), mtl_roughness(m), min(1.0, m["Pm"])
    else:
        g = default_material("diffuse")
        g["albedo"] = clamp(m["Kd"])
    g["emission"] = list(m["Ke"])

    def lookup(key, colorspace):
        t = maps[key]
        scale = [1.0] * 3 if key in ("map_Kd", "map_Ke") else 1.0
        return {"file": os.path.join(obj_folder, t["file"]), "scale": scale, "uv_scale": t["uv_scale"],
                "uv_offset": t["uv_offset"], "colorspace": colorspace, "channel": -1}

    kind = g["type"]
    if "map_Kd" in maps and kind in ("diffuse", "plastic"):
        g["maps"]["albedo"] = lookup("map_Kd", "srgb")
    if kind != "diffuse":
        for key in ("map_Pr", "map_Ns"):
            if key in maps:
                g["maps"]["roughness"] = lookup(key, "linear")
                break
    if "map_Pm" in maps and kind in ("metal", "plastic"):
        g["maps"]["metallic"] = lookup("map_Pm", "linear")
    if "map_Ke" in maps:
        g["maps"]["emission"] = lookup("map_Ke", "srgb")
    if "map_d" in maps:
        alpha = lookup("map_d", "linear")
        alpha["channel"] = "mask"  # the alpha where the image has one, else its grey (glint's map_d)
        g["maps"]["alpha"] = alpha
    if "norm" in maps or "bump" in maps:
        g["maps"]["normal"] = lookup("norm" if "norm" in maps else "bump", "linear")
    return g


def drop_twins(positions, faces, names):
    """Faces without the exact duplicates of earlier ones. CornellBox-Original repeats a side face
    of each box where its bottom face should be (`f -12 -11 -10 -9`). glint renders such a pair
    as one face (a ray leaves a surface offset past its rounding error, so the twin is never hit);
    a ray Cycles spawns on one face hits the other at distance zero, and the face goes black."""
    seen, kept_faces, kept_names = set(), [], []
    for face, name in zip(faces, names):
        key = tuple(sorted(tuple(positions[c[0]]) for c in face))
        if key not in seen:
            seen.add(key)
            kept_faces.append(face)
            kept_names.append(name)
    return kept_faces, kept_names


# --- glint's materials ------------------------------------------------------------------------

def colour(value):
    return [float(value)] * 3 if isinstance(value, (int, float)) else [float(x) for x in value]


SMOOTH_ROUGHNESS = 0.0316  # glint handles roughness below this (α below 0.001) as smooth
MIN_TEXTURED_ROUGHNESS = 0.032  # core/scene/material_maps.h: a textured roughness is at least this


def default_material(kind):
    """glint's defaults for a type (core/scene/material.h); maps: the textured fields."""
    return {"type": kind, "albedo": [0.75] * 3 if kind in ("diffuse", "plastic") else [1.0] * 3, "roughness": 0.0,
            "ior": 1.5, "fresnel": "schlick", "metallic": 1.0 if kind == "metal" else 0.0,
            "emission": [0.0] * 3, "alpha_cutoff": 0.5, "normal_strength": 1.0, "maps": {}}


def texture_lookup(value, folder, usage):
    """A JSON {"texture": file, "scale", "uv_scale", "uv_offset", "colorspace", "channel"}."""
    colourful = usage in ("colour", "emission")
    scale = value.get("scale", 1.0)
    return {"file": os.path.join(folder, value["texture"]),
            "scale": colour(scale) if colourful else float(scale),
            "uv_scale": [float(x) for x in value.get("uv_scale", [1, 1])],
            "uv_offset": [float(x) for x in value.get("uv_offset", [0, 0])],
            "colorspace": value.get("colorspace", "srgb" if colourful else "linear"),
            "channel": "rgba".index(value["channel"]) if "channel" in value else (3 if usage == "alpha" else -1)}


def material_fields(fields, m, folder):
    """glint's material_fields (core/assembly/scene_loader.cpp): `fields` over m; a new type brings its
    defaults for every field but the emission, the cut-out and the normal map."""
    m = json.loads(json.dumps(m))
    if "type" in fields and fields["type"] != m["type"]:
        out = default_material(fields["type"])
        for key in ("emission", "alpha_cutoff", "normal_strength"):
            out[key] = m[key]
        out["maps"] = {k: v for k, v in m["maps"].items() if k in ("emission", "alpha", "normal")}
        m = out
    for key, usage in (("albedo", "colour"), ("emission", "emission"), ("roughness", "number"),
                       ("metallic", "number")):
        if key not in fields:
            continue
        if isinstance(fields[key], dict):
            m["maps"][key] = texture_lookup(fields[key], folder, usage)
            m[key] = m["maps"][key]["scale"]
        else:
            m["maps"].pop(key, None)
            m[key] = colour(fields[key]) if usage in ("colour", "emission") else float(fields[key])
    for key in ("ior", "alpha_cutoff"):
        if key in fields:
            m[key] = float(fields[key])
    if "fresnel" in fields:
        m["fresnel"] = fields["fresnel"]
    if "alpha" in fields:
        m["maps"]["alpha"] = texture_lookup(fields["alpha"], folder, "alpha")
    if "normal_map" in fields:
        m["maps"]["normal"] = texture_lookup(fields["normal_map"], folder, "number")
        m["normal_strength"], m["maps"]["normal"]["scale"] = m["maps"]["normal"]["scale"], 1.0
    return m


def checked(m, where):
    """m, if Cycles 3.4 has the same surface."""
    kind = m["type"]
    if kind not in ("diffuse", "mirror", "glass"):
        fail(f"{where}: {kind} has no Cycles 3.4 BSDF that is the same surface")
    if kind == "glass" and (m["roughness"] >= SMOOTH_ROUGHNESS or "roughness" in m["maps"] or m["fresnel"] != "exact"):
        fail(f"{where}: only smooth glass with exact Fresnel is the same surface as Cycles' Glass BSDF")
    if "normal" in m["maps"]:
        fail(f"{where}: normal maps are not the same in Cycles 3.4 (its diffuse BSDF's bump shadowing term)")
    return m


# --- Textures ---------------------------------------------------------------------------------

IMAGES = {}


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def texture_image(path, colorspace):
    """(Blender image, the file's own channel count, whether its values stay in [0, 1]): linear
    float RGBA as glint decodes the file, an 8-bit colour channel by the exact sRGB curve or as
    byte/255, alpha as byte/255; grey in R, G and B; a missing alpha 1. Rows bottom first, as
    Blender stores them."""
    key = (path, colorspace)
    if key in IMAGES:
        return IMAGES[key]
    with open(path, "rb") as f:
        head = f.read(16)
    if head.startswith(b"\x89PNG") or head.startswith(b"\xff\xd8"):
        from PIL import Image
        with Image.open(path) as im:
            if im.mode == "P":
                im = im.convert("RGBA" if "transparency" in im.info else "RGB")
            if im.mode in ("I;16", "I;16B", "I"):
                texels = (np.asarray(im).astype(np.uint32) >> 8).astype(np.uint8)[:, :, None]  # stb's 16 to 8
            else:
                if im.mode not in ("L", "LA", "RGB", "RGBA"):
                    im = im.convert("RGB")
                texels = np.asarray(im)
                texels = texels[:, :, None] if texels.ndim == 2 else texels
        channels = texels.shape[2]
        values = texels.astype(np.float64) / 255
        colour_channels = channels - (channels in (2, 4))
        if colorspace == "srgb":
            values[:, :, :colour_channels] = srgb_to_linear(values[:, :, :colour_channels])
        h, w = values.shape[:2]
        rgba = np.ones((h, w, 4))
        rgba[:, :, :3] = values[:, :, :colour_channels] if colour_channels == 3 else values[:, :, :1]
        if channels in (2, 4):
            rgba[:, :, 3] = values[:, :, -1]
        image = bpy.data.images.new(os.path.basename(path) + "." + colorspace, w, h, alpha=True, float_buffer=True)
        image.colorspace_settings.name = "Linear"
        image.alpha_mode = "CHANNEL_PACKED"
        image.pixels.foreach_set(np.ascontiguousarray(rgba[::-1]).astype(np.float32).ravel())
        bounded = True
    else:  # Radiance .hdr or OpenEXR: linear floats, as glint reads them
        image = bpy.data.images.load(path)
        image.colorspace_settings.name = "Linear"
        image.alpha_mode = "CHANNEL_PACKED"
        channels = 4 if image.depth in (64, 128) and head.startswith(b"\x76\x2f\x31\x01") else 3
        bounded = False
    IMAGES[key] = (image, channels, bounded)
    return IMAGES[key]


class Nodes:
    """A material's node tree, with the texture lookups glint's material maps make."""

    def __init__(self, mat):
        self.nodes, self.links = mat.node_tree.nodes, mat.node_tree.links
        self.nodes.clear()
        self.uv = None

    def new(self, kind, **settings):
        node = self.nodes.new(kind)
        for k, v in settings.items():
            setattr(node, k, v)
        return node

    def link(self, a, b):
        self.links.new(a, b)

    def image(self, t):
        """The Image Texture node of lookup t: Linear, Repeat, at uv·uv_scale + uv_offset."""
        image, channels, bounded = texture_image(t["file"], t["colorspace"])
        node = self.new("ShaderNodeTexImage", image=image, interpolation="Linear", extension="REPEAT")
        if self.uv is None:
            self.uv = self.new("ShaderNodeUVMap", uv_map="UVMap").outputs["UV"]
        vector = self.uv
        if t["uv_scale"] != [1, 1] or t["uv_offset"] != [0, 0]:
            mapping = self.new("ShaderNodeMapping", vector_type="POINT")
            mapping.inputs["Location"].default_value = (*t["uv_offset"], 0)
            mapping.inputs["Scale"].default_value = (*t["uv_scale"], 1)
            self.link(vector, mapping.inputs["Vector"])
            vector = mapping.outputs["Vector"]
        self.link(vector, node.inputs["Vector"])
        return node, channels, bounded

    def channel(self, node, k):
        """Channel k (0..3: r, g, b, a) of an image node's output (grey images: their grey)."""
        if k == 3:
            return node.outputs["Alpha"]
        split = self.new("ShaderNodeSeparateColor", mode="RGB")
        self.link(node.outputs["Color"], split.inputs["Color"])
        return split.outputs[k]

    def colour(self, t, clamp):
        """The lookup's colour times its scale (clamped to [0, 1] for a reflectance, as glint)."""
        node, channels, bounded = self.image(t)
        out = node.outputs["Color"] if t["channel"] < 0 else self.channel(node, t["channel"])
        if t["scale"] != [1, 1, 1] or (clamp and not bounded):
            mix = self.new("ShaderNodeMixRGB", blend_type="MULTIPLY", use_clamp=clamp)
            mix.inputs["Fac"].default_value = 1
            self.link(out, mix.inputs["Color1"])
            mix.inputs["Color2"].default_value = (*t["scale"], 1)
            out = mix.outputs["Color"]
        return out

    def value(self, t):
        """The lookup's value times its scale: its channel, or the first one ('mask': a cut-out's
        alpha where the image has one, else its grey)."""
        node, channels, bounded = self.image(t)
        k = t["channel"]
        if k == "mask":
            k = 3 if channels in (2, 4) else 0
        out = self.channel(node, max(k, 0))
        if t["scale"] != 1:
            out = self.math("MULTIPLY", out, t["scale"])
        return out

    def math(self, operation, a, b, clamp=False):
        node = self.new("ShaderNodeMath", operation=operation, use_clamp=clamp)
        self.link(a, node.inputs[0])
        node.inputs[1].default_value = b
        return node.outputs[0]


def cycles_material(name, m, bsdf_only=False):
    mat = bpy.data.materials.new(name)
    mat.cycles.sample_as_light = not bsdf_only
    mat.use_nodes = True
    g = Nodes(mat)
    maps = m["maps"]
    out = g.new("ShaderNodeOutputMaterial")
    if m["type"] == "diffuse":
        bsdf = g.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Roughness"].default_value = 0
    elif m["type"] == "mirror":
        bsdf = g.new("ShaderNodeBsdfGlossy")
        textured = "roughness" in maps
        bsdf.distribution = "SHARP" if m["roughness"] < SMOOTH_ROUGHNESS and not textured else "GGX"
        bsdf.inputs["Roughness"].default_value = m["roughness"]
        if textured:
            # glint: clamp(texel · scale, 0.032, 1)
            roughness = g.math("MAXIMUM", g.value(maps["roughness"]), MIN_TEXTURED_ROUGHNESS, clamp=True)
            g.link(roughness, bsdf.inputs["Roughness"])
    else:
        bsdf = g.new("ShaderNodeBsdfGlass", distribution="SHARP")
        bsdf.inputs["IOR"].default_value = m["ior"]
    bsdf.inputs["Color"].default_value = (*m["albedo"], 1)
    if "albedo" in maps:
        g.link(g.colour(maps["albedo"], clamp=True), bsdf.inputs["Color"])
    shader = bsdf.outputs[0]
    if any(m["emission"]) or "emission" in maps:
        emit = g.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = (*m["emission"], 1)
        emit.inputs["Strength"].default_value = 1.0
        if "emission" in maps:
            g.link(g.colour(maps["emission"], clamp=False), emit.inputs["Color"])
        add = g.new("ShaderNodeAddShader")
        g.link(shader, add.inputs[0])
        g.link(emit.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    if "alpha" in maps:
        # glint keeps the surface where alpha >= cutoff: alpha > the float just below the cutoff.
        below = float(np.nextafter(np.float32(m["alpha_cutoff"]), np.float32(-1)))
        keep = g.math("GREATER_THAN", g.value(maps["alpha"]), below)
        mix = g.new("ShaderNodeMixShader")
        g.link(keep, mix.inputs["Fac"])
        g.link(g.new("ShaderNodeBsdfTransparent").outputs[0], mix.inputs[1])
        g.link(shader, mix.inputs[2])
        shader = mix.outputs[0]
    g.link(shader, out.inputs["Surface"])
    return mat


# --- The scene --------------------------------------------------------------------------------

def add_mesh(index, obj, folder, bsdf_only):
    if obj.get("type") != "mesh":
        fail("spheres are not built here (the benchmark leaves sphere scenes out)")
    scale = obj.get("scale", 1)
    scale = [scale] * 3 if isinstance(scale, (int, float)) else scale
    translate = obj.get("translate", [0, 0, 0])
    own = material_fields(obj.get("material", {}), default_material("diffuse"), folder)
    if "emission" in obj:
        own["emission"] = colour(obj["emission"])
        own["maps"].pop("emission", None)
    library = {}
    if "file" in obj:
        path = os.path.join(folder, obj["file"])
        positions, uvs, normals, faces, names, libraries = parse_obj(path)
        # The object's own material replaces the library's (glint then opens it only for the
        # names `materials` overrides).
        replaced = "material" in obj or "emission" in obj
        for lib in libraries if not replaced or obj.get("materials") else []:
            for name, m in parse_mtl(os.path.join(os.path.dirname(path), lib)).items():
                library.setdefault(name, own if replaced else mtl_material(m, os.path.dirname(path)))
        for name, fields in obj.get("materials", {}).items():
            if name not in library:
                fail(f"objects[{index}].materials: no material {name}")
            library[name] = material_fields(fields, library[name], folder)
    else:
        positions, uvs, normals = obj["vertices"], obj.get("uvs", []), obj.get("normals", [])
        faces = [tuple((i, i if uvs else -1, i if normals else -1) for i in t) for t in obj["indices"]]
        names = [None] * len(faces)
    faces, names = drop_twins(positions, faces, names)
    placed = [to_blender([v[k] * scale[k] + translate[k] for k in range(3)]) for v in positions]
    mesh = bpy.data.meshes.new(f"mesh{index}")
    mesh.from_pydata(placed, [], [tuple(c[0] for c in face) for face in faces])
    used = sorted({n for n in names if n in library})
    mesh.materials.append(cycles_material(f"m{index}", checked(own, f"objects[{index}]"), bsdf_only))
    for name in used:
        mesh.materials.append(cycles_material(f"m{index}_{name}", checked(library[name], f"objects[{index}] {name}"),
                                              bsdf_only))
    mesh.polygons.foreach_set("material_index", [used.index(n) + 1 if n in library else 0 for n in names])
    if uvs:
        # glint: a corner without a texture coordinate has (0, 0)
        corner_uvs = [uvs[c[1]] if c[1] >= 0 else (0.0, 0.0) for face in faces for c in face]
        mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", np.array(corner_uvs, np.float32).ravel())
    smooth = [all(c[2] >= 0 for c in face) for face in faces]
    if any(smooth):
        # A face with a normal on each corner is smooth, its corners' normals the file's (as
        # normals transform under the object's scale: n / scale); the others flat (a zero custom
        # normal keeps Blender's own, the face's). Blender normalises each corner's normal;
        # glint interpolates them as given, the same for unit normals.
        lengths = []
        corner_normals = []
        for face, is_smooth in zip(faces, smooth):
            for c in face:
                if is_smooth:
                    n = to_blender([normals[c[2]][k] / scale[k] for k in range(3)])
                    lengths.append(math.sqrt(sum(x * x for x in normals[c[2]])))
                    corner_normals.append(n)
                else:
                    corner_normals.append((0.0, 0.0, 0.0))
        if abs(max(lengths) - 1) > 1e-3 or abs(min(lengths) - 1) > 1e-3:
            print(f"cycles_scene.py: objects[{index}]: normals of length {min(lengths):.4f} to {max(lengths):.4f}: "
                  "Blender normalises them, glint interpolates them as given", file=sys.stderr)
        mesh.polygons.foreach_set("use_smooth", smooth)
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = math.pi
        mesh.normals_split_custom_set(corner_normals)
    mesh.update()
    blender_object = bpy.data.objects.new(f"object{index}", mesh)
    # Cycles 3.4 moves the shading point of smooth faces off the triangle (geometry offset 0.1 by
    # default) and can offset the terminator; glint does neither.
    blender_object.cycles.shadow_terminator_offset = 0
    blender_object.cycles.shadow_terminator_geometry_offset = 0
    bpy.context.scene.collection.objects.link(blender_object)


def add_camera(camera):
    position = camera.get("position", [0, 0, 0])
    if "look_at" in camera:
        forward = [a - b for a, b in zip(camera["look_at"], position)]
    else:
        forward = camera.get("direction", [0, 0, -1])
    up = camera.get("up", [0, 1, 0])
    f = np.array(to_blender(forward), float)
    f /= np.linalg.norm(f)
    right = np.cross(f, np.array(to_blender(up), float))
    right /= np.linalg.norm(right)
    true_up = np.cross(right, f)
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(camera.get("fov", 40))
    data.clip_start = max(camera.get("near", 0), 1e-5)
    data.clip_end = 1e9
    cam = bpy.data.objects.new("camera", data)
    from mathutils import Matrix
    rotation = Matrix([[right[i], true_up[i], -f[i]] for i in range(3)])
    cam.matrix_world = Matrix.Translation(to_blender(position)) @ rotation.to_4x4()
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam


def configure(scene, width, height, background):
    scene.render.engine = "CYCLES"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0
    c.blur_glossy = 0
    c.caustics_reflective = c.caustics_refractive = True
    c.light_sampling_threshold = 0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 128
    c.transparent_max_bounces = c.volume_bounces = 128
    c.use_animated_seed = False
    # glint's film.background: the radiance of rays that leave the scene (black by default).
    scene.world = bpy.data.worlds.new("background")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (*background, 1)
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1 if any(background) else 0
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"


def environment_image(path):
    """The equirectangular file as glint reads it: linear floats, negative values (lossy EXR's
    undershoot) set to 0, handed to Cycles as an image in memory."""
    loaded = bpy.data.images.load(path)
    w, h = loaded.size
    rgba = np.empty(w * h * 4, np.float32)
    loaded.pixels.foreach_get(rgba)
    bpy.data.images.remove(loaded)
    rgba = rgba.reshape(h, w, 4)
    rgba[:, :, :3] = np.maximum(rgba[:, :, :3], 0)
    rgba[:, :, 3] = 1
    image = bpy.data.images.new(os.path.basename(path), w, h, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Linear"
    image.pixels.foreach_set(rgba.ravel())
    return image


def add_environment(world, env, folder):
    """glint's environment as Cycles' Environment Texture (Linear, equirectangular) in the world.
    glint's direction d (y up) sees u = 1/2 + (atan2(d.z, d.x) + rotation)/2π; Blender's D = (d.x,
    -d.z, d.y) sees u = 1/2 - atan2(D.y, D.x)/2π: the same texel once a Mapping node turns D by
    -rotation about z. The importance map stays Cycles' default (background MIS on, automatic
    resolution)."""
    if not env.get("visible", True):
        fail("environment.visible false is not translated")
    nodes, links = world.node_tree.nodes, world.node_tree.links
    texture = nodes.new("ShaderNodeTexEnvironment")
    texture.image = environment_image(os.path.join(folder, env["file"]))
    texture.interpolation = "Linear"
    texture.projection = "EQUIRECTANGULAR"
    mapping = nodes.new("ShaderNodeMapping")
    mapping.vector_type = "VECTOR"
    mapping.inputs["Rotation"].default_value = (0, 0, -math.radians(env.get("rotation", 0)))
    links.new(nodes.new("ShaderNodeTexCoord").outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    background = nodes["Background"]
    links.new(texture.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = env.get("strength", 1)


def add_sun(sun):
    """glint's sun as a Sun lamp: Strength is the irradiance (its largest component, the colour
    the rest), Angle the angular diameter, shining along -direction."""
    irradiance = colour(sun.get("irradiance", 1))
    strength = max(irradiance)
    data = bpy.data.lights.new("sun", "SUN")
    data.energy = strength
    data.color = [c / strength for c in irradiance] if strength > 0 else (1, 1, 1)
    data.angle = math.radians(sun.get("angle", 0.526))
    lamp = bpy.data.objects.new("sun", data)
    toward = np.array(to_blender(sun["direction"]), float)
    from mathutils import Vector
    lamp.rotation_euler = Vector(toward).to_track_quat("Z", "Y").to_euler()  # local +z toward the sun
    bpy.context.scene.collection.objects.link(lamp)


def write_pfm(path, exr):
    image = bpy.data.images.load(exr)
    w, h = image.size
    rgba = np.array(image.pixels[:], dtype=np.float32).reshape(h, w, 4)  # bottom row first, as PFM
    with open(path, "wb") as f:
        f.write(f"PF\n{w} {h}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(rgba[:, :, :3]).astype("<f4").tobytes())
    bpy.data.images.remove(image)
    os.remove(exr)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    ap.add_argument("--spp", required=True)
    ap.add_argument("--seeds", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--bsdf-only", action="store_true")
    a = ap.parse_args(argv)
    with open(a.scene) as f:
        glint_scene = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    imported = time.perf_counter()
    scene = bpy.context.scene
    configure(scene, a.width, a.height, colour(glint_scene.get("film", {}).get("background", 0)))
    for i, obj in enumerate(glint_scene.get("objects", [])):
        add_mesh(i, obj, os.path.dirname(os.path.abspath(a.scene)), a.bsdf_only)
    add_camera(glint_scene.get("camera", {}))
    if "environment" in glint_scene:
        add_environment(scene.world, glint_scene["environment"], os.path.dirname(os.path.abspath(a.scene)))
    if "sun" in glint_scene:
        add_sun(glint_scene["sun"])
    imported = time.perf_counter() - imported
    with open(a.out + ".jsonl", "a") as log:
        for spp in [int(s) for s in a.spp.split(",")]:
            for seed in [int(s) for s in a.seeds.split(",")]:
                scene.cycles.samples = spp
                scene.cycles.seed = seed
                cpu, wall = time.process_time(), time.perf_counter()
                bpy.ops.render.render()
                cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
                exr = f"{a.out}_{spp}_{seed}.exr"
                bpy.data.images["Render Result"].save_render(exr)
                write_pfm(f"{a.out}_{spp}_{seed}.pfm", exr)
                log.write(json.dumps({"spp": spp, "seed": seed, "cpu": cpu, "wall": wall, "import": imported}) + "\n")
                log.flush()


main()
