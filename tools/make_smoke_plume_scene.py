#!/usr/bin/env python3
"""Writes scenes/experiments/smoke_plume.gltf: a smoke plume in open space for fitting grids.

The plume's medium fills the cube [-0.51, 0.51]^3 (a closed mesh), its density read from
smoke_plume.vdb beside the scene, which
`vkdr-make-plume --resolution 64 --seed 2 scenes/experiments/smoke_plume.vdb` writes
(the grid maps onto [-0.5, 0.5]^3). A square area light above lights it, a grey
background lies behind every view, and one camera looks at it from the front; the
experiment file scenes/experiments/smoke_reconstruction.json adds the cameras around it.
With --resolution N other than 64 the scene is smoke_plume_N.gltf and reads
smoke_plume_N.vdb (`vkdr-make-plume --resolution N --seed 2`), which is not shipped:
scenes/experiments/smoke_reconstruction_256.json fits such a grid on a GPU.

Usage: tools/make_smoke_plume_scene.py [OUTPUT_DIR] [--resolution N]
       (default: scenes/experiments/ next to tools/, N = 64)
"""
import argparse
import base64
import copy
import json
import pathlib

from make_cornell_scenes import append_mesh

HALF = 0.51  # the medium's box, just outside the grid's cube so no voxel touches a face
LIGHT_HEIGHT, LIGHT_HALF = 1.5, 0.5
MATERIALS = [
    {"name": "plume", "extensions": {"VKDR_participating_media": {
        "sigma_a": [0.25, 0.25, 0.25], "sigma_s": [10.0, 10.0, 10.0], "g": 0.2,
        "density": {"uri": "smoke_plume.vdb", "grid": "density"}}}},
    {"name": "light", "emissiveFactor": [1.0, 1.0, 1.0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8.0}},
     "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0}},
]


def cube_triangles(h):
    """12 triangles wound so that every face's normal points out of the cube."""
    corners = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    indices = []
    for a, b, c, d in faces:
        indices += [a, b, c, a, c, d]
    return corners, indices


def light_triangles():
    """A square at y = LIGHT_HEIGHT facing down."""
    s, y = LIGHT_HALF, LIGHT_HEIGHT
    return [(-s, y, -s), (s, y, -s), (s, y, s), (-s, y, s)], [0, 1, 2, 0, 2, 3]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output_dir", nargs="?", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parent.parent / "scenes" / "experiments")
    parser.add_argument("--resolution", type=int, default=64, help="the grid's voxels a side (names the files)")
    args = parser.parse_args()
    name = "smoke_plume" if args.resolution == 64 else f"smoke_plume_{args.resolution}"
    materials = copy.deepcopy(MATERIALS)
    materials[0]["extensions"]["VKDR_participating_media"]["density"]["uri"] = name + ".vdb"
    buffer = bytearray()
    gltf = {
        "asset": {"version": "2.0", "generator": "tools/make_smoke_plume_scene.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength", "VKDR_participating_media", "VKDR_background"],
        "extensions": {"VKDR_background": {"radiance": [0.4, 0.4, 0.4]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "plume_box", "mesh": 0}, {"name": "light", "mesh": 1},
                  {"name": "front", "camera": 0, "translation": [0.0, 0.0, 2.5]}],
        "cameras": [{"name": "front", "type": "perspective",
                     "perspective": {"yfov": 0.5, "aspectRatio": 1.0, "znear": 0.01}}],
        "materials": materials, "meshes": [], "accessors": [], "bufferViews": [], "buffers": [],
    }
    for material, (positions, indices) in enumerate([cube_triangles(HALF), light_triangles()]):
        append_mesh(gltf, buffer, gltf["nodes"][material]["name"], positions, indices, material)
    gltf["buffers"].append({"byteLength": len(buffer),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()})
    (args.output_dir / (name + ".gltf")).write_text(json.dumps(gltf, indent=1) + "\n")


if __name__ == "__main__":
    main()
