#!/usr/bin/env python3
"""Writes the malformed-input corpus next to this script, and cases.json, which says how
the command line must fail on each file (tests/cli/malformed_input_test.cpp).

Each file is a small valid input (valid_quad.gltf, a 4x4 EXR) with one thing broken.
Run it again after changing it; the files are committed so that the tests need no Python.
"""
import base64
import copy
import json
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
cases = []


def case(name, data, command, *fields, extra=""):
    """Writes `data` to `name`; the failure must name the file and every one of `fields`."""
    (HERE / name).write_bytes(data if isinstance(data, bytes) else data.encode())
    cases.append({"file": name, "command": command, "expect": list(fields), "extra": extra})


def quad_buffer():
    positions = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    return data + struct.pack("<6H", 0, 1, 2, 0, 2, 3)


def data_uri(data, mime="application/octet-stream"):
    return "data:" + mime + ";base64," + base64.b64encode(data).decode()


def valid_quad(buffer=None):
    """An emissive quad seen by a camera 3 units away, its buffer in a data URI."""
    buffer = quad_buffer() if buffer is None else buffer
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"name": "lamp", "emissiveFactor": [1, 1, 1]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
        "buffers": [{"byteLength": 60, "uri": data_uri(buffer)}],
    }


def gltf(document):
    large = len(document.get("nodes", [])) > 100
    return json.dumps(document, separators=(",", ":")) if large else json.dumps(document, indent=1)


def changed(edit):
    document = valid_quad()
    edit(document)
    return gltf(document)


def glb(document, binary):
    """A GLB container: the JSON chunk, then the binary chunk that buffer 0 refers to."""
    document = copy.deepcopy(document)
    del document["buffers"][0]["uri"]
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def png_header(width, height):
    """A PNG signature and IHDR chunk declaring an 8-bit RGB image, without pixels."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    chunk = struct.pack(">I", len(ihdr)) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    return b"\x89PNG\r\n\x1a\n" + chunk


def png(width, height):
    rows = b"".join(b"\0" + b"\x80" * (3 * width) for _ in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return png_header(width, height) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def exr(width, height, channels="BGR", data_window=None):
    """An uncompressed scanline OpenEXR file of float channels, every value 0.5."""
    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    channel_list = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in channels) + b"\0"
    window = struct.pack("<4i", *(data_window or (0, 0, width - 1, height - 1)))
    header = (attribute("channels", "chlist", channel_list) + attribute("compression", "compression", b"\0") +
              attribute("dataWindow", "box2i", window) + attribute("displayWindow", "box2i", window) +
              attribute("lineOrder", "lineOrder", b"\0") + attribute("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) +
              attribute("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    start = 8 + len(header) + 8 * height
    line = struct.pack("<f", 0.5) * (width * len(channels))
    line_block = 8 + len(line)
    offsets = b"".join(struct.pack("<Q", start + y * line_block) for y in range(height))
    lines = b"".join(struct.pack("<ii", y, len(line)) + line for y in range(height))
    return struct.pack("<ii", 20000630, 2) + header + offsets + lines


def set_path(document, path, value):
    *parents, last = path
    for key in parents:
        document = document[key]
    document[last] = value


def main():
    (HERE / "valid_quad.gltf").write_text(gltf(valid_quad()))
    (HERE / "valid_quad.glb").write_bytes(glb(valid_quad(), quad_buffer()))
    (HERE / "valid_target.exr").write_bytes(exr(4, 4))

    # Truncated files.
    text = gltf(valid_quad())
    case("truncated.gltf", text[: len(text) // 2], "render", "cannot parse glTF")
    binary = glb(valid_quad(), quad_buffer())
    case("truncated_header.glb", binary[:10], "render", "cannot parse glTF")
    case("truncated_binary_chunk.glb", binary[:-20], "render", "cannot parse glTF")
    case("huge_chunk_length.glb", binary[:12] + struct.pack("<I", 0x7FFFFFF0) + binary[16:], "render",
         "cannot parse glTF")

    # Counts and indices out of range, buffers shorter than their accessors.
    for name, path, value, fields in [
        ("accessor_index_out_of_range.gltf", ["meshes", 0, "primitives", 0, "attributes", "POSITION"], 9,
         ["attributes.POSITION", "accessor 9 out of range"]),
        ("buffer_view_out_of_range.gltf", ["accessors", 0, "bufferView"], 7, ["accessors[0].bufferView"]),
        ("buffer_out_of_range.gltf", ["bufferViews", 0, "buffer"], 3, ["bufferViews[0].buffer"]),
        ("material_out_of_range.gltf", ["meshes", 0, "primitives", 0, "material"], 5, ["primitives[0].material"]),
        ("mesh_out_of_range.gltf", ["nodes", 0, "mesh"], 40000, ["nodes[0].mesh"]),
        ("scene_node_out_of_range.gltf", ["scenes", 0, "nodes"], [0, 99999], ["scenes[0].nodes[1]"]),
        ("accessor_longer_than_view.gltf", ["accessors", 0, "count"], 40, ["accessors[0]", "40 elements"]),
        ("accessor_count_huge.gltf", ["accessors", 0, "count"], 2 ** 62, ["accessors[0]", "more than 2^64"]),
        # 12 * count wraps around to 8 in 64 bits: a sum that is not checked for overflow passes.
        ("accessor_count_wraps.gltf", ["accessors", 0, "count"], 1537228672809129302,
         ["accessors[0]", "more than 2^64"]),
        ("accessor_offset_huge.gltf", ["accessors", 1, "byteOffset"], 2 ** 40, ["accessors[1]"]),
        ("view_beyond_buffer.gltf", ["bufferViews", 1, "byteOffset"], 2 ** 33, ["bufferViews[1]", "exceeds"]),
        ("buffer_shorter_than_declared.gltf", ["buffers", 0, "byteLength"], 600,
         ["buffers[0].byteLength", "but the data URI holds"]),
        ("no_position.gltf", ["meshes", 0, "primitives", 0, "attributes"], {}, ["attributes", "no POSITION"]),
        # Parameters that are not finite numbers.
        ("sigma_a_infinite_as_float.gltf", ["extensions"],
         {"VKDR_participating_media": {"name": "fog", "sigma_a": [0.1, 1e39, 0.1]}},
         ["VKDR_participating_media.sigma_a[1]", "must be finite"]),
        ("sigma_s_nan_string.gltf", ["extensions"], {"VKDR_participating_media": {"name": "fog", "sigma_s": "NaN"}},
         ["VKDR_participating_media.sigma_s", "expected a number"]),
        ("g_out_of_range.gltf", ["extensions"], {"VKDR_participating_media": {"name": "fog", "g": -3}},
         ["VKDR_participating_media.g"]),
        ("emissive_infinite.gltf", ["materials", 0, "emissiveFactor"], [1, 1e39, 1], ["materials[0].emissiveFactor"]),
        # Cameras.
        ("camera_yfov_zero.gltf", ["cameras", 0, "perspective", "yfov"], 0, ["cameras[0].perspective.yfov"]),
        ("camera_yfov_negative.gltf", ["cameras", 0, "perspective", "yfov"], -0.5, ["cameras[0].perspective.yfov"]),
        ("camera_aspect_huge.gltf", ["cameras", 0, "perspective", "aspectRatio"], 1e30,
         ["cameras[0].perspective.aspectRatio"]),
        ("camera_zero_scale.gltf", ["nodes", 1, "scale"], [0, 0, 0], ["nodes[1]", "degenerate"]),
        # Data URIs.
        ("data_uri_bad_base64.gltf", ["buffers", 0, "uri"], "data:application/octet-stream;base64,!!!!%%%%",
         ["buffers[0].uri", "has '!' at character 1"]),
        ("data_uri_without_comma.gltf", ["buffers", 0, "uri"], "data:application/octet-stream;base64",
         ["buffers[0].uri", "a data URI holds its data after a ','"]),
        ("data_uri_too_short.gltf", ["buffers", 0, "uri"], data_uri(quad_buffer()[:30]),
         ["buffers[0].byteLength", "but the data URI holds 30 bytes"]),
        ("data_uri_unknown_type.gltf", ["buffers", 0, "uri"], data_uri(quad_buffer(), "text/html"),
         ["buffers[0].uri", "a data URI is read in base64", "this one starts 'data:text/html;base64'"]),
    ]:
        document = valid_quad()
        set_path(document, path, value)
        case(name, gltf(document), "render", *fields)

    case("g_number_overflow.gltf", changed(lambda d: d.update(extensions={
        "VKDR_participating_media": {"name": "fog", "g": 0.12345}})).replace("0.12345", "1e999"),
         "render", "cannot parse glTF")

    # Textures: undecodable, and declaring an enormous size.
    def textured(image_uri):
        def edit(document):
            document["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 0}}
            document["textures"] = [{"source": 0}]
            document["images"] = [{"uri": image_uri}]
        return changed(edit)
    case("texture_garbage.gltf", textured(data_uri(b"not an image at all", "image/png")), "render",
         "images[0] cannot be decoded")
    case("texture_huge.gltf", textured(data_uri(png_header(60000, 60000), "image/png")), "render",
         "images[0] cannot be decoded", "60000 x 60000 pixels is too large")
    case("texture_large_truncated.gltf", textured(data_uri(png_header(16384, 16384), "image/png")), "render",
         "images[0]", "16384 x 16384")

    # Node hierarchies: cycles, absurd depth, exponential instancing.
    def hierarchy(nodes, roots):
        def edit(document):
            document["nodes"] = nodes + [{"camera": 0, "translation": [0, 0, 3]}]
            document["scenes"] = [{"nodes": roots + [len(nodes)]}]
        return changed(edit)
    case("node_cycle.gltf", hierarchy([{"mesh": 0, "children": [1]}, {"children": [0]}], [0]), "render",
         "cycle in the node hierarchy")
    case("node_cycle_unreachable.gltf", hierarchy([{"mesh": 0}, {"children": [2]}, {"children": [1]}], [0]), "render",
         "nodes[2].children[0]", "cycle in the node hierarchy")
    chain = [{"children": [i + 1]} for i in range(1100)] + [{"mesh": 0}]
    case("nodes_nested_too_deep.gltf", hierarchy(chain, [0]), "render", "nested more than 1000")
    doubling = [{"children": [i + 1, i + 1]} for i in range(40)] + [{"mesh": 0}]
    case("nodes_instanced_exponentially.gltf", hierarchy(doubling, [0]), "render", "instances more than")

    # External files: a scene reads only regular files in its own directory tree.
    for name, uri, fields in [
        ("buffer_outside_directory.gltf", "../outside.bin", ["'../outside.bin'", "outside the scene's directory"]),
        ("buffer_etc_passwd.gltf", "../" * 12 + "etc/passwd", ["outside the scene's directory"]),
        ("buffer_percent_encoded_parent.gltf", "..%2F..%2F..%2F..%2Fetc%2Fpasswd",
         ["decoded '../../../../etc/passwd'", "outside the scene's directory"]),
        ("buffer_absolute_path.gltf", "/etc/passwd", ["'/etc/passwd' is an absolute path", "--allow-outside-files"]),
        ("buffer_file_uri.gltf", "file:///etc/passwd", ["'file:///etc/passwd'", "scheme (file:)"]),
        ("buffer_missing_file.gltf", "absent.bin", ["'absent.bin' names no file"]),
        ("buffer_is_a_directory.gltf", ".", ["'.' is a directory"]),
    ]:
        case(name, changed(lambda d: d["buffers"][0].update(uri=uri)), "render", "buffers[0].uri", *fields)
    case("image_outside_directory.gltf", textured("../../../../etc/hostname.png"), "render", "images[0].uri",
         "outside the scene's directory")

    # Experiment files (optimize --experiment): integers beyond their range, rates that are
    # not finite and positive, values beyond float range.
    def experiment(**changes):
        document = {"scene": "../../../../scenes/cornell_fog.gltf", "width": 8, "height": 8, "iterations": 2,
                    "start": {"media/fog/g": 0.2}, "true": {"media/fog/g": 0.1}}
        document.update(changes)
        return json.dumps(document, indent=1)
    for name, changes, fields in [
        ("experiment_iterations_beyond_32_bits.json", {"iterations": 4294967296}, ["iterations", "[1, 1000000]"]),
        ("experiment_seed_beyond_32_bits.json", {"seed": 4294967296}, ["seed", "[0, 4294967295]"]),
        ("experiment_spp_negative.json", {"spp": -3}, ["spp", "[1, 1048576]"]),
        ("experiment_width_beyond_64_bits.json", {"width": 10 ** 30}, ["width", "[1, 16384]"]),
        ("experiment_learning_rate_zero.json", {"learning_rate": 0}, ["learning_rate", "finite number > 0"]),
        ("experiment_learning_rate_negative.json", {"learning_rate": -0.5}, ["learning_rate", "finite number > 0"]),
        ("experiment_adam_epsilon_zero.json", {"adam_epsilon": 0.0}, ["adam_epsilon", "finite number > 0"]),
        ("experiment_adam_epsilon_with_sgd.json", {"adam_epsilon": 1e-6, "optimizer": "sgd"},
         ["adam_epsilon", "only Adam has an epsilon"]),
        ("experiment_learning_rates_negative.json", {"learning_rates": {"media/fog/g": -1}},
         ["learning_rates.media/fog/g", "finite number > 0"]),
        ("experiment_true_beyond_float.json", {"true": {"media/fog/g": 1e39}}, ["true.media/fog/g", "float range"]),
        ("experiment_scene_is_a_directory.json", {"scene": "."}, ["scene", "is a directory"]),
    ]:
        case(name, experiment(**changes), "experiment", *fields)
    case("experiment_adam_epsilon_then_sgd.json", experiment(adam_epsilon=1e-6), "experiment", "adam_epsilon",
         "only Adam has an epsilon, and --optimizer sgd is given", extra="--optimizer sgd")
    # Adam's own default, stated in the file, is still an epsilon SGD does not have.
    case("experiment_default_adam_epsilon_then_sgd.json", experiment(adam_epsilon=1e-8), "experiment",
         "adam_epsilon", "only Adam has an epsilon, and --optimizer sgd is given", extra="--optimizer sgd")

    # Targets for grad (the scene is scenes/cornell_fog.gltf).
    case("target_wrong_size.exr", exr(4, 4), "grad", "4x4", extra="--width 8 --height 8")
    case("target_depth_only.exr", exr(4, 4, channels="Z"), "grad", "needs channels R, G and B")
    case("target_truncated.exr", exr(4, 4)[:300], "grad", "cannot read EXR")
    case("target_huge.exr", exr(4, 4, data_window=(0, 0, 99999, 99999)), "grad", "exceeds the maximum")
    case("target_too_wide.png", png(20000, 1), "grad", "20000x1", "16384")
    case("target_truncated.png", png(8, 8)[:40], "grad", "cannot read image")
    idat_too_long = bytearray(png(8, 8))
    idat_too_long[33:37] = struct.pack(">I", 0x7FFFFFF0)  # the IDAT chunk's length, after IHDR
    case("target_chunk_longer_than_file.png", bytes(idat_too_long), "grad", "IDAT", "declares 2147483632 bytes")
    table = bytes([0x00, 150, 150] + [0] * 14) + bytes(300)  # DC table 0 with 300 codes; 256 is the most
    case("target_huffman_table_too_large.jpg", b"\xff\xd8\xff\xc4" + struct.pack(">H", 2 + len(table)) + table,
         "grad", "declares 300 codes")
    case("target_empty.png", b"", "grad", "empty")
    case("target_garbage.jpg", b"\xff\xd8\xff\xe0 not really a JPEG", "grad", "cannot read image")
    case("target_unknown_format.bmp", b"BM", "grad", "unknown extension")

    (HERE / "cases.json").write_text(json.dumps(cases, indent=1) + "\n")


if __name__ == "__main__":
    main()
