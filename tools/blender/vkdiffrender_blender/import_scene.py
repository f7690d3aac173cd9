"""File > Import > vkdiffrender (.gltf/.glb): Blender's glTF importer, then the media,
background and light values it does not know restored as Cycles nodes."""
import contextlib
import json
import math
import os
import struct

import bpy
from bpy.props import StringProperty
from bpy_extras.io_utils import ImportHelper

from . import mappings, node_graph
from .gltf_json import EXTENSION


@contextlib.contextmanager
def numpy_bool_alias():
    """Blender 3.4's glTF importer uses numpy.bool, which numpy 1.24 (Debian 12) removed;
    it meant the builtin bool, so the alias is set for the importer's run only."""
    import numpy
    added = not hasattr(numpy, "bool")
    if added:
        numpy.bool = bool
    try:
        yield
    finally:
        if added:
            del numpy.bool


def read_gltf_json(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:
            raise ValueError(f"{path}: the first GLB chunk is not JSON")
        return json.loads(data[20:20 + length])
    return json.loads(data)


def medium_from_json(entry, where):
    """A medium as vkdiffrender reads it: VKDR_participating_media (scalars broadcast), or
    KHR_materials_volume's attenuation (sigma_a = -ln(colour) / distance)."""
    def rgb(key):
        value = entry.get(key, 0.0)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return (float(value),) * 3
        if not (isinstance(value, list) and len(value) >= 3 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in value[:3])):
            raise ValueError(f"{where}.{key}: expected a number or three, got {json.dumps(value)}")
        return tuple(float(v) for v in value[:3])
    if "attenuationColor" in entry or "attenuationDistance" in entry:
        distance = float(entry.get("attenuationDistance", math.inf))
        colour = entry.get("attenuationColor", [1.0, 1.0, 1.0])
        if any(c <= 0.0 for c in colour):
            raise ValueError(f"{where}.attenuationColor: must be > 0, got {colour}")
        sigma_a = tuple(-math.log(c) / distance for c in colour)
        return mappings.Medium(sigma_a, (0.0, 0.0, 0.0), 0.0)
    return mappings.Medium(rgb("sigma_a"), rgb("sigma_s"), float(entry.get("g", 0.0)), rgb("emission"))


def set_volume(owner, medium, output_kind):
    """Make OWNER's Volume output a Principled Volume of this medium and, for a material,
    leave its Surface empty: a clear boundary, as in vkdiffrender."""
    owner.use_nodes = True
    tree = owner.node_tree
    out = node_graph.output_node(tree, output_kind)
    if out is None:
        out = tree.nodes.new("ShaderNodeOutputWorld" if output_kind == "OUTPUT_WORLD" else "ShaderNodeOutputMaterial")
    if output_kind == "OUTPUT_MATERIAL":
        for link in list(out.inputs["Surface"].links):
            tree.links.remove(link)
    node = node_graph.material_volume_node(owner)
    if node is None or node.bl_idname != "ShaderNodeVolumePrincipled":
        node = tree.nodes.new("ShaderNodeVolumePrincipled")
        node.location = (out.location[0] - 300, out.location[1] - 200)
        tree.links.new(node.outputs[0], out.inputs["Volume"])
    node_graph.write_medium(node, medium)
    return node


def new_ids(collection, before):
    return [item for item in collection if item.name not in before]


def match(items, gltf_name, renamed):
    """The importer names data after glTF names, with Blender's .001 suffix on a clash;
    a datablock found under another name than its glTF name goes into RENAMED."""
    for item in items:
        if item.name == gltf_name or item.name.startswith(gltf_name + "."):
            if item.name != gltf_name:
                renamed.append(gltf_name)
            return item
    return None


def warn_renamed(renamed, warnings):
    """Matching by Blender's suffixes can pair a value with another of the file's names."""
    if renamed:
        warnings.append(f"the .blend already had datablocks named like the file's ({', '.join(sorted(set(renamed)))}); "
                        f"Blender renamed the imported ones and the import matched them by their suffixes, which "
                        f"can pair media or light values with the wrong one: check them, or import into an empty "
                        f"file")


def restore_media(doc, materials, warnings, renamed):
    for index, material in enumerate(doc.get("materials", [])):
        extensions = material.get("extensions", {})
        key = EXTENSION if EXTENSION in extensions else "KHR_materials_volume"
        entry = extensions.get(key)
        if entry is None:
            continue
        name = material.get("name", str(index))
        blender_material = match(materials, name, renamed)
        if blender_material is None:
            warnings.append(f"material '{name}': not created by the importer (unused?); its medium is skipped")
            continue
        warn_grids(entry, f"material '{name}'", warnings)
        set_volume(blender_material, medium_from_json(entry, f"materials[{index}].extensions.{key}"), "OUTPUT_MATERIAL")


GRID_KEYS = {"density": "density", "albedoGrid": "albedo", "emissionGrid": "emission"}


def warn_grids(entry, what, warnings):
    """The import makes a medium of constants: a grid the medium reads is not imported."""
    for key, kind in GRID_KEYS.items():
        if key in entry:
            grid = entry[key]
            warnings.append(f"{what}: its {kind} grid ('{grid.get('grid')}' in {grid.get('uri')}) is not imported; "
                            f"the medium comes in uniform (import the file as a Volume object with File > Import "
                            f"> OpenVDB for the grid)")


def restore_world(doc, scene, warnings):
    """The scene medium and background in a new World, so that a World the scene had (which
    other scenes may share) keeps its values."""
    extensions = doc.get("extensions", {})
    medium_entry, background = extensions.get(EXTENSION), extensions.get("VKDR_background")
    if medium_entry is None and background is None:
        return
    world = bpy.data.worlds.new(medium_entry.get("name", "World") if medium_entry else "World")
    scene.world = world
    world.use_nodes = True
    if medium_entry is not None:
        warn_grids(medium_entry, "the scene medium", warnings)
        set_volume(world, medium_from_json(medium_entry, "extensions." + EXTENSION), "OUTPUT_WORLD")
    out = node_graph.output_node(world.node_tree, "OUTPUT_WORLD")
    node = node_graph.linked_node(out.inputs["Surface"])
    if node is None or node.bl_idname != "ShaderNodeBackground":
        node = world.node_tree.nodes.new("ShaderNodeBackground")
        world.node_tree.links.new(node.outputs[0], out.inputs["Surface"])
    emission = mappings.radiance_to_emission(background["radiance"] if background else 0.0)
    node.inputs["Color"].default_value = (*emission["color"], 1.0)
    node.inputs["Strength"].default_value = emission["strength"]


def restore_lights(doc, objects, renamed):
    """KHR_lights_punctual in Cycles' units (the importer converts with its own factors)."""
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    for node in doc.get("nodes", []):
        index = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        obj = match([o for o in objects if o.type == "LIGHT"], node.get("name", ""), renamed)
        if index is None or obj is None:
            continue
        entry = lights[index]
        value = tuple(c * float(entry.get("intensity", 1.0)) for c in entry.get("color", [1.0, 1.0, 1.0]))
        node_graph.set_light_value(obj.data, value)
        if obj.data.type != "SUN":
            obj.data.shadow_soft_size = 0.0
        if obj.data.type == "SPOT":
            # The importer's own blend is not the export's (mappings.spot_cone_angles).
            spot = entry.get("spot", {})
            obj.data.spot_size, obj.data.spot_blend = mappings.spot_size_and_blend(
                spot.get("outerConeAngle", math.pi / 4.0), spot.get("innerConeAngle", 0.0))


def import_scene(context, filepath):
    """Imports FILEPATH into the current scene; returns the warnings."""
    materials_before = {m.name for m in bpy.data.materials}
    objects_before = {o.name for o in bpy.data.objects}
    with numpy_bool_alias():
        bpy.ops.import_scene.gltf(filepath=filepath)
    doc = read_gltf_json(filepath)
    warnings, renamed = [], []
    restore_media(doc, new_ids(bpy.data.materials, materials_before), warnings, renamed)
    restore_world(doc, context.scene, warnings)
    new_objects = new_ids(bpy.data.objects, objects_before)
    restore_lights(doc, new_objects, renamed)
    warn_renamed(renamed, warnings)
    if context.scene.camera is None:  # Cycles renders through the scene camera
        context.scene.camera = next((o for o in new_objects if o.type == "CAMERA"), None)
    return warnings


class IMPORT_OT_vkdiffrender(bpy.types.Operator, ImportHelper):
    """Import a vkdiffrender scene or fitted scene.gltf, with its media as Principled Volume nodes"""
    bl_idname = "import_scene.vkdiffrender"
    bl_label = "Import vkdiffrender"
    filter_glob: StringProperty(default="*.gltf;*.glb", options={"HIDDEN"})

    def execute(self, context):
        if not os.path.isfile(self.filepath):
            self.report({"ERROR"}, f"{self.filepath}: no such file")
            return {"CANCELLED"}
        try:
            warnings = import_scene(context, self.filepath)
        except (OSError, ValueError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        except RuntimeError as error:
            # Blender's glTF importer, which reports a file it cannot read (and its own
            # failures, with a traceback) as a RuntimeError: its last line says what.
            lines = [line.strip() for line in str(error).splitlines() if line.strip()]
            self.report({"ERROR"}, f"{self.filepath}: Blender's glTF importer cannot read it "
                                   f"({lines[-1] if lines else type(error).__name__})")
            return {"CANCELLED"}
        for warning in warnings:
            self.report({"WARNING"}, warning)
        return {"FINISHED"}


def menu_entry(self, context):
    self.layout.operator(IMPORT_OT_vkdiffrender.bl_idname, text="vkdiffrender (.gltf/.glb)")
