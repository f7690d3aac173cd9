"""Fitted values (params.json of `vkdiffrender optimize`) written back into the Blender
nodes and lights they were exported from, with the inverse mappings, and the list of
parameters a scene offers for fitting. Names are those export_scene gives: a medium is
named after its material (or the World), an area light's emitter is '<object>.area'."""
import json

import bpy

from . import axes, export_scene, mappings, node_graph
from .rendered_objects import EXPORTED_GEOMETRY, rendered_objects

SURFACE_COLOR_INPUTS = {"ShaderNodeBsdfPrincipled": "Base Color", "ShaderNodeBsdfDiffuse": "Color"}
# A medium's values that its volume node holds, and those of its grids, which it does not.
MEDIUM_VALUES = ("sigma_a", "sigma_s", "g", "emission")
GRID_VALUES = ("density", "albedo_grid", "emission_grid")


def volume_owners(scene):
    """(name, material or world, its volume node) for every volume the Fit can write into."""
    owners = [(m.name, m, node_graph.material_volume_node(m)) for m in bpy.data.materials if m.users]
    if scene.world is not None:
        owners.append((node_graph.world_medium_name(scene.world), scene.world,
                       node_graph.material_volume_node(scene.world)))
    return [(name, owner, node) for name, owner, node in owners if node is not None]


def rendered_area_lights(view_layer):
    """{exported name: (light object, its world matrix)} of the area lights the export writes."""
    return {export_scene.area_light_material_name(r.name): (r.object, r.matrix_world)
            for r in rendered_objects(view_layer) if export_scene.emitting_area_light(r.object)}


def face_materials(obj, depsgraph):
    """The materials of OBJ's faces as the glTF exporter writes them, not a slot that no
    face uses: the faces as DEPSGRAPH evaluates the object, each with the material of the
    object's own slot of its index, the last slot's past them (a node tree's Set Material
    adds to the evaluated mesh's materials, not to the object's slots), as the exporter
    does, which leaves a curve's, surface's or text's empty slots out first."""
    materials = [slot.material for slot in obj.material_slots]
    if obj.type != "MESH":
        materials = [material for material in materials if material is not None]
    evaluated = obj.evaluated_get(depsgraph)
    try:
        mesh = evaluated.to_mesh()
        used = {polygon.material_index for polygon in mesh.polygons} if mesh is not None else set()
    except RuntimeError:  # no geometry to make a mesh of, which the exporter skips too
        used = set()
    finally:
        evaluated.to_mesh_clear()
    if not materials:
        return set()
    return {materials[min(i, len(materials) - 1)] for i in used} - {None}


def rendered_materials(scene, view_layer):
    """The materials the export writes: those of the exported faces, and Volume objects'
    (grid_media). A material used only by an object hidden from the render, by one the
    glTF exporter leaves out (a metaball) or by no face is in no exported scene, and has no
    parameter to fit."""
    materials = set()
    with export_scene.modifiers_as_rendered(scene):
        depsgraph = view_layer.depsgraph
        depsgraph.update()  # the faces as the render evaluates them, as the export writes them
        for obj in {r.object for r in rendered_objects(view_layer)}:
            if obj.type in EXPORTED_GEOMETRY:
                materials |= face_materials(obj, depsgraph)
            elif obj.type == "VOLUME":
                materials |= {slot.material for slot in obj.material_slots if slot.material is not None}
    return materials


def fittable_parameters(scene, view_layer):
    """Parameter names in vkdiffrender's spelling, each with a label for the UI. The Fit
    steps coefficients in log units (fit_run.optimize_command), so a coefficient is
    offered only where every channel of it is above 0; and a value only where no node
    feeds an input it would be written to, which Cycles would not use."""
    names = []
    rendered = rendered_materials(scene, view_layer)
    for name, owner, node in volume_owners(scene):
        if isinstance(owner, bpy.types.Material) and owner not in rendered:
            continue
        medium = node_graph.volume_medium(node, [], name)
        names += [f"media/{name}/{kind}" for kind, inputs in node_graph.WRITTEN_INPUTS[node.bl_idname].items()
                  if (kind == "g" or min(getattr(medium, kind)) > 0.0) and
                  not any(node_graph.is_fed(node.inputs[i]) for i in inputs)]
    for material in bpy.data.materials:
        # A material with a volume exports as a medium's boundary, which has no colour.
        surface = node_graph.surface_node(material) if material in rendered else None
        if surface is None or surface.bl_idname not in SURFACE_COLOR_INPUTS or \
                node_graph.material_volume_node(material) is not None:
            continue
        colour = surface.inputs[SURFACE_COLOR_INPUTS[surface.bl_idname]]
        if min(colour.default_value[:3]) > 0.0 and not node_graph.is_fed(colour):
            names.append(f"materials/{material.name}/base_color")
    names += [f"lights/{name}/emission" for name, (obj, _) in rendered_area_lights(view_layer).items()
              if obj.data.energy > 0.0 and min(obj.data.color) > 0.0]
    return names


def write_medium_values(owner_node, fitted, name):
    """Complete a fitted medium with the exported values of what was not fitted. Emission
    is written only when fitted: an Emission Strength read from a grid (a fire's flame)
    is not the node's unlinked value."""
    warnings = []
    current = node_graph.volume_medium(owner_node, warnings, name)
    medium = mappings.Medium(tuple(fitted.get("sigma_a", current.sigma_a)),
                             tuple(fitted.get("sigma_s", current.sigma_s)),
                             float(fitted.get("g", [current.g])[0]),
                             tuple(fitted.get("emission", current.emission)))
    return [f"{name}: {warning}" for warning in
            node_graph.write_medium(owner_node, medium, kinds=tuple(fitted))]


def parameter_parts(name):
    """(kind, owner, value) of a parameter name "kind/owner/value"; an owner's name may
    hold '/' (a material "Fog/Night")."""
    kind, _, rest = name.partition("/")
    owner, _, value = rest.rpartition("/")
    return kind, owner, value


def linked_library_warnings(name, datablock):
    """Blender saves no change to data linked from another file (or overridden from it):
    a warning saying so for such a datablock, else none."""
    if datablock is None or (datablock.library is None and datablock.override_library is None):
        return []
    source = datablock.library.filepath if datablock.library is not None else "that it overrides"
    return [f"{name}: '{datablock.name}' comes from the library {source}; the value is set for this session but "
            f"not saved with this file"]


def apply_fitted_values(scene, view_layer, params):
    """Write PARAMS ({name: [values]}) into the scene; returns warnings for names that have
    no Blender counterpart or cannot be held exactly."""
    warnings = []
    media = {}
    area_lights = rendered_area_lights(view_layer)
    for name, value in params.items():
        kind, owner, value_name = parameter_parts(name)
        if kind == "media" and owner and value_name in MEDIUM_VALUES:
            media.setdefault(owner, {})[value_name] = value
        elif kind == "media" and value_name in GRID_VALUES:
            warnings.append(f"{name}: a grid's fitted voxels are in the .vdb files beside the run's scene.gltf; "
                            f"not written back")
        elif kind == "materials" and value_name == "base_color":
            material = bpy.data.materials.get(owner)
            surface = node_graph.surface_node(material)
            if surface is None or surface.bl_idname not in SURFACE_COLOR_INPUTS:
                warnings.append(f"{name}: no Principled or Diffuse BSDF to write into")
                continue
            socket = surface.inputs[SURFACE_COLOR_INPUTS[surface.bl_idname]]
            if node_graph.is_fed(socket):
                warnings.append(f"{name}: '{surface.name}' input '{socket.name}' is linked (a texture); the value "
                                f"goes to its unlinked default, which Cycles does not use")
            socket.default_value = (*value[:3], 1.0)
            warnings += linked_library_warnings(name, material)
        elif kind == "lights" and value_name == "emission" and owner.endswith(".area"):
            if owner not in area_lights:
                warnings.append(f"{name}: no area light '{owner[:-len('.area')]}'")
                continue
            obj, matrix_world = area_lights[owner]
            corners = [axes.blender_to_gltf(p) for p in export_scene.area_light_polygon(obj, matrix_world)]
            light = mappings.radiance_to_area_light(value, export_scene.polygon_area(corners))
            obj.data.color, obj.data.energy = light["color"], light["power"]
            # Other objects of the same light data, and other instances of this object,
            # are other emitters of the export: one value is written for them all.
            sharing = [other for other, (other_obj, _) in area_lights.items()
                       if other_obj.data == obj.data and other != owner]
            if sharing:
                warnings.append(f"{name}: its light data is shared with {', '.join(sharing)}, which takes the "
                                f"value too")
            warnings += linked_library_warnings(name, obj.data)
        elif kind == "lights" and value_name == "intensity":
            # Blender's exporter names a glTF light after its light data, which vkdiffrender's
            # parameter names follow; a file from elsewhere may name it after the object.
            obj = next((o for o in scene.objects if o.type == "LIGHT" and o.data.name == owner), None)
            if obj is None:
                obj = scene.objects.get(owner)
                obj = obj if obj is not None and obj.type == "LIGHT" else None
            if obj is None:
                warnings.append(f"{name}: no light '{owner}'")
                continue
            node_graph.set_light_value(obj.data, value)
            warnings += linked_library_warnings(name, obj.data)
        else:
            warnings.append(f"{name}: not written back (no Blender counterpart)")
    owners = {name: (owner, node) for name, owner, node in volume_owners(scene)}
    for medium_name, fitted in media.items():
        if medium_name not in owners:
            warnings.append(f"media/{medium_name}: no material or world with a single volume node of that name")
            continue
        owner, node = owners[medium_name]
        warnings += write_medium_values(node, fitted, f"medium '{medium_name}'")
        warnings += linked_library_warnings(f"media/{medium_name}", owner)
    return warnings


def apply_params_file(scene, view_layer, path):
    with open(path, encoding="utf-8") as f:
        return apply_fitted_values(scene, view_layer, json.load(f))
