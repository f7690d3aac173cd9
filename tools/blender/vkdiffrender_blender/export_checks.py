"""What the export refuses because vkdiffrender would refuse the scene, or because
writing it would harm the user's files: numbers that are not finite (Blender stores a
NaN a driver or a script gives a socket, and json writes it as a bare NaN, which no
glTF reader parses), a medium's boundary that is not closed, and files in the export
folder that an export would replace without having written them."""
import filecmp
import json
import math
import os
from collections import Counter
from collections.abc import Mapping, Sequence
from urllib.parse import unquote

import bpy

from . import node_graph
from .gltf_json import EXTENSION


def _non_finite(value):
    return isinstance(value, float) and not math.isfinite(value)


def _numbers(value):
    """The numbers of a socket's or a property's value: a float, or a colour or vector."""
    if isinstance(value, (int, float)):
        return [value]
    try:
        return [v for v in value if isinstance(v, (int, float))]
    except TypeError:
        return []


def non_finite_light_value(light):
    """The name of the first property of a light (Blender's light data) that is not a
    finite number, or None. The glTF exporter fails on a NaN power with a traceback."""
    for name in ("energy", "color", "shadow_soft_size", "spot_size", "spot_blend", "angle", "size", "size_y"):
        if hasattr(light, name) and any(_non_finite(v) for v in _numbers(getattr(light, name))):
            return name
    return None


def reachable_nodes(tree, output):
    """The nodes whose outputs reach the node OUTPUT through links."""
    seen, todo = set(), [output]
    while todo:
        node = todo.pop()
        if node is None or node.name in seen:
            continue
        seen.add(node.name)
        for socket in node.inputs:
            todo.extend(link.from_node for link in socket.links)
    return [tree.nodes[name] for name in seen]


def non_finite_node_input(owner, kind):
    """(node name, input name) of the first unlinked input, of a node that reaches the
    output of OWNER's node tree (a material's, kind "OUTPUT_MATERIAL", or a World's,
    "OUTPUT_WORLD"), whose value is not a finite number; or None."""
    tree = owner.node_tree if owner is not None and owner.use_nodes else None
    output = node_graph.output_node(tree, kind) if tree is not None else None
    if output is None:
        return None
    for node in reachable_nodes(tree, output):
        for socket in node.inputs:
            if not socket.is_linked and hasattr(socket, "default_value") and any(
                    _non_finite(v) for v in _numbers(socket.default_value)):
                return node.name, socket.name
    return None


def open_boundary_edges(obj, material, depsgraph):
    """How many edges of OBJ's faces of MATERIAL, as the render evaluates the object,
    are not shared by exactly two of those faces: a medium's boundary must be closed."""
    slots = {i for i, slot in enumerate(obj.material_slots) if slot.material == material}
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        faces_at = Counter(key for polygon in mesh.polygons if polygon.material_index in slots
                           for key in polygon.edge_keys)
    finally:
        evaluated.to_mesh_clear()
    return sum(1 for count in faces_at.values() if count != 2)


def missing_images(owner, kind):
    """(image name, path) of the Image Texture nodes reaching the output of OWNER's node
    tree whose image is neither packed nor a file on disk: the glTF exporter leaves them
    out, where Cycles renders them magenta."""
    tree = owner.node_tree if owner is not None and owner.use_nodes else None
    output = node_graph.output_node(tree, kind) if tree is not None else None
    if output is None:
        return []
    missing = []
    for node in reachable_nodes(tree, output):
        image = getattr(node, "image", None) if node.bl_idname == "ShaderNodeTexImage" else None
        if image is None or image.packed_file is not None or image.source != "FILE":
            continue
        path = bpy.path.abspath(image.filepath, library=image.library)
        if not os.path.isfile(path):
            missing.append((image.name, path))
    return missing


def first_non_finite(value, path=""):
    """The JSON path of the first number in VALUE (a JSON document) that is not finite."""
    if _non_finite(value):
        return path
    if isinstance(value, Mapping):
        items = ((f"{path}.{key}" if path else key, item) for key, item in value.items())
    elif isinstance(value, Sequence) and not isinstance(value, str):
        items = ((f"{path}[{i}]", item) for i, item in enumerate(value))
    else:
        return None
    for item_path, item in items:
        found = first_non_finite(item, item_path)
        if found is not None:
            return found
    return None


def owner_of(doc, path):
    """' (name)' of the top-level entry (a material, a node, a light) that PATH lies in."""
    head = path.split(".", 1)[0]
    if "[" not in head:
        return ""
    array, index = head[:-1].split("[")
    entry = doc.get(array, [])[int(index)]
    name = entry.get("name") if isinstance(entry, Mapping) else None
    return f" ('{name}')" if name else ""


def previous_export_files(gltf_path):
    """The files a scene already at GLTF_PATH refers to (its buffers, images and grids):
    an export there may replace them, as it replaces the scene."""
    try:
        with open(gltf_path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return set()
    uris = [entry.get("uri") for key in ("buffers", "images") for entry in doc.get(key, [])
            if isinstance(entry, Mapping)]
    owners = [doc.get("extensions", {})] + [m.get("extensions", {}) for m in doc.get("materials", [])
                                            if isinstance(m, Mapping)]
    for extensions in owners:
        medium = extensions.get(EXTENSION, {}) if isinstance(extensions, Mapping) else {}
        for reference in medium.values() if isinstance(medium, Mapping) else []:
            if isinstance(reference, Mapping):
                uris.append(reference.get("uri"))
    return {os.path.normpath(unquote(uri)) for uri in uris if isinstance(uri, str) and not uri.startswith("data:")}


def files_it_would_replace(staging, directory, gltf_name):
    """The files of STAGING whose names are taken in DIRECTORY by a file that is neither
    the scene GLTF_NAME, nor one its previous export there refers to, nor the same bytes."""
    ours = previous_export_files(os.path.join(directory, gltf_name)) | {gltf_name}
    taken = []
    for name in sorted(os.listdir(staging)):
        existing = os.path.join(directory, name)
        if name in ours or not os.path.lexists(existing):
            continue
        if os.path.isfile(existing) and not os.path.islink(existing) and filecmp.cmp(
                existing, os.path.join(staging, name), shallow=False):
            continue
        taken.append(name)
    return taken
