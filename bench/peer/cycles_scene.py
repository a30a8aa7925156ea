"""Renders a glint scene in Blender Cycles, for the peer benchmark (bench/peer/run_cycles.py).

Run inside Blender:
  blender -b --factory-startup -noaudio -t 2 --python bench/peer/cycles_scene.py -- \
      SCENE.json --width W --height H --spp 4,16,64 --seeds 1,2,3 --out PREFIX

Builds the scene as glint reads it (y up in glint, z up in Blender): triangle meshes from inline
vertices or OBJ files (with their MTL's Kd and Ke), Diffuse BSDF for diffuse, a Glossy BSDF for
mirrors (Sharp when smooth, GGX of the same Roughness when rough: glint's mirror is that surface),
a Sharp Glass BSDF for smooth glass with `fresnel: "exact"` (the same surface; Cycles 3.4's rough
Glass BSDF takes its Fresnel term at the shading normal, not the microfacet's, so rough glass is
refused, as are metal, plastic and Schlick's glass), an Emission shader of strength 1 whose colour is glint's
radiance, a black world, a pinhole camera with glint's vertical field of view and a box pixel
filter of width 1 (glint's film.filter "box"). No clamping, denoising, adaptive sampling or light
threshold; caustics on; 128 bounces of every kind. With --bsdf-only, emitters are not sampled as
lights (their materials' Multiple Importance off): Cycles' BSDF-only estimator. For each (spp, seed) it writes PREFIX_SPP_SEED.pfm
(linear RGB) and one JSON line to PREFIX.jsonl with the render's CPU seconds (the process's user +
sys over the render call, all threads, Cycles' scene sync and BVH build included), its wall
seconds, and the seconds this script took to build the scene in Blender before (`import`).
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


def parse_obj(path):
    """Vertices, fan-triangulated faces in file order and each face's usemtl name (glint's rules)."""
    vertices, faces, names, current, libraries = [], [], [], None, []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "usemtl":
                current = parts[1] if len(parts) > 1 else None
            elif parts[0] == "mtllib":
                libraries += parts[1:]
            elif parts[0] == "f":
                idx = []
                for p in parts[1:]:
                    i = int(p.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(vertices) + i)
                for k in range(2, len(idx)):
                    faces.append((idx[0], idx[k - 1], idx[k]))
                    names.append(current)
    return vertices, faces, names, libraries


def parse_mtl(path):
    """Kd, Ke and illum per material: enough for the scenes the benchmark uses (all diffuse)."""
    materials, current = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "newmtl":
                current = materials.setdefault(parts[1], {"albedo": [0, 0, 0], "emission": [0, 0, 0]})
            elif parts[0] == "Kd":
                current["albedo"] = [float(x) for x in parts[1:4]]
            elif parts[0] == "Ke":
                current["emission"] = [float(x) for x in parts[1:4]]
            elif parts[0] == "illum" and parts[1] not in ("0", "1", "2"):
                sys.exit(f"cycles_scene.py: {path}: illum {parts[1]} is not handled here")
    return materials


def drop_twins(vertices, faces, names):
    """Faces without the exact duplicates of earlier ones. CornellBox-Original repeats a side face
    of each box where its bottom face should be (`f -12 -11 -10 -9`). glint renders such a pair
    as one face (a ray leaves a surface offset past its rounding error, so the twin is never hit);
    a ray Cycles spawns on one face hits the other at distance zero, and the face goes black."""
    seen, kept_faces, kept_names = set(), [], []
    for face, name in zip(faces, names):
        key = tuple(sorted(tuple(vertices[i]) for i in face))
        if key not in seen:
            seen.add(key)
            kept_faces.append(face)
            kept_names.append(name)
    return kept_faces, kept_names


def colour(value, default):
    if value is None:
        return list(default)
    return [float(value)] * 3 if isinstance(value, (int, float)) else [float(x) for x in value]


SMOOTH_ROUGHNESS = 0.0316  # glint handles roughness below this (α below 0.001) as smooth


def glint_material(obj_material, emission):
    """A glint material as a dict (type, albedo, ior, roughness, fresnel, emission), with glint's defaults."""
    m = dict(obj_material or {})
    kind = m.get("type", "diffuse")
    if kind not in ("diffuse", "mirror", "glass"):
        sys.exit(f"cycles_scene.py: {kind} has no Cycles 3.4 BSDF that is the same surface")
    roughness = float(m.get("roughness", 0))
    if kind == "glass" and (roughness >= SMOOTH_ROUGHNESS or m.get("fresnel") != "exact"):
        sys.exit("cycles_scene.py: only smooth glass with exact Fresnel is the same surface as Cycles' Glass BSDF")
    return {"type": kind, "albedo": colour(m.get("albedo"), [0.75] * 3 if kind == "diffuse" else [1] * 3),
            "ior": float(m.get("ior", 1.5)), "roughness": roughness, "emission": colour(emission, [0, 0, 0])}


def cycles_material(name, m, bsdf_only=False):
    mat = bpy.data.materials.new(name)
    mat.cycles.sample_as_light = not bsdf_only
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    if m["type"] == "diffuse":
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Roughness"].default_value = 0
    elif m["type"] == "mirror":
        bsdf = nodes.new("ShaderNodeBsdfGlossy")
        bsdf.distribution = "SHARP" if m["roughness"] < SMOOTH_ROUGHNESS else "GGX"
        bsdf.inputs["Roughness"].default_value = m["roughness"]
    else:
        bsdf = nodes.new("ShaderNodeBsdfGlass")
        bsdf.distribution = "SHARP"
        bsdf.inputs["IOR"].default_value = m["ior"]
    bsdf.inputs["Color"].default_value = (*m["albedo"], 1)
    shader = bsdf.outputs[0]
    if any(m["emission"]):
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = (*m["emission"], 1)
        emit.inputs["Strength"].default_value = 1.0
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(emit.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    links.new(shader, out.inputs["Surface"])
    return mat


def add_mesh(index, obj, folder, bsdf_only):
    if obj.get("type") != "mesh":
        sys.exit("cycles_scene.py: spheres are not built here (the benchmark leaves sphere scenes out)")
    scale = obj.get("scale", 1)
    scale = [scale] * 3 if isinstance(scale, (int, float)) else scale
    translate = obj.get("translate", [0, 0, 0])
    own = glint_material(obj.get("material"), obj.get("emission"))
    if "file" in obj:
        path = os.path.join(folder, obj["file"])
        vertices, faces, names, libraries = parse_obj(path)
        library = {}
        if "material" not in obj and "emission" not in obj:
            for lib in libraries:
                library.update(parse_mtl(os.path.join(os.path.dirname(path), lib)))
        if obj.get("materials"):
            sys.exit("cycles_scene.py: per-name material overrides are not handled here")
    else:
        vertices, faces = obj["vertices"], [tuple(t) for t in obj["indices"]]
        names, library = [None] * len(faces), {}
    faces, names = drop_twins(vertices, faces, names)
    placed = [to_blender([v[k] * scale[k] + translate[k] for k in range(3)]) for v in vertices]
    mesh = bpy.data.meshes.new(f"mesh{index}")
    mesh.from_pydata(placed, [], faces)
    slots = [None] + sorted(library)
    mesh.materials.append(cycles_material(f"m{index}", own, bsdf_only))
    for name in slots[1:]:
        m = library[name]
        mesh.materials.append(
            cycles_material(f"m{index}_{name}", glint_material({"albedo": m["albedo"]}, m["emission"]), bsdf_only))
    mesh.polygons.foreach_set("material_index", [slots.index(n) if n in library else 0 for n in names])
    mesh.update()
    bpy.context.scene.collection.objects.link(bpy.data.objects.new(f"object{index}", mesh))


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


def configure(scene, width, height):
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
    scene.world = bpy.data.worlds.new("black")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"


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
    configure(scene, a.width, a.height)
    for i, obj in enumerate(glint_scene.get("objects", [])):
        add_mesh(i, obj, os.path.dirname(os.path.abspath(a.scene)), a.bsdf_only)
    add_camera(glint_scene.get("camera", {}))
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
