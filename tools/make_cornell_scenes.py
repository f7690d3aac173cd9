#!/usr/bin/env python3
"""Writes scenes/cornell_box.gltf, cornell_fog.gltf, cornell_smoke.gltf, cornell_plume.gltf,
cornell_fire.gltf and cornell_softbox.gltf.

The geometry is the published Cornell box data (https://www.graphics.cornell.edu/online/box/data.html),
kept in millimetres in the buffer and scaled by 0.01 by the root node, so the box is
about 5.55 units across (a unit is 100 mm) and media coefficients are per unit. Each quad is wound so
that its front face points into the room (walls), out of the block (blocks), or down
(the light); the script checks this rather than trusting the data's vertex order.

cornell_plume.gltf reads the density grid cornell_plume.vdb beside it, which
`vkdr-make-plume --resolution 64 --seed 1 scenes/cornell_plume.vdb` writes;
cornell_fire.gltf the same smoke burning at its base, its emission following the flame
grid cornell_fire_flame.vdb (`vkdr-make-plume --resolution 64 --seed 1 --flame
scenes/cornell_fire_flame.vdb`).

cornell_softbox.gltf hangs a light panel 300 mm square (a softbox) 120 mm above the tall
block in place of the ceiling light: the scene where sampling an emitter by its solid
angle rather than its area matters.

Usage: tools/make_cornell_scenes.py [OUTPUT_DIR]   (default: scenes/ next to tools/)
"""
import base64
import json
import math
import pathlib
import struct
import sys

ROOM_CENTRE = (278.0, 274.4, 279.6)

# (name, material, quads, facing) where facing is "in" (towards ROOM_CENTRE),
# "out" (away from the quads' own centre) or a fixed normal.
WALLS = [
    ("floor", "white", [[(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]], "in"),
    ("ceiling", "white", [[(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]], "in"),
    ("back_wall", "white", [[(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]], "in"),
    ("right_wall", "green", [[(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]], "in"),
    ("left_wall", "red", [[(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]], "in"),
]
# Just below the ceiling (548.8), so the light and the ceiling are not coplanar.
LIGHT = ("light", "light", [[(343, 548.7, 227), (343, 548.7, 332), (213, 548.7, 332), (213, 548.7, 227)]], (0, -1, 0))
# A large panel low in the room, facing down, about as powerful as LIGHT.
SOFTBOX = ("softbox", "softbox", [[(428, 450, 130), (428, 450, 430), (128, 450, 430), (128, 450, 130)]], (0, -1, 0))
SHORT_BLOCK = ("short_block", "white", [
    [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
    [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
    [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
    [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
    [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)],
], "out")
TALL_BLOCK = ("tall_block", "white", [
    [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
    [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
    [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
    [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
    [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)],
], "out")


def box_quads(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [
        [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
        [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
        [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
        [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
    ]


# Where the tall block stood, 150 x 250 x 150 mm, lifted 1 mm off the floor so that
# the medium boundary and the floor are not coplanar; clear of the short block (x < 290).
SMOKE_BOX = ("smoke_box", "smoke", box_quads((293.5, 1, 276.5), (443.5, 251, 426.5)), "out")

# Where the tall block stood, taller: the smoke plume's medium, 150 x 400 x 150 mm.
PLUME_LO, PLUME_HI = (293.5, 1, 276.5), (443.5, 401, 426.5)
PLUME_BOX = ("plume_box", "plume", box_quads(PLUME_LO, PLUME_HI), "out")
FIRE_BOX = ("fire_box", "fire", box_quads(PLUME_LO, PLUME_HI), "out")

MATERIALS = {
    "white": {"pbrMetallicRoughness": {"baseColorFactor": [0.725, 0.71, 0.68, 1.0], "metallicFactor": 0.0}},
    "red": {"pbrMetallicRoughness": {"baseColorFactor": [0.63, 0.065, 0.05, 1.0], "metallicFactor": 0.0}},
    "green": {"pbrMetallicRoughness": {"baseColorFactor": [0.14, 0.45, 0.091, 1.0], "metallicFactor": 0.0}},
    "light": {
        "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.78, 0.78, 1.0], "metallicFactor": 0.0},
        "emissiveFactor": [1.0, 0.7059, 0.2353],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 17.0}},
    },
    "softbox": {
        "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.78, 0.78, 1.0], "metallicFactor": 0.0},
        "emissiveFactor": [1.0, 0.7059, 0.2353],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.6}},
    },
    "smoke": {"extensions": {"VKDR_participating_media": {
        "sigma_a": [0.05, 0.05, 0.05], "sigma_s": [4.0, 4.0, 4.0], "g": 0.3}}},
    # Per unit density: the plume is thin, its densities mostly far below their peak of 0.9.
    "plume": {"extensions": {"VKDR_participating_media": {
        "sigma_a": [2.0, 2.0, 2.0], "sigma_s": [150.0, 150.0, 150.0], "g": 0.3,
        "density": {"uri": "cornell_plume.vdb", "grid": "density"}}}},
    # The same smoke, thinner, burning at its base: the emission (radiance per unit at a
    # flame strength of 1) follows the flame grid.
    "fire": {"extensions": {"VKDR_participating_media": {
        "sigma_a": [1.0, 1.0, 1.0], "sigma_s": [60.0, 60.0, 60.0], "g": 0.3, "emission": [40.0, 12.0, 2.5],
        "density": {"uri": "cornell_plume.vdb", "grid": "density"},
        "emissionGrid": {"uri": "cornell_fire_flame.vdb", "grid": "flame"}}}},
}
# The plume grid's cube [-0.5, 0.5]^3 placed on the plume's box, in scene units (the
# root node scales millimetres by 0.01).
PLUME_PLACEMENT = {
    "name": "plume_placement",
    "translation": [round((lo + hi) / 200, 6) for lo, hi in zip(PLUME_LO, PLUME_HI)],
    "scale": [round((hi - lo) / 100, 6) for lo, hi in zip(PLUME_LO, PLUME_HI)],
}
FOG = {"name": "fog", "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.04, 0.04, 0.04], "g": 0.0}


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def centre(points):
    return tuple(sum(c) / len(points) for c in zip(*points))


def oriented(quad, facing, object_centre):
    normal = cross(sub(quad[1], quad[0]), sub(quad[2], quad[0]))
    if facing == "in":
        wanted = sub(ROOM_CENTRE, centre(quad))
    elif facing == "out":
        wanted = sub(centre(quad), object_centre)
    else:
        wanted = facing
    return quad if dot(normal, wanted) > 0 else quad[::-1]


def append_mesh(gltf, buffer, name, positions, indices, material):
    """Appends a triangle mesh's positions and 16-bit indices to BUFFER (buffer 0) and
    its buffer views, accessors (bounds as the floats stored) and mesh to GLTF."""
    position_offset = len(buffer)
    for p in positions:
        buffer += struct.pack("<3f", *p)
    index_offset = len(buffer)
    buffer += struct.pack(f"<{len(indices)}H", *indices)
    while len(buffer) % 4:
        buffer += b"\0"
    views = gltf["bufferViews"]
    views.append({"buffer": 0, "byteOffset": position_offset, "byteLength": index_offset - position_offset, "target": 34962})
    views.append({"buffer": 0, "byteOffset": index_offset, "byteLength": 2 * len(indices), "target": 34963})
    stored = [struct.unpack("<3f", struct.pack("<3f", *p)) for p in positions]
    gltf["accessors"].append({"bufferView": len(views) - 2, "componentType": 5126, "count": len(positions), "type": "VEC3",
                              "min": [min(c) for c in zip(*stored)], "max": [max(c) for c in zip(*stored)]})
    gltf["accessors"].append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
    gltf["meshes"].append({"name": name, "primitives": [{
        "attributes": {"POSITION": len(gltf["accessors"]) - 2}, "indices": len(gltf["accessors"]) - 1,
        "material": material}]})


def build(meshes, root_extensions):
    buffer = bytearray()
    gltf = {
        "asset": {"version": "2.0", "generator": "tools/make_cornell_scenes.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "cornell_box", "scale": [0.01, 0.01, 0.01], "children": []},
            # glTF cameras look down -Z: a half turn about y makes this one look down +Z.
            {"name": "camera", "camera": 0, "translation": [2.78, 2.73, -8.0], "rotation": [0.0, 1.0, 0.0, 0.0]},
        ],
        "cameras": [{"name": "camera", "type": "perspective", "perspective": {
            # 35 mm focal length, 25 mm film: the published 39.3 degree field of view.
            "yfov": round(2 * math.atan(12.5 / 35.0), 6), "aspectRatio": 1.0, "znear": 0.01}}],
        "materials": [],
        "meshes": [],
        "accessors": [],
        "bufferViews": [],
        "buffers": [],
    }
    material_index = {}
    for name, material, quads, facing in meshes:
        if material not in material_index:
            material_index[material] = len(gltf["materials"])
            gltf["materials"].append({"name": material, **MATERIALS[material]})
        object_centre = centre([p for quad in quads for p in quad])
        positions, indices = [], []
        for quad in quads:
            first = len(positions)
            positions += oriented(quad, facing, object_centre)
            indices += [first, first + 1, first + 2, first, first + 2, first + 3]
        append_mesh(gltf, buffer, name, positions, indices, material_index[material])
        gltf["nodes"][0]["children"].append(len(gltf["nodes"]))
        gltf["nodes"].append({"name": name, "mesh": len(gltf["meshes"]) - 1})
    gltf["buffers"].append({"byteLength": len(buffer),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()})
    if any("VKDR_participating_media" in m.get("extensions", {}) for m in gltf["materials"]) or root_extensions:
        gltf["extensionsUsed"].append("VKDR_participating_media")
    if root_extensions:
        gltf["extensions"] = root_extensions
    return gltf


def with_plume_placement(gltf):
    """Adds the node that places the plume's grid and points the plume's density at it."""
    node = len(gltf["nodes"])
    gltf["nodes"].append(PLUME_PLACEMENT)
    gltf["scenes"][0]["nodes"].append(node)
    for material in gltf["materials"]:
        medium = material.get("extensions", {}).get("VKDR_participating_media", {})
        for grid in ("density", "emissionGrid"):
            if grid in medium:
                medium[grid]["node"] = node
    return gltf


def to_text(value, indent=0):
    """JSON with objects one member per line and arrays of numbers on one line."""
    pad = "  " * indent
    if isinstance(value, dict):
        members = [f'{pad}  {json.dumps(k)}: {to_text(v, indent + 1)}' for k, v in value.items()]
        return "{\n" + ",\n".join(members) + "\n" + pad + "}"
    if isinstance(value, list) and any(isinstance(v, (dict, list)) for v in value):
        return "[\n" + ",\n".join(pad + "  " + to_text(v, indent + 1) for v in value) + "\n" + pad + "]"
    if isinstance(value, list):
        return "[" + ", ".join(to_text(v) for v in value) + "]"
    if isinstance(value, float):
        return repr(float(f"{value:.9g}"))
    return json.dumps(value)


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent / "scenes"
    box = WALLS + [LIGHT, SHORT_BLOCK, TALL_BLOCK]
    scenes = {
        "cornell_box.gltf": build(box, None),
        "cornell_fog.gltf": build(box, {"VKDR_participating_media": FOG}),
        "cornell_smoke.gltf": build(WALLS + [LIGHT, SHORT_BLOCK, SMOKE_BOX], None),
        "cornell_plume.gltf": with_plume_placement(build(WALLS + [LIGHT, SHORT_BLOCK, PLUME_BOX], None)),
        "cornell_fire.gltf": with_plume_placement(build(WALLS + [LIGHT, SHORT_BLOCK, FIRE_BOX], None)),
        "cornell_softbox.gltf": build(WALLS + [SOFTBOX, SHORT_BLOCK, TALL_BLOCK], None),
    }
    for name, gltf in scenes.items():
        (out / name).write_text(to_text(gltf) + "\n")


if __name__ == "__main__":
    main()
