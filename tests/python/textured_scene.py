"""A copy of scenes/cornell_fog.gltf whose back wall carries a 4 x 4 base colour texture
(material "poster"), for the tests of texel gradients; and one whose left wall also
carries it, with a material of its own ("poster2")."""
import base64
import json
import struct

import numpy as np
import vkdiffrender

from conftest import SCENES

TEXTURE_SIDE = 4


def write_textured_fog_scene(directory):
    gltf = json.loads((SCENES / "cornell_fog.gltf").read_text())
    back_wall = next(mesh for mesh in gltf["meshes"] if mesh["name"] == "back_wall")
    uvs = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    gltf["buffers"].append({"byteLength": len(uvs),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(uvs).decode()})
    gltf["bufferViews"].append({"buffer": len(gltf["buffers"]) - 1, "byteOffset": 0, "byteLength": len(uvs)})
    gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5126, "count": 4,
                              "type": "VEC2"})
    primitive = back_wall["primitives"][0]
    primitive["attributes"]["TEXCOORD_0"] = len(gltf["accessors"]) - 1
    primitive["material"] = len(gltf["materials"])
    gltf["materials"].append({"name": "poster", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                                         "metallicFactor": 0.0}})
    texels = np.random.default_rng(1).uniform(0.2, 0.9, size=(TEXTURE_SIDE, TEXTURE_SIDE, 3)).astype(np.float32)
    vkdiffrender.write_image(directory / "poster.png", texels)
    gltf["images"] = [{"uri": "poster.png"}]
    gltf["textures"] = [{"source": 0}]
    path = directory / "textured_fog.gltf"
    path.write_text(json.dumps(gltf))
    return path


def write_shared_texture_scene(directory):
    path = write_textured_fog_scene(directory)
    gltf = json.loads(path.read_text())
    meshes = {mesh["name"]: mesh for mesh in gltf["meshes"]}
    uvs = meshes["back_wall"]["primitives"][0]["attributes"]["TEXCOORD_0"]
    left_wall = meshes["left_wall"]["primitives"][0]
    assert gltf["accessors"][left_wall["attributes"]["POSITION"]]["count"] == 4
    left_wall["attributes"]["TEXCOORD_0"] = uvs
    left_wall["material"] = len(gltf["materials"])
    gltf["materials"].append({"name": "poster2", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                                          "metallicFactor": 0.0}})
    shared = directory / "shared_texture.gltf"
    shared.write_text(json.dumps(gltf))
    return shared
