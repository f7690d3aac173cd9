"""Face-corner colour attributes through Blender 3.4's glTF exporter.

The exporter of Blender 3.4 (io_scene_gltf2 3.4.x) reads a face-corner colour attribute's
value at each corner from the element numbered like the corner's vertex, not from the
corner itself, so a painted mesh is exported with its colours shuffled (glTF-Blender-IO
issue 1815; later versions read the corner's own). Face Corner is the domain Vertex Paint
gives a new colour attribute. For the export this module makes the exporter read each
corner's own colour, and leaves the exporter as it was afterwards."""
import contextlib

import numpy as np

# The exporter versions that index corners by vertex.
MISREADING_VERSIONS = ((3, 4),)


def corner_colours(mesh):
    """The render colour attribute of MESH at each face corner, as an array (corners, 4)."""
    attributes = mesh.color_attributes
    values = np.empty(len(mesh.loops) * 4, dtype=np.float32)
    attributes[attributes.render_color_index].data.foreach_get("color", values)
    return values.reshape(-1, 4)


def exporter_creator():
    """The exporter's PrimitiveCreator where its version misreads corners, else None."""
    import io_scene_gltf2
    if tuple(io_scene_gltf2.bl_info["version"][:2]) not in MISREADING_VERSIONS:
        return None
    from io_scene_gltf2.blender.exp import gltf2_blender_gather_primitives_extract as extract
    creator = getattr(extract, "PrimitiveCreator", None)
    return creator if hasattr(creator, "_PrimitiveCreator__get_color_attribute") else None


@contextlib.contextmanager
def read_at_each_corner():
    """Within it the exporter gives every exported corner (its "dots", one a face corner)
    the colour of that corner where the render colour attribute is stored per corner;
    attributes stored per vertex go through the exporter's own reading."""
    creator = exporter_creator()
    if creator is None:
        yield
        return
    original = creator._PrimitiveCreator__get_color_attribute

    def get_color_attribute(self, attr):
        if attr["blender_domain"] != "CORNER":
            original(self, attr)
            return
        colours = corner_colours(self.blender_mesh)
        for channel in range(4):
            self.dots[attr["gltf_attribute_name"] + str(channel)] = colours[:, channel]

    creator._PrimitiveCreator__get_color_attribute = get_color_attribute
    try:
        yield
    finally:
        creator._PrimitiveCreator__get_color_attribute = original
