"""Colour attributes that a material reads as its surface colour, exported as glTF's
COLOR_0, which multiplies the base colour factor. Blender's glTF exporter writes the
render colour attribute of every mesh as COLOR_0 when asked to, whether its material reads
it or not, where Cycles uses an attribute only where a node reads it: the export asks for
them only when some material reads one, and takes COLOR_0 off the other materials'
primitives."""
import contextlib

import bpy
import numpy as np

from . import node_graph

# The input of each exported surface shader that COLOR_0 multiplies.
COLOUR_INPUTS = {"ShaderNodeBsdfPrincipled": "Base Color", "ShaderNodeBsdfDiffuse": "Color"}


def attribute_read(material):
    """The name of the colour attribute whose Color output feeds MATERIAL's surface colour
    directly (through reroutes), "" for a Color Attribute node left on the render colour
    attribute; None where none does (a muted node passes nothing, and an Attribute node
    without a name reads nothing)."""
    node = node_graph.surface_node(material)
    if node is None or node.bl_idname not in COLOUR_INPUTS:
        return None
    link = node_graph.source_link(node.inputs[COLOUR_INPUTS[node.bl_idname]])
    if link is None or link.from_socket.name != "Color" or link.from_node.mute:
        return None
    source = link.from_node
    if source.bl_idname == "ShaderNodeVertexColor":
        return source.layer_name
    if source.bl_idname == "ShaderNodeAttribute" and source.attribute_type == "GEOMETRY":
        return source.attribute_name or None
    return None


def reading_materials():
    """The materials whose surface colour a colour attribute feeds (the materials
    themselves: a linked library's material may share a local one's name)."""
    return {m for m in bpy.data.materials if m.users and attribute_read(m) is not None}


def render_attribute(mesh):
    """The name of MESH's render colour attribute, None without one."""
    attributes = mesh.color_attributes
    return attributes[attributes.render_color_index].name if attributes.render_color_index >= 0 else None


def colour_exports(objects, readers, warnings):
    """{mesh: (the colour attribute to export as its COLOR_0, the materials that read it)}
    for the meshes of OBJECTS whose materials among READERS read one (a mesh shared by
    several objects once, with the materials of all), with a warning where that differs
    from Cycles: a material reading an attribute the mesh lacks (Cycles reads black; it is
    exported without vertex colours), a mesh whose materials read different ones (the
    exporter writes one a mesh), and a mesh from a linked library whose materials read
    another than its render one (which the export cannot change; exported without)."""
    read_by_mesh, first_object = {}, {}
    for obj in sorted({o for o in objects if o.type == "MESH"}, key=lambda o: o.name):
        first_object.setdefault(obj.data, obj)
        read = read_by_mesh.setdefault(obj.data, {})
        # The exporter writes primitives for the slots that faces use, and Cycles shades
        # only those: a slot no face uses reads nothing.
        used = {polygon.material_index for polygon in obj.data.polygons}
        for index, slot in enumerate(obj.material_slots):
            if index in used and slot.material in readers:
                read[slot.material.name] = attribute_read(slot.material) or render_attribute(obj.data)
    exports = {}
    for mesh, read in read_by_mesh.items():
        what = f"object '{first_object[mesh].name}'"
        present = {}
        for material, name in sorted(read.items()):
            if name is not None and mesh.color_attributes.find(name) >= 0:
                present[material] = name
                continue
            attribute = "the render colour attribute" if name is None else f"colour attribute '{name}'"
            warnings.append(f"{what}: material '{material}' reads {attribute}, which is not among the mesh's colour "
                            f"attributes: Cycles reads black (or, for an attribute of another kind, its values); "
                            f"exported without vertex colours, so white times the factor")
        names = sorted(set(present.values()))
        if len(names) > 1:
            warnings.append(f"{what}: its materials read colour attributes {names}, but a mesh is exported with "
                            f"one; all read '{names[0]}'")
        if not names:
            continue
        if mesh.library is not None and names[0] != render_attribute(mesh):
            warnings.append(f"{what}: mesh '{mesh.name}' comes from a linked library, so the export cannot make "
                            f"'{names[0]}', which its materials read, its render colour attribute; exported without "
                            f"vertex colours")
            continue
        exports[mesh] = (names[0], set(present))
    return exports


def first_value_outside_unit_range(exports):
    """A message naming the first mesh of EXPORTS whose exported attribute holds a colour
    channel outside [0, 1] (or not a number), which glTF's COLOR_0 cannot hold and
    vkdiffrender refuses; None where every one is within."""
    for mesh, (name, _) in exports.items():
        attribute = mesh.color_attributes[name]
        values = np.empty(len(attribute.data) * 4, dtype=np.float32)
        attribute.data.foreach_get("color", values)
        rgb = values.reshape(-1, 4)[:, :3]
        outside = np.flatnonzero(~((rgb >= 0.0) & (rgb <= 1.0)).all(axis=1))
        if outside.size:
            return (f"mesh '{mesh.name}': colour attribute '{name}' holds {tuple(rgb[outside[0]].tolist())} at "
                    f"element {outside[0]}; vertex colours must be within [0, 1] in every channel")
    return None


@contextlib.contextmanager
def attributes_read_as_render(exports):
    """The glTF exporter writes a mesh's render colour attribute: for the export it is the
    one EXPORTS (colour_exports) gives, and is set back after."""
    changed = []
    try:
        for mesh, (name, _) in exports.items():
            attributes = mesh.color_attributes
            index = attributes.find(name)
            if index != attributes.render_color_index:
                changed.append((mesh, attributes.render_color_index))
                attributes.render_color_index = index
                mesh.update()
        yield
    finally:
        for mesh, index in reversed(changed):
            mesh.color_attributes.render_color_index = index
            mesh.update()


def keep_only_where_read(doc, exports):
    """Takes COLOR_0 off every primitive but those of a mesh and material of EXPORTS
    (colour_exports; the accessors stay, unused)."""
    kept = {(mesh.name, material) for mesh, (_, materials) in exports.items() for material in materials}
    materials = doc.get("materials", [])
    for mesh in doc.get("meshes", []):
        for primitive in mesh.get("primitives", []):
            index = primitive.get("material")
            name = materials[index].get("name") if index is not None and index < len(materials) else None
            if (mesh.get("name"), name) not in kept:
                primitive.get("attributes", {}).pop("COLOR_0", None)
