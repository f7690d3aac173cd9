"""Grid media: Volume objects (an OpenVDB file, such as an imported smoke cache) and
smoke simulation domains (a Fluid modifier of type Domain) become media whose density,
albedo and emission grids are the file's, copied beside the scene (a scene reads only
files in its own directory)."""
import os
import re
import shutil
import urllib.parse

import bpy
import mathutils

from . import gltf_json, mappings, node_graph
from .axes import Z_UP_TO_Y_UP, blender_to_gltf
from .gltf_json import EXTENSION, medium_json
from .rendered_objects import rendered_objects

# A box's corners (x fastest, then y, then z) and its 12 triangles wound counter-clockwise
# seen from outside, so that their normals point out of the medium.
BOX_TRIANGLES = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
                 (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]


def object_box(obj):
    """The lowest and highest corners of OBJ's box in its own space."""
    corners = [mathutils.Vector(c) for c in obj.bound_box]
    return (mathutils.Vector([min(c[i] for c in corners) for i in range(3)]),
            mathutils.Vector([max(c[i] for c in corners) for i in range(3)]))


def volume_box(obj, matrix_world):
    """World-space corners of the object-space box around a volume object's grids, placed
    by MATRIX_WORLD, grown by a voxel on every side so that the density's trilinear
    fade-out lies inside."""
    low, high = object_box(obj)
    voxel = max((max(grid.matrix_object.col[i].xyz.length for i in range(3)) for grid in obj.data.grids),
                default=0.0)
    low -= mathutils.Vector((voxel, voxel, voxel))
    high += mathutils.Vector((voxel, voxel, voxel))
    box = [mathutils.Vector((high.x if i & 1 else low.x, high.y if i & 2 else low.y, high.z if i & 4 else low.z))
           for i in range(8)]
    return [tuple(matrix_world @ c) for c in box]


def volume_grid_attributes(node, volume, what, warnings):
    """The grids a Volume object's Principled Volume reads: the one its Density Attribute
    names (the density; `density` for other volume nodes), the one its Color Attribute
    names (an albedo grid: Cycles multiplies Color by it) and the scalar grid an Attribute
    node feeding Emission Strength names (an emission grid). Returns (density grid, albedo
    grid or None, emission grid or None, constant() overrides)."""
    if node is None or node.bl_idname != "ShaderNodeVolumePrincipled":
        return "density", None, None, {}
    density = node.inputs["Density Attribute"].default_value
    albedo = node.inputs["Color Attribute"].default_value
    if albedo not in volume.grids:
        albedo = None  # Cycles ignores an attribute the volume lacks (or none named)
    elif max(node.inputs["Absorption Color"].default_value[:3]) > 0.0:
        warnings.append(f"{what}: '{node.name}' Color Attribute with an Absorption Color other than black: "
                        f"vkdiffrender's albedo grid scatters Color x attribute and absorbs the rest, which "
                        f"differs from Cycles where the attribute is below 1")
    emission = node_graph.attribute_input(node, "Emission Strength")
    if emission is None:
        return density, albedo, None, {}
    if emission not in volume.grids:
        return density, albedo, None, {"Emission Strength": 0.0}  # a missing attribute reads 0 in Cycles
    if volume.grids[emission].channels != 1:
        warnings.append(f"{what}: Emission Strength reads the vector grid '{emission}', and an emission grid "
                        f"must be scalar; the input's unlinked value is used")
        return density, albedo, None, {"Emission Strength": node.inputs["Emission Strength"].default_value}
    return density, albedo, emission, {"Emission Strength": 1.0}


def volume_file_name(stem, object_name, taken):
    """A name for the copy of a volume's file beside the scene: the object's name with
    what file names should not hold replaced, made unique among TAKEN (names compared
    without case, as some file systems do)."""
    base = f"{stem}.{re.sub(r'[^A-Za-z0-9_.-]', '_', object_name)}"
    name, number = f"{base}.vdb", 1
    while name.lower() in taken:
        number += 1
        name = f"{base}.{number}.vdb"
    taken.add(name.lower())
    return name


class GridCopies:
    """Where the grid files go: beside the scene file, under names of their own, one copy
    of each file however many objects (instances of one cloud, say) read it."""

    def __init__(self, filepath):
        self.directory = os.path.dirname(os.path.abspath(filepath))
        self.stem = os.path.splitext(os.path.basename(filepath))[0]
        self.taken = set()
        self.copied = {}  # the source's real path: its copy's name

    def copy(self, source, object_name):
        key = os.path.realpath(source)
        if key not in self.copied:
            name = volume_file_name(self.stem, object_name, self.taken)
            shutil.copyfile(source, os.path.join(self.directory, name))
            self.copied[key] = name
        return self.copied[key]


def grid_medium(doc, material, volume, placement, name, copies, what, warnings):
    """The medium entry of MATERIAL's volume reading the grids of VOLUME (a bpy Volume whose
    grids are loaded from one file), which is copied beside the scene, placed by a node of
    world matrix PLACEMENT (Blender's Z up) named `<name>.grid`; None where the material
    has no volume the export can read (warned)."""
    node = node_graph.material_volume_node(material)
    grid, albedo, emission, overrides = volume_grid_attributes(node, volume, what, warnings)
    medium = node_graph.medium_of(material, warnings, what, overrides)
    if medium is None:
        warnings.append(f"{what}: has no volume material that vkdiffrender can read; skipped")
        return None
    if node is None or node.bl_idname != "ShaderNodeVolumePrincipled":
        kind = node.bl_idname if node is not None else "a combination of volume shaders"
        warnings.append(f"{what}: its volume is {kind}, which Cycles does not multiply by the '{grid}' grid "
                        f"as the export does; use one Principled Volume (its Density Attribute) for the two to "
                        f"render the same")
    source = bpy.path.abspath(volume.grids.frame_filepath)
    if not os.path.isfile(source) or grid not in volume.grids:
        warnings.append(f"{what}: no grid '{grid}' in a file on disk (a volume generated in memory, or a "
                        f"Density Attribute the file lacks); skipped")
        return None
    if volume.grids[grid].channels != 1:
        warnings.append(f"{what}: its density reads the vector grid '{grid}', and a density grid must be scalar; "
                        f"skipped (name a scalar grid in the Principled Volume's Density Attribute)")
        return None
    copy = copies.copy(source, name)
    matrix = Z_UP_TO_Y_UP @ placement
    nodes = doc.setdefault("nodes", [])
    nodes.append({"name": name + ".grid", "matrix": [matrix[row][column] for column in range(4) for row in range(4)]})
    entry = medium_json(medium)
    reference = {"uri": urllib.parse.quote(copy), "node": len(nodes) - 1}
    entry["density"] = {**reference, "grid": grid}
    if albedo is not None:
        entry["albedoGrid"] = {**reference, "grid": albedo}
    if emission is not None and "emission" in entry:
        entry["emissionGrid"] = {**reference, "grid": emission}
    elif "emission" in entry:
        warnings.append(f"{what}: a constant Emission Strength, which Cycles emits evenly over the volume; "
                        f"vkdiffrender emits it times the '{grid}' grid, so where that is below 1 the export glows "
                        f"less; feed Emission Strength from a grid attribute for the two to agree")
    return entry


def is_flattening(matrix):
    """Whether MATRIX maps a voxel to nothing or to nearly a plane, by vkdiffrender's rule
    for a grid's placement (docs/density-grids.md): its unit axes span less than 1e-6."""
    axes = [matrix.col[i].xyz for i in range(3)]
    if any(axis.length == 0.0 for axis in axes):
        return True
    units = [axis.normalized() for axis in axes]
    return abs(units[0].dot(units[1].cross(units[2]))) < 1e-6


def add_volume_objects(doc, view_layer, copies, warnings):
    """Volume objects become media: a box around their grids as the boundary, the grids
    their material reads (grid_medium), placed by the object's transform (the file's own
    transform inside it, as in Blender)."""
    for rendered in rendered_objects(view_layer):
        obj = rendered.object
        if obj.type != "VOLUME":
            continue
        what = f"volume '{rendered.name}'"
        volume = obj.data
        if not volume.grids.load():
            warnings.append(f"{what}: its grids do not load ({volume.grids.error_message}); skipped")
            continue
        for modifier in obj.modifiers:
            if modifier.show_render:
                warnings.append(f"{what}: its modifier '{modifier.name}' ({modifier.type}) is not applied, which "
                                f"Cycles renders; the grids are exported as the file holds them, where the object "
                                f"places them")
        if is_flattening(rendered.matrix_world):
            warnings.append(f"{what}: its transform flattens it (a scale of 0, or axes nearly in one plane), so "
                            f"that it has no volume, and Cycles renders nothing of it; skipped")
            continue
        material = obj.active_material
        entry = grid_medium(doc, material, volume, rendered.matrix_world, rendered.name, copies, what, warnings)
        if entry is None:
            continue
        names = {m.get("name") for m in doc.get("materials", [])}
        name = material.name if material.name not in names else f"{material.name}.{rendered.name}"
        if name != material.name:
            warnings.append(f"{what}: shares material '{material.name}' with another volume, so its medium is "
                            f"named '{name}'; a Fit of either writes into the material both share")
        corners = [blender_to_gltf(p) for p in volume_box(obj, rendered.matrix_world)]
        gltf_json.add_mesh_node(doc, rendered.name, corners, BOX_TRIANGLES,
                                {"name": name, "extensions": {EXTENSION: entry}})


def fluid_domain_settings(obj):
    """The domain settings of OBJ's Fluid modifier of type Domain, or None."""
    modifier = next((m for m in obj.modifiers if m.type == "FLUID" and m.fluid_type == "DOMAIN"), None)
    return modifier.domain_settings if modifier is not None else None


def fluid_domain_materials(view_layer):
    """Names of the materials of the smoke domains VIEW_LAYER renders (add_fluid_domains
    gives them their media)."""
    return {slot.material.name for rendered in rendered_objects(view_layer)
            if fluid_domain_settings(rendered.object) is not None
            for slot in rendered.object.material_slots if slot.material is not None}


def domain_cache_problem(settings, source):
    """Why a domain's grids cannot be exported, or None."""
    if settings.domain_type != "GAS":
        return "a liquid domain"
    if settings.cache_data_format != "OPENVDB":
        return f"its cache format is {settings.cache_data_format}, not OpenVDB"
    if settings.use_adaptive_domain:
        return "an adaptive domain (its grid moves with the smoke)"
    if settings.use_noise:
        return "a domain with noise (its upres grids)"
    if not os.path.isfile(source):
        return f"no baked cache of this frame ({source}): bake the simulation"
    return None


def domain_grid_placement(obj, matrix_world, volume):
    """The world matrix that places the cache's grids as Cycles does: the simulation's
    resolution stretched over the domain's box, cell i's centre at (i + 1/2) / resolution
    of it. The resolution follows from the cell size as Blender sets it from the longest
    side (at least 4 cells a side); the file's own transform, a voxel of the cell size,
    comes first. None where every grid is empty (no smoke yet), which gives no cell size."""
    low, high = object_box(obj)
    # The cache's grids share one cell size; an empty grid (no flame yet) has none.
    voxel = next((g.matrix_object for g in volume.grids if g.matrix_object.to_3x3().determinant() != 0.0), None)
    if voxel is None:
        return None
    cell_size = [voxel.col[i].xyz.length for i in range(3)]
    resolution = [max(int(obj.dimensions[i] / cell_size[i] + 0.5), 4) for i in range(3)]
    cell = [(high[i] - low[i]) / resolution[i] for i in range(3)]
    stretch = mathutils.Matrix.Diagonal([cell[i] / cell_size[i] for i in range(3)] + [1.0])
    centre = mathutils.Matrix.Translation([low[i] + 0.5 * cell[i] for i in range(3)])
    return matrix_world @ centre @ stretch


def add_fluid_domains(doc, frame, view_layer, copies, warnings):
    """Smoke simulation domains become media inside the domain's mesh, reading the grids
    of the simulation's OpenVDB cache at FRAME (grid_medium); a domain whose cache cannot
    be read is exported empty, with a warning."""
    materials = {m.get("name"): m for m in doc.get("materials", [])}
    for rendered in rendered_objects(view_layer):
        settings = fluid_domain_settings(rendered.object)
        material = rendered.object.active_material
        if settings is None or material is None or material.name not in materials:
            continue
        what = f"smoke domain '{rendered.name}'"
        source = os.path.join(bpy.path.abspath(settings.cache_directory), "data", f"fluid_data_{frame:04d}.vdb")
        entry, problem = None, domain_cache_problem(settings, source)
        if problem is None:
            volume = bpy.data.volumes.new(f"{rendered.name}.cache")
            try:
                volume.filepath = source
                placement = domain_grid_placement(rendered.object, rendered.matrix_world, volume) \
                    if volume.grids.load() else None
                if placement is not None:
                    entry = grid_medium(doc, material, volume, placement, rendered.name, copies, what, warnings)
                else:
                    problem = f"its cache {source} does not load or holds no smoke"
            finally:
                bpy.data.volumes.remove(volume)
        if entry is None:
            if problem is not None:
                warnings.append(f"{what}: {problem}; exported as an empty medium")
            entry = medium_json(mappings.Medium((0.0,) * 3, (0.0,) * 3, 0.0))
        extensions = materials[material.name].setdefault("extensions", {})
        for name in gltf_json.TRANSMISSION_EXTENSIONS:
            extensions.pop(name, None)
        extensions[EXTENSION] = entry


def add_grid_media(doc, scene, view_layer, filepath, warnings):
    copies = GridCopies(filepath)
    add_volume_objects(doc, view_layer, copies, warnings)
    add_fluid_domains(doc, scene.frame_current, view_layer, copies, warnings)
