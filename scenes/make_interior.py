#!/usr/bin/env python3
"""Writes interior.json: a closed room lit only through a door left ajar from a lit corridor.

Run from this folder: python3 make_interior.py > interior.json (no randomness: the same bytes
every time).

The room is 5 m wide (x, 0..5), 3 m high (y, 0..3) and 4 m deep (z, 0..4). Its far wall (z = 4)
is a partition 0.15 m thick with a doorway 0.9 m by 2.1 m; behind it is a small corridor, 2.6 m
high, whose ceiling carries the only light, an emissive panel. The door leaf, hinged at x = 4.1
(the left, seen from the room), opens into the room and stands ajar by DOOR_ANGLE: its free edge
is about 0.19 m from the frame, and all the light the room gets comes through that gap (and the
5 mm slits under and over the leaf), most of it after bouncing in the corridor first. Apart from
the fan of direct light the gap lets onto the floor, every surface the camera sees is lit by light
that bounced two or more times: a scene for path guiding, on which plain path tracing stays noisy.

Only triangle meshes (written inline) and only diffuse and emissive materials, so that
bench/peer/run_cycles.py renders it in Cycles too. Every wall runs MARGIN past the walls it meets,
into the dark outside, and the floor under them, so no seam between two surfaces is a slit that
light could pass; where a wall meets the door frame the two share the edge's vertices.

Licence: CC0 1.0 (public domain dedication, https://creativecommons.org/publicdomain/zero/1.0/).
Made for glint; nothing here comes from elsewhere (scenes/meshes/README.md).
"""
import json
import math

MARGIN = 0.05                         # how far walls, floors and ceilings run past each other
ROOM = (5.0, 3.0, 4.0)                # width (x), height (y), depth (z)
WALL = 0.15                           # thickness of the partition between room and corridor
DOOR_X = (3.2, 4.1)                   # the doorway in the far wall, the hinge at x = 4.1
DOOR_HEIGHT = 2.1
DOOR_ANGLE = math.radians(12)         # gap at the free edge 2 * 0.9 * sin(6°) = 0.188 m
LEAF_THICKNESS = 0.04
CORRIDOR_X = (1.9, 4.9)               # the corridor behind the far wall: x range, depth, height
CORRIDOR_DEPTH = 1.5
CORRIDOR_HEIGHT = 2.6
LIGHT = {"x": (3.05, 4.15), "z": (4.65, 5.35), "emission": [360, 330, 280]}

WALL_PAINT = [0.74, 0.71, 0.64]
CEILING_PAINT = [0.8, 0.8, 0.78]
FLOOR = [0.62, 0.52, 0.42]
DOOR_PAINT = [0.78, 0.78, 0.75]
WOOD = [0.55, 0.4, 0.28]
CABINET = [0.42, 0.5, 0.58]
BENCH = [0.6, 0.33, 0.27]
CARDBOARD = [0.62, 0.5, 0.34]


class Mesh:
    """Triangles of one material, vertices shared where quads and boxes share corners."""

    def __init__(self):
        self.vertices, self.indices, self.index = [], [], {}

    def vertex(self, p):
        key = tuple(round(c, 6) for c in p)
        if key not in self.index:
            self.index[key] = len(self.vertices)
            self.vertices.append(list(key))
        return self.index[key]

    def quad(self, a, b, c, d):
        i = [self.vertex(p) for p in (a, b, c, d)]
        self.indices += [[i[0], i[1], i[2]], [i[0], i[2], i[3]]]

    def rect(self, axis, at, u, v):
        """An axis-aligned rectangle on the plane coordinate[axis] = at, spanning u and v (ranges
        of the other two coordinates, in x, y, z order)."""
        def point(s, t):
            p = [0.0, 0.0, 0.0]
            others = [k for k in range(3) if k != axis]
            p[axis], p[others[0]], p[others[1]] = at, s, t
            return p
        self.quad(point(u[0], v[0]), point(u[1], v[0]), point(u[1], v[1]), point(u[0], v[1]))

    def box(self, origin, du, dv, dw):
        """The six faces of the box origin + [0,1]·du + [0,1]·dv + [0,1]·dw."""
        def p(a, b, c):
            return [origin[k] + a * du[k] + b * dv[k] + c * dw[k] for k in range(3)]
        corners = {(a, b, c): p(a, b, c) for a in (0, 1) for b in (0, 1) for c in (0, 1)}
        for axis in range(3):
            for side in (0, 1):
                face = [k for k in corners if k[axis] == side]
                face.sort(key=lambda k: math.atan2(k[(axis + 2) % 3] - 0.5, k[(axis + 1) % 3] - 0.5))
                self.quad(*(corners[k] for k in face))

    def aabb(self, lo, hi):
        self.box(lo, [hi[0] - lo[0], 0, 0], [0, hi[1] - lo[1], 0], [0, 0, hi[2] - lo[2]])


def wall_with_doorway(mesh, z, x_range, top):
    """The wall z = const from x_range, floor to `top` (both run MARGIN further), less the
    doorway: its pieces meet the frame's faces along the same edges."""
    (x0, x1), (d0, d1), m = x_range, DOOR_X, MARGIN
    for u in ((x0 - m, d0), (d1, x1 + m)):
        mesh.rect(2, z, u, (-m, DOOR_HEIGHT))
        mesh.rect(2, z, u, (DOOR_HEIGHT, top + m))
    mesh.rect(2, z, (d0, d1), (DOOR_HEIGHT, top + m))


def room(meshes):
    (w, h, d), m = ROOM, MARGIN
    back = d + WALL + CORRIDOR_DEPTH
    # One floor under the room, the doorway and the corridor.
    meshes["floor"].rect(1, 0, (-m, w + m), (-m, back + m))
    meshes["ceiling"].rect(1, h, (-m, w + m), (-m, d + m))
    walls = meshes["walls"]
    walls.rect(0, 0, (-m, h + m), (-m, d + m))
    walls.rect(0, w, (-m, h + m), (-m, d + m))
    walls.rect(2, 0, (-m, w + m), (-m, h + m))
    wall_with_doorway(walls, d, (0, w), h)
    # The doorway through the partition: two jambs and the head (the floor runs through).
    frame = meshes["door"]
    for x in DOOR_X:
        frame.rect(0, x, (-m, DOOR_HEIGHT), (d, d + WALL))
    frame.rect(1, DOOR_HEIGHT, DOOR_X, (d, d + WALL))


def corridor(meshes):
    (x0, x1), m, h = CORRIDOR_X, MARGIN, CORRIDOR_HEIGHT
    z0 = ROOM[2] + WALL
    z1 = z0 + CORRIDOR_DEPTH
    meshes["ceiling"].rect(1, h, (x0 - m, x1 + m), (z0 - m, z1 + m))
    walls = meshes["walls"]
    walls.rect(0, x0, (-m, h + m), (z0 - m, z1 + m))
    walls.rect(0, x1, (-m, h + m), (z0 - m, z1 + m))
    walls.rect(2, z1, (x0 - m, x1 + m), (-m, h + m))
    wall_with_doorway(walls, z0, CORRIDOR_X, h)
    light = meshes["light"]
    light.rect(1, h - 0.02, LIGHT["x"], LIGHT["z"])


def door_leaf(mesh):
    """The leaf, hinged at the doorway's right edge on the room's side and turned into the room
    by DOOR_ANGLE. It starts 2 cm behind the hinge line, inside the wall, so no crack opens at
    the hinge; it clears the floor by 5 mm and the head by 5 mm."""
    width = DOOR_X[1] - DOOR_X[0]
    c, s = math.cos(DOOR_ANGLE), math.sin(DOOR_ANGLE)
    along = [-c, 0, -s]                      # from the hinge towards the free edge
    inward = [s, 0, -c]                      # the leaf's thickness, into the room
    hinge = [DOOR_X[1], 0.005, ROOM[2]]
    start = [hinge[k] - 0.02 * along[k] for k in range(3)]
    mesh.box(start, [(width + 0.02) * a for a in along], [0, DOOR_HEIGHT - 0.01, 0],
             [LEAF_THICKNESS * a for a in inward])


def furniture(meshes):
    # A table: top and four legs.
    table, (cx, cz), (sx, sz), height, top = meshes["wood"], (2.0, 1.9), (1.5, 0.85), 0.75, 0.04
    table.aabb([cx - sx / 2, height - top, cz - sz / 2], [cx + sx / 2, height, cz + sz / 2])
    for ex in (-1, 1):
        for ez in (-1, 1):
            lx, lz = cx + ex * (sx / 2 - 0.1), cz + ez * (sz / 2 - 0.1)
            table.aabb([lx - 0.03, 0, lz - 0.03], [lx + 0.03, height - top, lz + 0.03])
    # A tall cabinet against the left wall, a low bench against the right wall.
    meshes["cabinet"].aabb([0, 0, 2.3], [0.45, 1.9, 3.5])
    meshes["bench"].aabb([4.55, 0, 0.9], [5, 0.45, 2.3])
    # Two boxes on the floor, the upper one turned.
    boxes = meshes["boxes"]
    boxes.aabb([4.25, 0, 3.3], [4.85, 0.45, 3.8])
    a = math.radians(25)
    c, s = math.cos(a), math.sin(a)
    boxes.box([4.35, 0.45, 3.37], [0.4 * c, 0, 0.4 * s], [0, 0.3, 0], [-0.35 * s, 0, 0.35 * c])


def main():
    meshes = {name: Mesh() for name in ("walls", "floor", "ceiling", "door", "wood", "cabinet", "bench",
                                        "boxes", "light")}
    room(meshes)
    corridor(meshes)
    door_leaf(meshes["door"])
    furniture(meshes)
    materials = {"walls": WALL_PAINT, "floor": FLOOR, "ceiling": CEILING_PAINT, "door": DOOR_PAINT,
                 "wood": WOOD, "cabinet": CABINET, "bench": BENCH, "boxes": CARDBOARD}
    objects = []
    for name, mesh in meshes.items():
        obj = {"type": "mesh", "material": {"albedo": materials.get(name, 0)}}
        if name == "light":
            obj["emission"] = LIGHT["emission"]
        obj["vertices"], obj["indices"] = mesh.vertices, mesh.indices
        objects.append(obj)
    triangles = sum(len(m.indices) for m in meshes.values())
    scene = {
        "description": "A closed room (5 m × 3 m × 4 m, %d triangles) lit only through a door left ajar: the "
                       "light panel is in the corridor behind it, so nearly all the room sees is light that "
                       "bounced two or more times, which plain path tracing finds by chance (a case for path "
                       "guiding). Made by make_interior.py; CC0." % triangles,
        "camera": {"position": [4.6, 1.7, 0.3], "look_at": [2.5, 0.85, 3.7], "fov": 60},
        "film": {"width": 512, "height": 384, "spp": 256},
        "objects": objects,
    }
    # One object to a line or two: the vertices and indices of a mesh on a line each.
    lines = ["{"]
    for key in ("description", "camera", "film"):
        lines.append("  %s: %s," % (json.dumps(key), json.dumps(scene[key], ensure_ascii=False)))
    lines.append('  "objects": [')
    for i, obj in enumerate(objects):
        head = {k: v for k, v in obj.items() if k not in ("vertices", "indices")}
        text = json.dumps(head)[:-1]
        lines.append("    %s,\n     \"vertices\": %s,\n     \"indices\": %s}%s" % (
            text, json.dumps(obj["vertices"]), json.dumps(obj["indices"]), "," if i + 1 < len(objects) else ""))
    lines += ["  ]", "}"]
    print("\n".join(lines))


if __name__ == "__main__":
    main()
