"""File > Import > vkdiffrender (.gltf/.glb): Blender's glTF importer, then the media,
background and light values it does not know restored as Cycles nodes. The values are
read and checked before the importer runs, so that a file with a bad one changes
nothing."""
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


@contextlib.contextmanager
def unit_scale_of_one(scene):
    """Blender 3.4's glTF importer divides positions by the scene's Unit Scale, while its
    exporter, and so the add-on's export, writes Blender units as they are: the importer
    runs at a Unit Scale of 1, so that a scene comes back at the size it was exported
    with and its media's coefficients and lights' powers still fit it."""
    units = scene.unit_settings
    scale = units.scale_length
    units.scale_length = 1.0
    try:
        yield
    finally:
        units.scale_length = scale


def read_gltf_json(path):
    """The JSON object of a .gltf or .glb file; ValueError naming the file where there is
    none."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        if len(data) < 20:
            raise ValueError(f"{path}: a GLB file cut short ({len(data)} bytes)")
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:
            raise ValueError(f"{path}: the first GLB chunk is not JSON")
        data = data[20:20 + length]
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError) as error:  # ValueError: undecodable bytes, bad JSON, huge integers
        raise ValueError(f"{path}: not a glTF file (its JSON does not parse: {error})") from None
    return json_object(doc, path)


FLOAT_MAX = 3.4028234663852886e38


def shown(value):
    """A JSON value for a message, cut short where long."""
    text = json.dumps(value)
    return text if len(text) <= 60 else text[:57] + "..."


def is_number(value):
    """A JSON number a float holds: Python's json also reads NaN, Infinity and integers of
    any size."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return False
    try:
        return abs(float(value)) <= FLOAT_MAX
    except OverflowError:
        return False


def number(entry, key, default, where):
    value = entry.get(key, default)
    if not is_number(value):
        raise ValueError(f"{where}.{key}: expected a finite number within float range, got {shown(value)}")
    return float(value)


def rgb(entry, key, default, where):
    """ENTRY[KEY] as three floats: a number broadcasts, a list gives its first three."""
    value = entry.get(key, default)
    if is_number(value):
        return (float(value),) * 3
    if not (isinstance(value, list) and len(value) >= 3 and all(is_number(v) for v in value[:3])):
        raise ValueError(f"{where}.{key}: expected a finite number or three within float range, "
                         f"got {shown(value)}")
    return tuple(float(v) for v in value[:3])


def json_object(value, where):
    if not isinstance(value, dict):
        raise ValueError(f"{where}: expected an object, got {shown(value)}")
    return value


GRID_KEYS = {"density": "density", "albedoGrid": "albedo", "emissionGrid": "emission"}


def medium_from_json(entry, where):
    """A medium as vkdiffrender reads it: VKDR_participating_media (scalars broadcast), or
    KHR_materials_volume's attenuation (sigma_a = -ln(colour) / distance)."""
    entry = json_object(entry, where)
    for key in GRID_KEYS:
        if key in entry:
            json_object(entry[key], f"{where}.{key}")
    if "attenuationColor" in entry or "attenuationDistance" in entry:
        distance = number(entry, "attenuationDistance", 0.0, where) if "attenuationDistance" in entry else math.inf
        if distance <= 0.0:
            raise ValueError(f"{where}.attenuationDistance: must be > 0, got {shown(entry['attenuationDistance'])}")
        colour = rgb(entry, "attenuationColor", 1.0, where)
        if any(not 0.0 < c <= 1.0 for c in colour):
            raise ValueError(f"{where}.attenuationColor: must be in (0, 1], "
                             f"got {shown(entry['attenuationColor'])}")
        sigma_a = tuple(-math.log(c) / distance for c in colour)
        return mappings.Medium(sigma_a, (0.0, 0.0, 0.0), 0.0)
    return mappings.Medium(rgb(entry, "sigma_a", 0.0, where), rgb(entry, "sigma_s", 0.0, where),
                           number(entry, "g", 0.0, where), rgb(entry, "emission", 0.0, where))


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


def json_list(value, where):
    if not isinstance(value, list):
        raise ValueError(f"{where}: expected an array, got {shown(value)}")
    return value


def member(obj, key, where, default=None):
    """OBJ[KEY] as an object (DEFAULT, or an empty one, where absent)."""
    return json_object(obj.get(key, {} if default is None else default), f"{where}.{key}" if where else key)


def material_media(doc):
    """(material name, medium entry, Medium) of every material of DOC with a medium."""
    media = []
    for index, material in enumerate(json_list(doc.get("materials", []), "materials")):
        material = json_object(material, f"materials[{index}]")
        extensions = member(material, "extensions", f"materials[{index}]")
        key = EXTENSION if EXTENSION in extensions else "KHR_materials_volume"
        entry = extensions.get(key)
        # vkdiffrender reads KHR_materials_volume only behind a surface that transmits all
        # light (transmissionFactor 1); elsewhere the surface is opaque and hides it.
        if key == "KHR_materials_volume" and entry is not None:
            transmission = member(extensions, "KHR_materials_transmission", f"materials[{index}].extensions")
            if number(transmission, "transmissionFactor", 0.0,
                      f"materials[{index}].extensions.KHR_materials_transmission") != 1.0:
                entry = None
        if entry is not None:
            medium = medium_from_json(entry, f"materials[{index}].extensions.{key}")
            name = material.get("name", f"Material_{index}")  # as Blender's importer names an unnamed one
            if not isinstance(name, str):
                raise ValueError(f"materials[{index}].name: expected text, got {shown(name)}")
            media.append((name, entry, medium))
    return media


def restore_media(media, materials, warnings, renamed):
    for name, entry, medium in media:
        blender_material = match(materials, name, renamed)
        if blender_material is None:
            warnings.append(f"material '{name}': not created by the importer (unused?); its medium is skipped")
            continue
        warn_grids(entry, f"material '{name}'", warnings)
        set_volume(blender_material, medium, "OUTPUT_MATERIAL")



def warn_grids(entry, what, warnings):
    """The import makes a medium of constants: a grid the medium reads is not imported."""
    for key, kind in GRID_KEYS.items():
        if key in entry:
            grid = entry[key]
            warnings.append(f"{what}: its {kind} grid ('{grid.get('grid')}' in {grid.get('uri')}) is not imported; "
                            f"the medium comes in uniform (import the file as a Volume object with File > Import "
                            f"> OpenVDB for the grid)")


def world_values(doc):
    """The scene medium's entry and Medium (or None, None) and the background radiance (or
    None) of DOC."""
    extensions = member(doc, "extensions", "")
    medium_entry, medium = extensions.get(EXTENSION), None
    if medium_entry is not None:
        medium = medium_from_json(medium_entry, "extensions." + EXTENSION)
    background = extensions.get("VKDR_background")
    if background is not None:
        where = "extensions.VKDR_background"
        background = rgb(json_object(background, where), "radiance", 0.0, where)
    return medium_entry, medium, background


def restore_world(world_values, scene, warnings):
    """The scene medium and background in a new World, so that a World the scene had (which
    other scenes may share) keeps its values."""
    medium_entry, medium, background = world_values
    if medium_entry is None and background is None:
        return
    name = medium_entry.get("name", "World") if medium_entry else "World"
    world = bpy.data.worlds.new(name if isinstance(name, str) else "World")
    scene.world = world
    world.use_nodes = True
    if medium_entry is not None:
        warn_grids(medium_entry, "the scene medium", warnings)
        set_volume(world, medium, "OUTPUT_WORLD")
    out = node_graph.owner_output(world)
    node = node_graph.linked_node(out.inputs["Surface"])
    if node is None or node.bl_idname != "ShaderNodeBackground":
        node = world.node_tree.nodes.new("ShaderNodeBackground")
        world.node_tree.links.new(node.outputs[0], out.inputs["Surface"])
    emission = mappings.radiance_to_emission(background if background else 0.0)
    node.inputs["Color"].default_value = (*emission["color"], 1.0)
    node.inputs["Strength"].default_value = emission["strength"]


# The names Blender's importer gives a light without one, by its type.
UNNAMED_LIGHTS = {"directional": "Sun", "point": "Point", "spot": "Spot"}


def light_values(doc):
    """(the name of the object Blender's importer makes of it, colour x intensity, (outer,
    inner) cone angles) of every node of DOC that holds a KHR_lights_punctual light. The
    importer names the object after the node, else after the light, else after the light's
    type."""
    punctual = member(member(doc, "extensions", ""), "KHR_lights_punctual", "extensions")
    lights = json_list(punctual.get("lights", []), "extensions.KHR_lights_punctual.lights")
    values = []
    for node_index, node in enumerate(json_list(doc.get("nodes", []), "nodes")):
        where = f"nodes[{node_index}]"
        node = json_object(node, where)
        index = member(member(node, "extensions", where), "KHR_lights_punctual", where + ".extensions").get("light")
        if index is None:
            continue
        if not (isinstance(index, int) and not isinstance(index, bool) and 0 <= index < len(lights)):
            raise ValueError(f"nodes[{node_index}].extensions.KHR_lights_punctual.light: expected the index of one of "
                             f"the {len(lights)} lights, got {shown(index)}")
        where = f"extensions.KHR_lights_punctual.lights[{index}]"
        entry = json_object(lights[index], where)
        intensity = number(entry, "intensity", 1.0, where)
        value = tuple(c * intensity for c in rgb(entry, "color", 1.0, where))
        spot = member(entry, "spot", where)
        cone = (number(spot, "outerConeAngle", math.pi / 4.0, where + ".spot"),
                number(spot, "innerConeAngle", 0.0, where + ".spot"))
        name = node.get("name") or entry.get("name") or UNNAMED_LIGHTS.get(entry.get("type"), "")
        values.append((str(name), value, cone))
    return values


def restore_lights(lights, objects, renamed):
    """KHR_lights_punctual in Cycles' units (the importer converts with its own factors)."""
    for name, value, cone in lights:
        obj = match([o for o in objects if o.type == "LIGHT"], name, renamed)
        if obj is None:
            continue
        node_graph.set_light_value(obj.data, value)
        if obj.data.type != "SUN":
            obj.data.shadow_soft_size = 0.0
        if obj.data.type == "SPOT":
            # The importer's own blend is not the export's (mappings.spot_cone_angles).
            obj.data.spot_size, obj.data.spot_blend = mappings.spot_size_and_blend(*cone)


def restore_orthographic_views(doc, new_objects, renamed):
    """Blender's glTF importer spans an orthographic camera's Orthographic Scale, 2
    max(xmag, ymag), over the image's longer side (Sensor Fit Auto); vkdiffrender keeps the
    view's height, 2 ymag, and lets its width follow the image's, as Sensor Fit Vertical
    does. Cameras are found by their node's name."""
    cameras = doc.get("cameras", [])
    new_cameras = [obj for obj in new_objects if obj.type == "CAMERA"]
    for node in doc.get("nodes", []):
        index = node.get("camera")
        if not isinstance(index, int) or not 0 <= index < len(cameras) or not isinstance(node.get("name"), str):
            continue
        obj = match(new_cameras, node["name"], renamed)
        if obj is None:
            continue
        if cameras[index].get("type") == "orthographic" and obj.data.type == "ORTHO":
            obj.data.sensor_fit = "VERTICAL"
            obj.data.ortho_scale = 2.0 * float(cameras[index]["orthographic"]["ymag"])


# What Blender's glTF importer adds to the file, objects first since they use the rest.
IMPORTED_DATA = ("objects", "meshes", "armatures", "materials", "cameras", "lights", "images", "node_groups",
                 "actions")


@contextlib.contextmanager
def removed_if_failed():
    """Removes what the glTF importer added where it fails part way (a node that refers to
    a mesh the file lacks, after the objects before it were made): a failed import
    changes nothing."""
    before = {kind: set(getattr(bpy.data, kind)) for kind in IMPORTED_DATA}
    try:
        yield
    except Exception:
        for kind in IMPORTED_DATA:
            data = getattr(bpy.data, kind)
            for added in set(data) - before[kind]:
                data.remove(added)
        raise


def importer_failure(error):
    """What a RuntimeError of Blender's glTF importer says went wrong: its last line
    before the operator call's 'Location:'."""
    lines = [line.strip() for line in str(error).splitlines()
             if line.strip() and not line.strip().startswith("Location:")]
    return lines[-1] if lines else type(error).__name__


def import_scene(context, filepath):
    """Imports FILEPATH into the current scene; returns the warnings."""
    doc = read_gltf_json(filepath)
    try:
        media, world, lights = material_media(doc), world_values(doc), light_values(doc)
    except ValueError as error:
        raise ValueError(f"{filepath}: {error}") from None
    materials_before = {m.name for m in bpy.data.materials}
    objects_before = {o.name for o in bpy.data.objects}
    with numpy_bool_alias(), unit_scale_of_one(context.scene), removed_if_failed():
        bpy.ops.import_scene.gltf(filepath=filepath)
    warnings, renamed = [], []
    restore_media(media, new_ids(bpy.data.materials, materials_before), warnings, renamed)
    restore_world(world, context.scene, warnings)
    new_objects = new_ids(bpy.data.objects, objects_before)
    restore_lights(lights, new_objects, renamed)
    restore_orthographic_views(doc, new_objects, renamed)
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
            # failures, with a traceback) as a RuntimeError.
            self.report({"ERROR"}, f"{self.filepath}: Blender's glTF importer cannot read it "
                                   f"({importer_failure(error)}); nothing was imported")
            return {"CANCELLED"}
        for warning in warnings:
            self.report({"WARNING"}, warning)
        return {"FINISHED"}


def menu_entry(self, context):
    self.layout.operator(IMPORT_OT_vkdiffrender.bl_idname, text="vkdiffrender (.gltf/.glb)")
