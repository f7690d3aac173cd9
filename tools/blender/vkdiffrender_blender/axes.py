"""Blender's Z-up world in glTF's Y-up one, as the glTF exporter's export_yup turns it."""
import mathutils

# (x, y, z) -> (x, z, -y), as blender_to_gltf.
Z_UP_TO_Y_UP = mathutils.Matrix(((1, 0, 0, 0), (0, 0, 1, 0), (0, -1, 0, 0), (0, 0, 0, 1)))


def blender_to_gltf(v):
    return (v[0], v[2], -v[1])
