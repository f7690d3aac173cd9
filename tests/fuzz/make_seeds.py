#!/usr/bin/env python3
"""Writes the fuzzers' seed inputs into corpus/scene and corpus/image: small valid files
that reach the loaders' features (textures, media, GLB chunks, strips and fans,
normalized texture coordinates, 16-bit and grey images, EXR channel layouts). The
malformed-input corpus (tests/cli/data/malformed) seeds the fuzzers as well.
"""
import struct
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # keep __pycache__ out of the source tree
sys.path.insert(0, str(HERE.parent / "cli" / "data" / "malformed"))
import make_corpus as corpus  # noqa: E402  (the shared file builders)


def png_grey_alpha_16(width, height):
    rows = b"".join(b"\0" + b"\x80\x00\xff\xff" * width for _ in range(height))
    ihdr = struct.pack(">IIBBBBB", width, height, 16, 4, 0, 0, 0)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", corpus.zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", corpus.zlib.compress(rows)) +
            chunk(b"IEND", b""))


def textured(document, image):
    document["materials"][0]["pbrMetallicRoughness"] = {
        "baseColorFactor": [1, 0.5, 0.5, 1],
        "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2, 2]}}}}
    document["textures"] = [{"source": 0, "sampler": 0}]
    document["samplers"] = [{"wrapS": 33071, "wrapT": 10497}]
    document["images"] = [image]
    return document


def with_uvs(document):
    """Adds TEXCOORD_0 as normalized unsigned shorts in an interleaved, strided view."""
    uvs = b"".join(struct.pack("<2H2x", u, v) for u, v in [(0, 0), (65535, 0), (65535, 65535), (0, 65535)])
    buffer = corpus.quad_buffer() + uvs
    document["buffers"][0] = {"byteLength": len(buffer), "uri": corpus.data_uri(buffer)}
    document["bufferViews"].append({"buffer": 0, "byteOffset": 60, "byteLength": 24, "byteStride": 8})
    document["accessors"].append({"bufferView": 2, "componentType": 5123, "normalized": True, "count": 4,
                                  "type": "VEC2"})
    document["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2
    return document


def main():
    scenes, images = HERE / "corpus" / "scene", HERE / "corpus" / "image"
    scenes.mkdir(parents=True, exist_ok=True)
    images.mkdir(parents=True, exist_ok=True)
    small_png = corpus.png(2, 2)

    document = textured(with_uvs(corpus.valid_quad()), {"uri": corpus.data_uri(small_png, "image/png")})
    (scenes / "textured_quad.gltf").write_text(corpus.gltf(document))

    document = corpus.valid_quad()
    document["extensions"] = {"VKDR_participating_media": {"name": "fog", "sigma_a": 0.1, "sigma_s": [0.2, 0.3, 0.4],
                                                           "g": 0.3}}
    document["extensionsUsed"] = ["VKDR_participating_media", "KHR_materials_volume"]
    document["materials"].append({"name": "ink", "extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1},
        "KHR_materials_ior": {"ior": 1},
        "KHR_materials_volume": {"attenuationColor": [0.5, 0.6, 0.7], "attenuationDistance": 2}}})
    document["materials"].append({"name": "smoke", "extensions": {
        "VKDR_participating_media": {"sigma_s": 1, "g": -0.2}}})
    document["meshes"].append({"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 1, "mode": 5},
                                              {"attributes": {"POSITION": 0}, "material": 2, "mode": 6}]})
    document["nodes"].append({"mesh": 1, "scale": [1, 1, -1], "rotation": [0, 0.7071, 0, 0.7071]})
    document["scenes"][0]["nodes"].append(2)
    (scenes / "media_strips_fans.gltf").write_text(corpus.gltf(document))

    # A GLB whose texture lives in a buffer view of the binary chunk.
    binary = corpus.quad_buffer()
    binary += b"\0" * (-len(binary) % 4)
    image_offset = len(binary)
    binary += small_png
    document = textured(corpus.valid_quad(), {"bufferView": 2, "mimeType": "image/png"})
    document["bufferViews"].append({"buffer": 0, "byteOffset": image_offset, "byteLength": len(small_png)})
    document["buffers"][0]["byteLength"] = len(binary)
    (scenes / "textured_quad.glb").write_bytes(corpus.glb(document, binary))

    (images / "rgb8.png").write_bytes(small_png)
    (images / "grey_alpha16.png").write_bytes(png_grey_alpha_16(3, 2))
    (images / "rgb_float.exr").write_bytes(corpus.exr(3, 2))
    (images / "grey_float.exr").write_bytes(corpus.exr(2, 3, channels="Y"))
    (images / "rgba_float.exr").write_bytes(corpus.exr(2, 2, channels="ABGR"))


if __name__ == "__main__":
    main()
