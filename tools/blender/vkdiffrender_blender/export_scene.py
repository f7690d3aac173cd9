"""File > Export > vkdiffrender (.gltf): Blender's glTF exporter, then the exported JSON
completed with what that exporter leaves out or converts differently from Cycles.

Post-processing the written JSON, rather than the exporter's user-extension hooks, because
three of the four additions are things the exporter never visits (the World, area lights,
which it drops, and a root-level extension), and the light intensities it does write must
be replaced as a whole; the JSON is the one interface that stays the same across exporter
versions."""
import contextlib
import itertools
import json
import math
import os
import shutil
import tempfile
import urllib.parse

import bpy
import mathutils
import numpy
from bpy.props import StringProperty
from bpy_extras.io_utils import ExportHelper

from . import (corner_colours, export_checks, gltf_json, grid_media, mappings, node_graph, scene_checks,
               texture_lookups, vertex_colours)
from .axes import blender_to_gltf
from .gltf_json import EXTENSION, TRANSMISSION_EXTENSIONS, medium_json
from .rendered_objects import EXPORTED_GEOMETRY, Instances, rendered_objects


class ExportError(Exception):
    """A scene or path the export cannot write a loadable scene for; nothing is written."""


def run_gltf_exporter(filepath, colours):
    """The scene at the current frame, objects as the render shows them (renders_as_cycles,
    modifiers_as_rendered). With every mesh's render colour attribute as COLOR_0 where
    COLOURS (vertex_colours)."""
    bpy.ops.export_scene.gltf(filepath=filepath, export_format="GLTF_SEPARATE", export_cameras=True,
                              export_lights=True, export_apply=True, export_yup=True,
                              export_normals=True, export_materials="EXPORT", export_extras=False,
                              export_colors=colours,
                              export_animations=False, export_current_frame=True,
                              use_selection=False, use_visible=False, use_renderable=True)


# The camera types vkdiffrender renders through (not panoramic ones).
RENDERED_CAMERAS = ("PERSP", "ORTHO")
# Modifier settings whose viewport value the glTF exporter's depsgraph evaluates, with the
# setting the render evaluates instead.
RENDER_LEVELS = {"SUBSURF": ("levels", "render_levels"), "MULTIRES": ("levels", "render_levels")}


# Simplify's viewport settings, with the setting the render takes instead.
SIMPLIFY_LEVELS = {"simplify_subdivision": "simplify_subdivision_render",
                   "simplify_child_particles": "simplify_child_particles_render"}


def render_settings(scene, objects, collections):
    """(owner, attribute, the value a render uses) where the viewport's depsgraph evaluates
    otherwise: a modifier enabled for one of the two, or subdividing to another level;
    Simplify's viewport limits; objects and collections disabled in viewports, which it
    does not evaluate at all (their modifiers would be left out). Linked library data
    cannot be changed and is left."""
    for viewport, render in SIMPLIFY_LEVELS.items():
        yield scene.render, viewport, getattr(scene.render, render)
    for collection in collections:
        if collection.library is None:
            yield collection, "hide_viewport", False
    for obj in objects:
        if obj.library is not None:
            continue
        yield obj, "hide_viewport", False
        for modifier in obj.modifiers:
            yield modifier, "show_viewport", modifier.show_render
            if modifier.type in RENDER_LEVELS:
                viewport, render = RENDER_LEVELS[modifier.type]
                yield modifier, viewport, getattr(modifier, render)


@contextlib.contextmanager
def modifiers_as_rendered(scene):
    """The scene's depsgraph, which the glTF exporter and rendered_objects read, evaluates
    the viewport's settings: for the export they take the render's (render_settings), in
    every object, instanced assets too."""
    changed = []
    for owner, attribute, value in list(render_settings(scene, bpy.data.objects, bpy.data.collections)):
        if getattr(owner, attribute) != value:
            changed.append((owner, attribute, getattr(owner, attribute)))
            setattr(owner, attribute, value)
    try:
        yield
    finally:
        for owner, attribute, value in reversed(changed):
            setattr(owner, attribute, value)


@contextlib.contextmanager
def renders_as_cycles(scene, view_layer):
    """The glTF exporter's renderable test looks at an object's own flag and its direct
    collections only: for its run, objects the render does not show (rendered_objects:
    excluded or render-disabled collections at any depth) are disabled for rendering, and
    the scene camera, which Cycles renders through whatever its flag, is enabled."""
    shown = {r.object.name_full for r in rendered_objects(view_layer)}
    changed = []
    for obj in scene.objects:
        wanted = obj == scene.camera or (obj.name_full in shown and not obj.hide_render)
        if obj.hide_render == wanted and obj.library is None:
            changed.append((obj, obj.hide_render))
            obj.hide_render = not wanted
    try:
        yield
    finally:
        for obj, hidden in changed:
            obj.hide_render = hidden


# Objects Cycles renders that Blender's glTF exporter leaves out, as the warning names them.
UNEXPORTED_GEOMETRY = {"META": "a metaball", "CURVES": "hair curves", "POINTCLOUD": "a point cloud"}


def warn_render_differences(view_layer, warnings):
    """What the render does with an object that the export cannot follow."""
    ray_visibility = ("visible_camera", "visible_diffuse", "visible_glossy", "visible_transmission",
                      "visible_volume_scatter", "visible_shadow")
    # A light's Camera flag is off by default (docs/blender.md: vkdiffrender shows area
    # lights), and Cast Shadow stands for its Shadow flag.
    lit_by_light = ("visible_diffuse", "visible_glossy", "visible_transmission", "visible_volume_scatter")
    instances = Instances(view_layer)
    for rendered in rendered_objects(view_layer):
        obj, what = rendered.object, f"object '{rendered.name}'"
        if obj.type in {"MESH", "VOLUME"} and (obj.is_holdout or
                                               not all(getattr(obj, flag, True) for flag in ray_visibility)):
            warnings.append(f"{what}: its ray visibility (or holdout) is not exported: every ray sees it")
        if obj.type == "LIGHT" and (not getattr(getattr(obj.data, "cycles", None), "cast_shadow", True) or
                                    not all(getattr(obj, flag, True) for flag in lit_by_light)):
            warnings.append(f"light '{rendered.name}': its ray visibility and Cast Shadow are not exported: it "
                            f"lights every surface and medium, and everything casts its shadow")
        if obj.type in UNEXPORTED_GEOMETRY:
            warnings.append(f"{what}: {UNEXPORTED_GEOMETRY[obj.type]}, which Blender's glTF exporter leaves out "
                            f"(it writes meshes, curves, surfaces and text); convert it to a mesh to export it")
        if obj.type in EXPORTED_GEOMETRY and not obj.is_instancer and not rendered.in_collection_instance and \
                any(m.type == "NODES" and m.show_render for m in obj.modifiers):
            # Blender hands out what a node tree makes besides the mesh (instances, and
            # points, curves or volumes) as instances of the object, and so does the
            # mesh of a curve or text object: the tree's are looked for only where one is.
            placed = instances.of(obj)
            if placed:
                warnings.append(f"{what}: its Geometry Nodes make {len(placed)} instances (or points, curves or "
                                f"volumes), which Blender's glTF exporter leaves out; a Realize Instances node at "
                                f"the end of its node tree exports instanced meshes (instanced lights stay out)")
        if obj.library is not None and any(m.show_viewport != m.show_render for m in obj.modifiers):
            warnings.append(f"{what}: its modifiers enabled for the viewport or for rendering only are exported as "
                            f"the viewport shows them (it is linked from a library, whose settings the export "
                            f"cannot change)")
        if rendered.in_collection_instance and obj.is_instancer and obj.instance_type != "COLLECTION":
            warnings.append(f"{what}: instances objects at its vertices, faces or particles inside an instanced "
                            f"collection; lights and volumes among them are not exported there")


def warn_added_volumes(scene, view_layer, warnings):
    """Cycles adds up the volumes a point is inside, the World's among them; vkdiffrender's
    medium at a point is the innermost one's alone (docs/blender.md)."""
    volumes = [r for r in rendered_objects(view_layer)
               if r.object.type == "VOLUME" or (r.object.type == "MESH" and
                                                any(node_graph.has_volume(s.material) for s in r.object.material_slots))]
    if volumes and node_graph.has_volume(scene.world):
        names = ", ".join(f"'{r.name}'" for r in volumes[:4])
        if len(volumes) > 4:
            names += f" and {len(volumes) - 4} more"
        warnings.append(f"world '{scene.world.name}': Cycles adds its volume inside {names}, where vkdiffrender has "
                        f"their own medium alone: add the World's coefficients to theirs for the same render")
    boxes = [(r.name, world_box(r)) for r in volumes]
    for (a, (low_a, high_a)), (b, (low_b, high_b)) in itertools.combinations(boxes, 2):
        if all(low_a[k] < high_b[k] and low_b[k] < high_a[k] for k in range(3)):
            warnings.append(f"objects '{a}' and '{b}': their volumes' boxes overlap; where the volumes do, Cycles "
                            f"adds them and vkdiffrender has the inner one's medium alone")


def world_box(rendered):
    """The world-space bounds (lowest, highest corner) of a rendered object's box."""
    corners = [rendered.matrix_world @ mathutils.Vector(corner) for corner in rendered.object.bound_box]
    return ([min(c[k] for c in corners) for k in range(3)], [max(c[k] for c in corners) for k in range(3)])


def require_closed_boundaries(material, bodies, depsgraph):
    """ExportError naming the object of BODIES (rendered objects with faces) whose faces
    of MATERIAL, a medium's, do not close."""
    for obj in bodies:
        if not any(slot.material == material for slot in obj.material_slots):
            continue
        open_edges = scene_checks.open_boundary_edges(obj, material, depsgraph)
        if open_edges:
            raise ExportError(f"object '{obj.name}': its faces of material '{material.name}', a volume, do not close "
                              f"({open_edges} edges are not shared by exactly two of them); vkdiffrender fills "
                              f"only closed meshes with a medium")


def add_material_media(doc, view_layer, warnings):
    """Volumes of materials: the glTF material of the same name becomes a medium boundary.
    Smoke simulation domains' materials are grid_media's."""
    domains = grid_media.fluid_domain_materials(view_layer)
    bodies = sorted({r.object for r in rendered_objects(view_layer)
                     if r.object.type in {"MESH", "CURVE", "SURFACE", "FONT", "META"}}, key=lambda o: o.name)
    for material in doc.get("materials", []):
        blender_material = bpy.data.materials.get(material.get("name", ""))
        if blender_material is not None and blender_material.name in domains:
            continue
        medium = node_graph.medium_of(blender_material, warnings, f"material '{material.get('name')}'")
        if medium is None:
            unread = node_graph.unsupported_volume_node(blender_material)
            if unread is None or node_graph.surface_node(blender_material) is not None:
                continue
            # Cycles renders the boundary of a volume without a Surface clear; the glTF
            # exporter would write an opaque white surface.
            warnings.append(f"material '{blender_material.name}': its volume ('{unread.name}') cannot be "
                            f"exported; its boundary is exported clear, enclosing no medium")
            medium = mappings.Medium((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.0)
        require_closed_boundaries(blender_material, bodies, view_layer.depsgraph)
        if node_graph.surface_node(blender_material) is not None:
            warnings.append(f"material '{blender_material.name}': has a Surface shader besides its volume; "
                            f"vkdiffrender renders the boundary clear (as Cycles does with no Surface)")
        extensions = material.setdefault("extensions", {})
        # Our extension takes precedence, but a refracting transmission would still be refused.
        for name in TRANSMISSION_EXTENSIONS:
            extensions.pop(name, None)
        extensions[EXTENSION] = medium_json(medium)


def non_negative(radiance, what, source):
    """RADIANCE, or ExportError naming WHAT and SOURCE where a channel is negative: Cycles
    subtracts such light, which vkdiffrender cannot (it would be exported as none)."""
    if min(radiance) < 0.0:
        raise ExportError(f"{what}: {source} is negative ({', '.join(f'{c:g}' for c in radiance)}); Cycles "
                          f"subtracts such light, which vkdiffrender cannot: make it 0 or more")
    return radiance


# Cycles renders faces without a material with its default surface, a Diffuse BSDF of
# grey 0.8; glTF's default material, which a primitive without one gets, is white.
DEFAULT_SURFACE_ALBEDO = 0.8


def add_default_surface(doc):
    """A material of Cycles' default surface for every triangle primitive without one, named
    apart from the document's and Blender's materials (so that no fit writes into it)."""
    primitives = [primitive for mesh in doc.get("meshes", []) for primitive in mesh.get("primitives", [])
                  if "material" not in primitive and primitive.get("mode", 4) == 4]
    if not primitives:
        return
    taken = {m.get("name") for m in doc.get("materials", [])} | {m.name for m in bpy.data.materials}
    name = next(n for n in itertools.chain(["default surface"], (f"default surface.{k}" for k in itertools.count(2)))
                if n not in taken)
    materials = doc.setdefault("materials", [])
    materials.append({"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": [DEFAULT_SURFACE_ALBEDO] * 3 + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    for primitive in primitives:
        primitive["material"] = len(materials) - 1


def quote_file_uris(doc):
    """Blender's glTF exporter writes its buffer's file name as the URI as it is, where a
    URI escapes '%', spaces and other characters (and the loader decodes them): a scene
    named 'a%20b.gltf' would refer to 'a b.bin'."""
    for buffer in doc.get("buffers", []):
        uri = buffer.get("uri")
        if isinstance(uri, str) and not uri.startswith("data:"):
            buffer["uri"] = urllib.parse.quote(uri)


def set_surfaces(doc, warnings):
    """Surfaces as Cycles shades them where the exporter reads only Principled BSDF: a
    Diffuse BSDF is Lambertian with its Color; an Emission shader emits Color x Strength
    and reflects nothing. Every surface is double-sided: Cycles shades and emits on both
    sides whatever a material's Backface Culling (a setting of the viewport and Eevee),
    which the exporter writes as glTF's doubleSided, one-sided emission for vkdiffrender."""
    for material in doc.get("materials", []):
        blender_material = bpy.data.materials.get(material.get("name", ""))
        if blender_material is not None:
            material["doubleSided"] = True
        node = node_graph.surface_node(blender_material)
        if node is None:
            continue
        what = f"material '{blender_material.name}'"
        pbr = material.setdefault("pbrMetallicRoughness", {})
        # A Color the exporter wrote as a texture, or as vertex colours, is that times a
        # factor of 1.
        textured = {"Color": (1.0, 1.0, 1.0, 1.0)}
        # Whether the exporter carried the base colour as a texture or as vertex colours.
        carried = "baseColorTexture" in pbr or vertex_colours.attribute_read(blender_material) is not None
        if node.bl_idname in {"ShaderNodeBsdfDiffuse", "ShaderNodeEmission"}:
            # glTF's metallicFactor defaults to 1: without it Blender's importer, and
            # any other glTF viewer, would read these surfaces back as rough metal.
            pbr["metallicFactor"] = 0.0
            pbr["roughnessFactor"] = 1.0
        if node.bl_idname == "ShaderNodeBsdfDiffuse":
            albedo = mappings.base_color_to_albedo(node_graph.constant(
                node, "Color", warnings, what, textured if carried else None))
            pbr["baseColorFactor"] = [*albedo, 1.0]
            if node.inputs["Roughness"].default_value > 0.0 or node_graph.is_fed(node.inputs["Roughness"]):
                warnings.append(f"{what}: Diffuse BSDF roughness (Oren-Nayar) is exported as Lambertian")
        elif node.bl_idname == "ShaderNodeEmission":
            radiance = non_negative(mappings.emission_to_radiance(
                node_graph.constant(node, "Color", warnings, what, textured if "emissiveTexture" in material else None),
                node_graph.constant(node, "Strength", warnings, what)), what, "its Emission (Color x Strength)")
            emission = mappings.radiance_to_emission(radiance)
            pbr["baseColorFactor"] = [0.0, 0.0, 0.0, 1.0]
            material["emissiveFactor"] = list(emission["color"])
            material.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {
                "emissiveStrength": emission["strength"]}
            gltf_json.use_extension(doc, "KHR_materials_emissive_strength")
        elif node.bl_idname == "ShaderNodeBsdfPrincipled":
            warnings.append(f"{what}: Principled BSDF is exported as a Lambertian of its Base Color; Cycles adds "
                            f"its specular lobe (Specular {node.inputs['Specular'].default_value:g}) and a "
                            f"retro-reflective diffuse")
            if not carried and node_graph.is_fed(node.inputs["Base Color"]):
                # The glTF exporter writes no factor for a Base Color it cannot read (a
                # procedural texture): white, where the unlinked value is what the
                # Diffuse BSDF's export uses too.
                albedo = mappings.base_color_to_albedo(node_graph.constant(node, "Base Color", warnings, what))
                pbr["baseColorFactor"] = [*albedo, 1.0]
            # The exporter writes KHR_materials_ior for any Specular but 0.5, which the loader
            # reads only with a transmission.
            extensions = material.get("extensions", {})
            for name in TRANSMISSION_EXTENSIONS:
                extensions.pop(name, None)
            if node.inputs["Transmission"].default_value > 0.0 or node_graph.is_fed(node.inputs["Transmission"]):
                warnings.append(f"{what}: Transmission is exported as an opaque surface (vkdiffrender does not "
                                f"refract)")
            colour = node.inputs["Emission"]
            non_negative(mappings.emission_to_radiance(
                (1.0, 1.0, 1.0) if node_graph.is_fed(colour) else colour.default_value,
                node.inputs["Emission Strength"].default_value), what, "its Emission x Emission Strength")
            if node.inputs["Alpha"].default_value < 1.0 or node_graph.is_fed(node.inputs["Alpha"]):
                warnings.append(f"{what}: Alpha below 1 is exported as an opaque surface (vkdiffrender ignores "
                                f"alpha)")
        else:
            warnings.append(f"{what}: surface shader {node.bl_idname} is exported as the glTF exporter reads it")


def add_world(doc, scene, warnings):
    """The World's volume fills the scene; its constant Background is the radiance of
    escaping rays."""
    world = scene.world
    if world is None:
        return
    if not world.use_nodes:
        if max(world.color) > 0.0:  # what Cycles renders for a World without nodes
            doc.setdefault("extensions", {})["VKDR_background"] = {"radiance": list(world.color)}
        return
    medium = node_graph.medium_of(world, warnings, f"world '{world.name}'")
    if medium is not None:
        doc.setdefault("extensions", {})[EXTENSION] = {"name": node_graph.world_medium_name(world),
                                                       **medium_json(medium)}
        warn_camera_clipping(scene, medium, warnings)
    out = node_graph.owner_output(world)
    background = node_graph.linked_node(out.inputs["Surface"]) if out else None
    if background is not None and background.bl_idname == "ShaderNodeBackground":
        radiance = non_negative(mappings.emission_to_radiance(
            node_graph.constant(background, "Color", warnings, f"world '{world.name}'"),
            node_graph.constant(background, "Strength", warnings, f"world '{world.name}'")),
            f"world '{world.name}'", "its Background (Color x Strength)")
        if max(radiance) > 0.0:
            doc.setdefault("extensions", {})["VKDR_background"] = {"radiance": list(radiance)}
    elif background is not None:
        warnings.append(f"world '{world.name}': its Surface is a {background.bl_idname}, not a Background node; "
                        f"exported without a background (black)")


def warn_camera_clipping(scene, medium, warnings):
    """Cycles starts camera rays at the camera's Clip Start and ends them at Clip End, so
    the World volume nearer than Clip Start is not there for it; vkdiffrender's camera rays
    start at the camera (an orthographic camera's at its plane). The warning gives the
    transmittance of the skipped stretch on the view axis (a perspective camera's longer,
    so darker, off axis)."""
    sigma_t = max(a + s for a, s in zip(medium.sigma_a, medium.sigma_s))
    for obj in scene.objects:
        if obj.type != "CAMERA" or obj.data.clip_start * sigma_t < 1e-3:
            continue
        darker = 1.0 - math.exp(-sigma_t * obj.data.clip_start)
        warnings.append(f"camera '{obj.name}': Cycles starts camera rays at Clip Start "
                        f"({obj.data.clip_start:g}), skipping the World volume in front of the lens, which "
                        f"vkdiffrender renders ({100 * darker:.2g} % darker on the view axis); set Clip Start "
                        f"near 0 for Cycles renders that vkdiffrender should match")


def set_punctual_lights(doc, warnings):
    """Replace the exporter's photometric intensities by Cycles' radiometric ones."""
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    for node in doc.get("nodes", []):
        index = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        if index is None:
            continue
        # bpy.data rather than the scene's objects: a lamp instanced from a collection is
        # not in the scene, and every instance has the same light data. A linked library's
        # objects may share a name with this file's.
        named = [o for o in bpy.data.objects if o.name == node.get("name") and o.type == "LIGHT"]
        obj = named[0] if named else None
        if len({o.data for o in named}) > 1:
            warnings.append(f"light '{node.get('name')}': several lights have this name (from linked libraries); "
                            f"the export cannot tell them apart and gives each the power of one: rename them")
        if obj is None:
            warnings.append(f"light node '{node.get('name')}': no Blender light of that name; its intensity is "
                            f"left as the glTF exporter wrote it (photometric units, not Cycles' watts)")
            continue
        warn_light_nodes(obj, warnings)
        light, entry = obj.data, lights[index]
        entry["color"] = list(light.color)
        if light.type == "SUN":
            entry["intensity"] = light.energy
            if light.angle > 0.0:
                warnings.append(f"light '{obj.name}': a sun of angle {math.degrees(light.angle):.2f} deg "
                                f"is exported as a directional light (angle 0)")
            continue
        entry["intensity"] = light.energy / (4.0 * math.pi)
        if light.shadow_soft_size > 0.0:
            warnings.append(f"light '{obj.name}': radius {light.shadow_soft_size:g} is exported as a point "
                            f"(same intensity, hard shadows)")
        if light.type == "SPOT":
            outer, inner = mappings.spot_cone_angles(light.spot_size, light.spot_blend)
            entry["spot"] = {"outerConeAngle": outer, "innerConeAngle": inner}
            warnings.append(f"light '{obj.name}': Cycles' spot falloff (a smoothstep times the cosine to "
                            f"the axis) differs from glTF's; exported with the same cone angles")


def warn_light_nodes(obj, warnings):
    """Cycles scales a light by its node tree (an Emission's Strength x Color); the export
    reads the light's Power and Color alone, so it warns where the tree changes them."""
    tree = obj.data.node_tree if obj.data.use_nodes else None
    if tree is None:
        return
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputLight"]
    shader = node_graph.linked_node(outputs[0].inputs["Surface"]) if outputs else None
    if shader is not None and shader.bl_idname == "ShaderNodeEmission" and not any(
            node_graph.is_fed(socket) for socket in shader.inputs) and \
            shader.inputs["Strength"].default_value == 1.0 and \
            tuple(shader.inputs["Color"].default_value[:3]) == (1.0, 1.0, 1.0):
        return
    warnings.append(f"light '{obj.name}': its shader nodes are not read (they change what Cycles emits); "
                    f"exported with its Power and Color alone")


def area_light_polygon(obj, matrix_world=None):
    """World-space corners of an area light placed by MATRIX_WORLD (by default its own),
    ordered counter-clockwise seen from its emitting side, local -Z, also when the
    matrix mirrors it."""
    matrix_world = obj.matrix_world if matrix_world is None else matrix_world
    light = obj.data
    sx = light.size
    sy = light.size_y if light.shape in {"RECTANGLE", "ELLIPSE"} else light.size
    if light.shape in {"DISK", "ELLIPSE"}:
        n = 64
        local = [(0.5 * sx * math.cos(-2 * math.pi * i / n), 0.5 * sy * math.sin(-2 * math.pi * i / n), 0.0)
                 for i in range(n)]
    else:
        local = [(-0.5 * sx, -0.5 * sy, 0.0), (-0.5 * sx, 0.5 * sy, 0.0), (0.5 * sx, 0.5 * sy, 0.0),
                 (0.5 * sx, -0.5 * sy, 0.0)]
    if matrix_world.to_3x3().determinant() < 0.0:
        local.reverse()
    return [tuple(matrix_world @ mathutils.Vector(p)) for p in local]


def polygon_area(points):
    a = [0.0, 0.0, 0.0]
    for p, q in zip(points, points[1:] + points[:1]):
        a[0] += p[1] * q[2] - p[2] * q[1]
        a[1] += p[2] * q[0] - p[0] * q[2]
        a[2] += p[0] * q[1] - p[1] * q[0]
    return 0.5 * math.sqrt(sum(c * c for c in a))


def area_light_material_name(name):
    """The emitter's name for the area light rendered as NAME (rendered_objects)."""
    return f"{name}.area"


def is_portal(light):
    """A Cycles light portal: it guides the sampling of the sky through a window and
    emits nothing, nor blocks anything."""
    return bool(getattr(getattr(light, "cycles", None), "is_portal", False))


def emitting_area_light(obj):
    """Whether OBJ is an area light that emits: one the export writes as an emitter."""
    return obj.type == "LIGHT" and obj.data.type == "AREA" and not is_portal(obj.data)


def add_area_lights(doc, view_layer, warnings):
    """Area lights, which the glTF exporter drops, become one-sided emissive polygons of
    Cycles' radiance Power / (4 area), black so that they reflect nothing; one for each
    place a render shows the light (rendered_objects)."""
    for rendered in rendered_objects(view_layer):
        obj = rendered.object
        if obj.type != "LIGHT" or obj.data.type != "AREA":
            continue
        if is_portal(obj.data):
            warnings.append(f"light '{obj.name}': a light portal is not exported (vkdiffrender has no portals, and "
                            f"samples the background without them)")
            continue
        light = obj.data
        if light.spread < math.pi - 1e-6:
            warnings.append(f"light '{obj.name}': spread {math.degrees(light.spread):.0f} deg is exported as 180")
        warn_light_nodes(obj, warnings)
        corners = [blender_to_gltf(p) for p in area_light_polygon(obj, rendered.matrix_world)]
        area = polygon_area(corners)
        if not area > 0.0:
            raise ExportError(f"light '{obj.name}': an area light of no area (size {light.size:g}, scale "
                              f"{tuple(round(v, 6) for v in rendered.matrix_world.to_scale())}); give it a size")
        emitter = area_light_material_name(rendered.name)
        if any(m.get("name") == emitter for m in doc.get("materials", [])):
            raise ExportError(f"light '{obj.name}': its emitter's material would be named '{emitter}', which a "
                              f"material of the scene is named already; rename one of them")
        radiance = mappings.area_light_radiance(light.color, light.energy, area)
        emission = mappings.radiance_to_emission(radiance)
        material = {"name": area_light_material_name(rendered.name), "doubleSided": False,
                    "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0,
                                             "roughnessFactor": 1.0},
                    "emissiveFactor": list(emission["color"]),
                    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": emission["strength"]}}}
        triangles = [(0, i, i + 1) for i in range(1, len(corners) - 1)]
        gltf_json.add_mesh_node(doc, area_light_material_name(rendered.name), corners, triangles, material)
        gltf_json.use_extension(doc, "KHR_materials_emissive_strength")


def warn_film_settings(scene, warnings):
    """What Cycles' film does to its image that vkdiffrender's does not."""
    cycles = getattr(scene, "cycles", None)
    exposure = getattr(cycles, "film_exposure", 1.0)
    if exposure != 1.0:
        warnings.append(f"Cycles' film Exposure {exposure:g} scales its render by {exposure:g}, and vkdiffrender's "
                        f"is not scaled: set it to 1 for Cycles renders that vkdiffrender should match")
    if scene.render.film_transparent:
        warnings.append("Cycles' film Transparent renders the background as transparent black, and vkdiffrender "
                        "renders the World there: turn it off for Cycles renders that vkdiffrender should match")


def object_vertices(obj, depsgraph):
    """The vertices of `obj` as the render has them (modifiers applied), in its own space:
    an n x 3 array."""
    evaluated = obj.evaluated_get(depsgraph)
    try:
        mesh = evaluated.to_mesh()
    except RuntimeError:
        return numpy.zeros((0, 3))
    try:
        vertices = numpy.empty(3 * len(mesh.vertices), dtype=numpy.float32)
        mesh.vertices.foreach_get("co", vertices)
    finally:
        evaluated.to_mesh_clear()
    return vertices.reshape(-1, 3).astype(numpy.float64)


# Camera rays cast across the view per side to find what it shows beyond Clip End.
CLIP_PROBES = 48


def clipped_objects(scene, view_layer):
    """The rendered objects in the scene camera's view nearer than its Clip Start or
    farther than its Clip End, which Cycles' camera rays do not reach: ([names nearer],
    [names farther]). Nearer: any vertex in view (nothing nearer can hide it). Farther:
    the first hits of a grid of camera rays from Clip Start on (a wall hides what lies
    behind it)."""
    camera = scene.camera
    data = camera.data
    # Cycles' camera rays take the camera object's place and orientation, not its scale.
    location, orientation, _ = camera.matrix_world.decompose()
    to_world = mathutils.Matrix.Translation(location) @ orientation.to_matrix().to_4x4()
    to_camera = to_world.inverted()
    frame = [mathutils.Vector(corner) for corner in data.view_frame(scene=scene)]
    half_x, half_y = max(abs(c.x) for c in frame), max(abs(c.y) for c in frame)
    perspective = data.type == "PERSP"
    depth_of_frame = abs(frame[0].z) if perspective else 1.0
    depsgraph = bpy.context.evaluated_depsgraph_get()
    names = {}  # each rendered object's name, as the warnings give it
    nearer = {}
    for rendered in rendered_objects(view_layer):
        obj = rendered.object
        if obj.type not in EXPORTED_GEOMETRY:
            continue
        names.setdefault(obj, rendered.name)
        placement = numpy.array(to_camera @ rendered.matrix_world)
        box_depth = -(numpy.array([tuple(corner) for corner in obj.bound_box]) @ placement[2, :3] + placement[2, 3])
        if box_depth.min() >= data.clip_start or box_depth.max() <= 0.0:
            continue  # wholly beyond Clip Start, or behind the camera
        p = object_vertices(obj, depsgraph) @ placement[:3, :3].T + placement[:3, 3]
        depth = -p[:, 2]
        reach = depth / depth_of_frame if perspective else 1.0
        in_view = (depth > 0.0) & (numpy.abs(p[:, 0]) <= half_x * reach) & (numpy.abs(p[:, 1]) <= half_y * reach)
        if numpy.any(in_view & (depth < data.clip_start)):
            nearer[rendered.name] = None
    farther = {}
    for i, j in itertools.product(range(CLIP_PROBES), repeat=2):
        x = half_x * (2.0 * (i + 0.5) / CLIP_PROBES - 1.0)
        y = half_y * (2.0 * (j + 0.5) / CLIP_PROBES - 1.0)
        # From Clip Start on, as Cycles' rays: what lies nearer does not hide what they meet.
        if perspective:
            start = to_world @ (mathutils.Vector((x, y, -depth_of_frame)) * (data.clip_start / depth_of_frame))
            direction = to_world.to_3x3() @ mathutils.Vector((x, y, -depth_of_frame))
        else:
            start = to_world @ mathutils.Vector((x, y, -data.clip_start))
            direction = to_world.to_3x3() @ mathutils.Vector((0.0, 0.0, -1.0))
        hit, point, _, _, obj, _ = scene.ray_cast(depsgraph, start, direction.normalized())
        # The viewport's objects, which the ray meets, may differ from the render's.
        if hit and obj.original in names and -(to_camera @ point).z > data.clip_end:
            farther[names[obj.original]] = None
    return sorted(nearer), sorted(farther)


def warn_camera_clipping_of_objects(scene, view_layer, warnings):
    """Cycles starts and ends camera rays at Clip Start and Clip End; vkdiffrender's start
    at the camera and do not end."""
    nearer, farther = clipped_objects(scene, view_layer)
    data = scene.camera.data

    def objects(names):
        return ("object " if len(names) == 1 else "objects ") + ", ".join(f"'{name}'" for name in names)

    if nearer:
        warnings.append(f"camera '{scene.camera.name}': {objects(nearer)} in view nearer than its Clip Start "
                        f"({data.clip_start:g}), where Cycles renders nothing and vkdiffrender renders them: "
                        f"lower Clip Start for Cycles renders that vkdiffrender should match")
    if farther:
        warnings.append(f"camera '{scene.camera.name}': {objects(farther)} in view beyond its Clip End "
                        f"({data.clip_end:g}), where Cycles renders nothing and vkdiffrender renders them: "
                        f"raise Clip End for Cycles renders that vkdiffrender should match")


def warn_bounce_limits(scene, warnings):
    """vkdiffrender has one limit on scattering vertices (--max-depth, which the Fit sets
    to Max Bounces + 1); Cycles also stops a path at its per-kind limits, and its default
    Volume bounces 0 leaves fog single-scattered."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None:
        return
    lower = {label: getattr(cycles, name) for label, name in
             (("Diffuse", "diffuse_bounces"), ("Glossy", "glossy_bounces"), ("Volume", "volume_bounces"))
             if getattr(cycles, name) < cycles.max_bounces}
    if lower:
        limits = ", ".join(f"{label} {value}" for label, value in lower.items())
        warnings.append(f"Cycles' bounce limits {limits} are below Max Bounces {cycles.max_bounces}; vkdiffrender "
                        f"has only the total (max depth {cycles.max_bounces + 1}): set them to Max Bounces for "
                        f"Cycles renders that vkdiffrender should match")


def checked_output_path(filepath):
    """FILEPATH made absolute (a '//' path is relative to the .blend), or ExportError where
    it cannot be written without harm: a directory, a symbolic link (whose target would
    be left holding the glTF exporter's own output), a directory that does not exist, a
    name that does not end in .gltf."""
    if filepath.startswith("//") and not bpy.data.filepath:
        raise ExportError(f"{filepath}: a path relative to the .blend file, which has not been saved")
    path = os.path.abspath(bpy.path.abspath(filepath))
    if os.path.islink(path):
        raise ExportError(f"{path}: is a symbolic link; export to the file it points to instead")
    if os.path.isdir(path):
        raise ExportError(f"{path}: is a directory")
    if not os.path.isdir(os.path.dirname(path)):
        raise ExportError(f"{os.path.dirname(path)}: the directory does not exist")
    if not path.lower().endswith(".gltf"):
        raise ExportError(f"{path}: the export writes a .gltf with a .bin beside it; give a path ending in .gltf")
    return path


def exported_cameras(scene, view_layer):
    """The camera objects the export writes: those the render shows, and the scene camera,
    of a type vkdiffrender renders through (the glTF exporter leaves panoramic ones out)."""
    shown = [r.object for r in rendered_objects(view_layer) if r.object.type == "CAMERA"]
    if scene.camera is not None and scene.camera.type == "CAMERA" and scene.camera not in shown:
        shown.append(scene.camera)
    return [camera for camera in dict.fromkeys(shown) if camera.data.type in RENDERED_CAMERAS]


def check_cameras(scene, view_layer, warnings):
    """vkdiffrender renders perspective and orthographic cameras, without depth of field or
    lens shift, and the first camera of the file unless told another (`--camera`)."""
    cameras = [r.object for r in rendered_objects(view_layer) if r.object.type == "CAMERA"]
    if scene.camera is None or scene.camera.type != "CAMERA":
        raise ExportError("the scene has no camera; vkdiffrender renders through a perspective or orthographic "
                          "camera")
    if scene.camera.data.type not in RENDERED_CAMERAS:
        raise ExportError(f"camera '{scene.camera.name}': {scene.camera.data.type.lower()} cameras are not "
                          f"supported; vkdiffrender renders through a perspective or orthographic camera")
    for camera in cameras:
        if camera.data.type not in RENDERED_CAMERAS:
            warnings.append(f"camera '{camera.name}': {camera.data.type.lower()} cameras are not supported; "
                            f"Blender's glTF exporter leaves it out")
        if camera.data.dof.use_dof:
            warnings.append(f"camera '{camera.name}': depth of field is exported as a pinhole (all in focus)")
        if camera.data.shift_x != 0.0 or camera.data.shift_y != 0.0:
            warnings.append(f"camera '{camera.name}': lens shift is not exported (the view is centred)")
    render = scene.render
    if render.pixel_aspect_x != render.pixel_aspect_y:
        scale = render.resolution_percentage / 100.0
        width = round(render.resolution_x * scale * render.pixel_aspect_x / render.pixel_aspect_y)
        warnings.append(f"the render's pixels are not square (Pixel Aspect {render.pixel_aspect_x:g} x "
                        f"{render.pixel_aspect_y:g}); vkdiffrender's are, and it frames the view to --width and "
                        f"--height: render {width} x {round(render.resolution_y * scale)} for Cycles' view")
    exported = exported_cameras(scene, view_layer)
    if len(exported) > 1:
        warnings.append(f"the scene has {len(exported)} cameras; vkdiffrender renders the first in the file unless "
                        f"given `--camera NAME` (the scene camera is '{scene.camera.name}')")


def set_orthographic_views(doc, scene):
    """Blender's glTF exporter spans an orthographic camera's Orthographic Scale over the
    image's longer side, as Sensor Fit Auto does; Cycles spans it over the side Sensor Fit
    names. xmag and ymag are half the view's width and height."""
    render = scene.render
    width, height = render.resolution_x * render.pixel_aspect_x, render.resolution_y * render.pixel_aspect_y
    for entry in doc.get("cameras", []):
        camera = bpy.data.cameras.get(entry.get("name", ""))
        if entry.get("type") != "orthographic" or camera is None:
            continue
        entry["orthographic"]["xmag"], entry["orthographic"]["ymag"] = mappings.orthographic_half_extents(
            camera.ortho_scale, camera.sensor_fit, width, height)


def check_values(scene, view_layer, warnings):
    """ExportError naming the light, or the material or World and the node input, of a
    value that is not a finite number, before the glTF exporter meets it; a warning for
    an image texture whose file is missing."""
    materials = set()
    for rendered in rendered_objects(view_layer):
        obj = rendered.object
        if obj.type == "LIGHT":
            name = scene_checks.non_finite_light_value(obj.data)
            if name is not None:
                raise ExportError(f"light '{obj.name}': its {name} is not a finite number")
            if not is_portal(obj.data):
                non_negative((obj.data.energy,), f"light '{obj.name}'", "its Power (a sun's Strength)")
        materials.update(slot.material for slot in getattr(obj, "material_slots", []) if slot.material is not None)
    owners = [(m, f"material '{m.name}'") for m in sorted(materials, key=lambda m: m.name)]
    if scene.world is not None:
        owners.append((scene.world, f"world '{scene.world.name}'"))
    for owner, what in owners:
        found = scene_checks.non_finite_node_input(owner)
        if found is not None:
            raise ExportError(f"{what}: input '{found[1]}' of node '{found[0]}' is not a finite number")
        for image, path in scene_checks.missing_images(owner):
            warnings.append(f"{what}: image '{image}' is not packed and {path} is no file; exported without it "
                            f"(Cycles renders it magenta)")


def export_scene(context, filepath):
    """Writes FILEPATH (.gltf, with its .bin beside it) for vkdiffrender; returns the
    warnings. Raises ExportError, before writing anything, for a scene or path that
    cannot give a scene vkdiffrender loads."""
    scene = context.scene
    view_layer = context.view_layer
    filepath = checked_output_path(filepath)
    warnings = []
    check_cameras(scene, view_layer, warnings)
    check_values(scene, view_layer, warnings)
    # Every file is written into a staging folder beside FILEPATH and moved in only once
    # the whole scene is complete: a failure leaves the previous export as it was.
    directory = os.path.dirname(filepath)
    staging = tempfile.mkdtemp(prefix=".vkdiffrender-export-", dir=directory)
    try:
        staged = os.path.join(staging, os.path.basename(filepath))
        with modifiers_as_rendered(scene):
            colours = vertex_colours.colour_exports([r.object for r in rendered_objects(view_layer)],
                                                    vertex_colours.reading_materials(), warnings)
            beyond = vertex_colours.first_value_outside_unit_range(colours)
            if beyond is not None:
                raise ExportError(beyond)
            with renders_as_cycles(scene, view_layer), vertex_colours.attributes_read_as_render(colours), \
                    corner_colours.read_at_each_corner():
                run_gltf_exporter(staged, colours=bool(colours))
            with open(staged, encoding="utf-8") as f:
                doc = json.load(f)
            vertex_colours.keep_only_where_read(doc, colours)
            set_surfaces(doc, warnings)
            set_orthographic_views(doc, scene)
            texture_lookups.warn_texture_lookups(doc, warnings)
            add_material_media(doc, view_layer, warnings)
            add_world(doc, scene, warnings)
            set_punctual_lights(doc, warnings)
            add_area_lights(doc, view_layer, warnings)
            grid_media.add_grid_media(doc, scene, view_layer, staged, warnings)
            add_default_surface(doc)
            quote_file_uris(doc)
            warn_bounce_limits(scene, warnings)
            warn_film_settings(scene, warnings)
            warn_camera_clipping_of_objects(scene, view_layer, warnings)
            warn_render_differences(view_layer, warnings)
            warn_added_volumes(scene, view_layer, warnings)
        if EXTENSION in json.dumps(doc):
            gltf_json.use_extension(doc, EXTENSION)
        if "VKDR_background" in doc.get("extensions", {}):
            gltf_json.use_extension(doc, "VKDR_background")
        gltf_json.drop_unused_extensions(doc)
        non_finite = export_checks.first_non_finite(doc)
        if non_finite is not None:  # what the checks above do not reach; no glTF reader parses it
            raise ExportError(f"{non_finite}{export_checks.owner_of(doc, non_finite)}: not a finite number")
        beyond = export_checks.first_beyond_emission_limit(doc)
        if beyond is not None:
            path, value = beyond
            raise ExportError(f"{path}{export_checks.owner_of(doc, path)}: emits {value:g} in its brightest channel, "
                              f"more than the {export_checks.MAX_EMISSION:g} vkdiffrender takes")
        gltf_json.write_atomically(staged, doc, mode_of=filepath)
        taken = export_checks.files_it_would_replace(staging, directory, os.path.basename(filepath))
        if taken:
            raise ExportError(f"{', '.join(taken)}: in {directory} already, not written by an export of "
                              f"{os.path.basename(filepath)} there; the export would replace "
                              f"{'it' if len(taken) == 1 else 'them'}: move {'it' if len(taken) == 1 else 'them'}, "
                              f"or export to another folder")
        names = sorted(os.listdir(staging), key=lambda name: name == os.path.basename(filepath))
        for name in names:  # the .gltf last, once what it refers to is in place
            os.replace(os.path.join(staging, name), os.path.join(directory, name))
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return list(dict.fromkeys(warnings))  # once each, though every instance of a lamp finds the same


class EXPORT_OT_vkdiffrender(bpy.types.Operator, ExportHelper):
    """Export the scene for vkdiffrender: glTF with media, lights in Cycles' units, area lights as emitters"""
    bl_idname = "export_scene.vkdiffrender"
    bl_label = "Export vkdiffrender"
    filename_ext = ".gltf"
    filter_glob: StringProperty(default="*.gltf", options={"HIDDEN"})

    def execute(self, context):
        try:
            warnings = export_scene(context, self.filepath)
        except (ExportError, OSError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        except Exception as error:  # a Blender setup the export does not know: a message, not a traceback
            self.report({"ERROR"}, f"the export failed on what it does not handle ({type(error).__name__}: {error}); "
                                   f"nothing was written")
            return {"CANCELLED"}
        for warning in warnings:
            self.report({"WARNING"}, warning)
        self.report({"INFO"}, f"wrote {os.path.basename(self.filepath)}")
        return {"FINISHED"}


def menu_entry(self, context):
    self.layout.operator(EXPORT_OT_vkdiffrender.bl_idname, text="vkdiffrender (.gltf)")
