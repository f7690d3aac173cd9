"""What an Image Texture node does in Cycles that the glTF export cannot carry: Blender's
glTF exporter writes the image, its extension as a sampler wrap mode and a Mapping node
as KHR_texture_transform where it can, and drops the rest without telling the add-on."""
import bpy

from . import node_graph

# Mapping node types the glTF exporter turns into KHR_texture_transform.
EXPORTED_MAPPINGS = {"POINT", "TEXTURE", "VECTOR"}


def coordinate_source(texture, warnings, what):
    """Follows the texture's Vector input back through Mapping nodes, warning of each one the
    exporter drops; returns the node and output name the coordinates come from, or None for
    an unlinked input (the UV map)."""
    socket, seen = texture.inputs["Vector"], set()
    while (link := node_graph.source_link(socket)) is not None and link.from_node.name not in seen:
        node = link.from_node
        seen.add(node.name)
        if node.bl_idname != "ShaderNodeMapping":
            return node, link.from_socket.name
        rotation = node.inputs["Rotation"].default_value
        linked = [s.name for s in node.inputs if s.name != "Vector" and node_graph.is_fed(s)]
        if node.vector_type not in EXPORTED_MAPPINGS or rotation[0] != 0.0 or rotation[1] != 0.0 or linked:
            warnings.append(f"{what}: Mapping node '{node.name}' cannot be exported as a texture transform (only "
                            f"unlinked location, scale and rotation about Z of a Point, Texture or Vector "
                            f"mapping can); the glTF exporter drops it")
        socket = node.inputs["Vector"]
    return None


def warn_texture_lookups(doc, warnings):
    """Warns, per Image Texture node that feeds something, of what vkdiffrender will look up
    differently from Cycles."""
    for material in doc.get("materials", []):
        blender_material = bpy.data.materials.get(material.get("name", ""))
        if blender_material is None or not blender_material.use_nodes:
            continue
        for node in blender_material.node_tree.nodes:
            if node.bl_idname != "ShaderNodeTexImage" or not any(o.is_linked for o in node.outputs):
                continue
            what = f"material '{blender_material.name}': image texture '{node.name}'"
            if node.extension == "CLIP":
                warnings.append(f"{what}: extension Clip is exported as Extend (glTF has no clipping): "
                                f"vkdiffrender shows the image's edge where Cycles shows black")
            if node.projection != "FLAT":
                warnings.append(f"{what}: {node.projection.capitalize()} projection is exported as Flat "
                                f"(a lookup by the texture coordinates alone)")
            if node.interpolation != "Linear":
                warnings.append(f"{what}: {node.interpolation} interpolation is exported as Linear "
                                f"(vkdiffrender looks textures up bilinearly)")
            image = node.image
            if image is not None and image.colorspace_settings.name != "sRGB":
                warnings.append(f"{what}: image '{image.name}' is in colour space "
                                f"'{image.colorspace_settings.name}', but glTF colour textures are sRGB, so "
                                f"vkdiffrender decodes it as sRGB")
            source = coordinate_source(node, warnings, what)
            if source is None:
                continue
            node_of, output = source
            if node_of.bl_idname == "ShaderNodeUVMap" or (node_of.bl_idname == "ShaderNodeTexCoord" and output == "UV"):
                continue
            warnings.append(f"{what}: it is looked up with '{node_of.name}' output '{output}', which glTF cannot "
                            f"carry; vkdiffrender uses the UV map")
