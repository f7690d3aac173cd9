"""What the export refuses or warns of in the Blender scene before the glTF exporter
runs: values that are not finite (Blender stores a NaN that a driver or a script gives
a socket, and the glTF exporter fails on some with a traceback), a medium's boundary
that is not closed, image textures whose file is missing."""
import os
from collections import Counter

import bpy

from . import node_graph
from .export_checks import is_non_finite


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
        if hasattr(light, name) and any(is_non_finite(v) for v in _numbers(getattr(light, name))):
            return name
    return None


def rendered_nodes(owner):
    """The nodes of a material's or World's tree whose outputs reach the output Cycles
    uses, through links; none without nodes or an output."""
    output = node_graph.owner_output(owner)
    seen, todo = set(), [output]
    while todo:
        node = todo.pop()
        if node is None or node.name in seen:
            continue
        seen.add(node.name)
        for socket in node.inputs:
            todo.extend(link.from_node for link in node_graph.live_links(socket))
    return [owner.node_tree.nodes[name] for name in seen]


def non_finite_node_input(owner):
    """(node name, input name) of the first unlinked input of a rendered node of OWNER (a
    material or World) whose value is not a finite number, or None."""
    for node in rendered_nodes(owner):
        for socket in node.inputs:
            if not node_graph.is_fed(socket) and hasattr(socket, "default_value") and any(
                    is_non_finite(v) for v in _numbers(socket.default_value)):
                return node.name, socket.name
    return None


def open_boundary_edges(obj, material, depsgraph):
    """How many edges of OBJ's faces of MATERIAL, as the render evaluates the object,
    are not shared by exactly two of those faces: a medium's boundary must be closed.
    Vertices at the same position are one, as vkdiffrender's loader counts them, so a mesh
    split along its edges (an Edge Split modifier, a glTF import) still closes."""
    slots = {i for i, slot in enumerate(obj.material_slots) if slot.material == material}
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        coordinates = [0.0] * (3 * len(mesh.vertices))
        mesh.vertices.foreach_get("co", coordinates)
        position = list(zip(coordinates[0::3], coordinates[1::3], coordinates[2::3]))
        faces_at = Counter()
        for polygon in mesh.polygons:
            if polygon.material_index not in slots:
                continue
            corners = [position[v] for v in polygon.vertices]
            for a, b in zip(corners, corners[1:] + corners[:1]):
                if a != b:  # an edge of no length bounds nothing
                    faces_at[min(a, b), max(a, b)] += 1
    finally:
        evaluated.to_mesh_clear()
    return sum(1 for count in faces_at.values() if count != 2)


def missing_images(owner):
    """(image name, path) of the rendered Image Texture nodes of OWNER (a material or
    World) whose image is neither packed nor a file on disk: the glTF exporter leaves them
    out, where Cycles renders them magenta."""
    missing = []
    for node in rendered_nodes(owner):
        image = getattr(node, "image", None) if node.bl_idname == "ShaderNodeTexImage" else None
        if image is None or image.packed_file is not None or image.source != "FILE":
            continue
        path = bpy.path.abspath(image.filepath, library=image.library)
        if not os.path.isfile(path):
            missing.append((image.name, path))
    return missing
