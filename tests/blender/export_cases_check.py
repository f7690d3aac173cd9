"""Run inside Blender for test_export_cases.py: build small scenes that an artist's file
may hold, each from an empty file, and export each with the add-on to OUT/<case>/scene.gltf.
OUT/<case>/result.json holds the export's warnings, or the ExportError it raised, and
the case's own facts (the file mode a new file gets); a baked smoke simulation's domain
writes its size and place to OUT/baked_smoke/baked_smoke.json.

  blender -b --factory-startup --python export_cases_check.py -- --out DIR"""
import argparse
import json
import os
import pathlib
import sys

import bpy

HERE = pathlib.Path(__file__).resolve().parent
SCENES = HERE.parents[1] / "scenes"
sys.path[:0] = [str(HERE.parents[1] / "tools" / "blender")]
from vkdiffrender_blender import export_scene, write_back  # noqa: E402


def empty_scene():
    """A perspective camera above a floor lit by nothing yet."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.location, camera.rotation_euler = (0.0, -5.0, 1.0), (1.5708, 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    bpy.ops.mesh.primitive_plane_add(size=10.0)
    return scene


def add_light(kind, name, location, energy, collection):
    light = bpy.data.objects.new(name, bpy.data.lights.new(name, kind))
    light.data.energy = energy
    light.location = location
    collection.objects.link(light)
    return light


def instanced_lights(scene):
    """A point and an area lamp in a collection the scene does not hold, instanced 1 m
    along x, as a linked lamp asset arrives; the area lamp is in a child collection of it
    too, and an instance holds each object once."""
    asset = bpy.data.collections.new("LampAsset")
    add_light("POINT", "Bulb", (0.0, 0.0, 3.0), 200.0, asset)
    panel = add_light("AREA", "Panel", (0.0, 0.0, 2.5), 100.0, asset)
    inner = bpy.data.collections.new("LampAssetInner")
    asset.children.link(inner)
    inner.objects.link(panel)
    instance = bpy.data.objects.new("Lamps", None)
    instance.instance_type, instance.instance_collection = "COLLECTION", asset
    instance.location = (1.0, 0.0, 0.0)
    scene.collection.objects.link(instance)


def vertex_instanced_lights(scene):
    """An area and a point lamp parented to a mesh of two vertices that instances its
    children at them: Cycles renders each lamp at both vertices and not at its own place."""
    mesh = bpy.data.meshes.new("Row")
    mesh.from_pydata([(-1.5, 0.0, 0.0), (1.5, 0.0, 0.0)], [], [])
    row = bpy.data.objects.new("Row", mesh)
    scene.collection.objects.link(row)
    row.instance_type = "VERTS"
    for light in (add_light("AREA", "Panel", (0.0, 0.0, 2.5), 100.0, scene.collection),
                  add_light("POINT", "Bulb", (0.0, 0.0, 3.0), 100.0, scene.collection)):
        light.parent = row


def render_modifiers(scene):
    """A cube subdivided once for rendering (not in the viewport) and repeated by an Array
    modifier enabled for rendering only; another whose Array is enabled for the viewport
    only; cubes subdivided once for rendering that are disabled in viewports, one
    themselves and one by their collection; and Simplify on, at level 0 in the viewport
    and 6 for the render."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    cube = bpy.context.object
    cube.name = "Rendered"
    subdivision = cube.modifiers.new("Subdivision", "SUBSURF")
    subdivision.levels, subdivision.render_levels = 0, 1
    array = cube.modifiers.new("Array", "ARRAY")
    array.count, array.show_viewport = 2, False
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 2.0, 0.5))
    cube = bpy.context.object
    cube.name = "Viewport"
    array = cube.modifiers.new("Array", "ARRAY")
    array.count, array.show_render = 2, False
    hidden = bpy.data.collections.new("NotInViewports")
    scene.collection.children.link(hidden)
    for name, x, collection in (("Disabled", 2.0, scene.collection), ("InDisabled", -2.0, hidden)):
        cube = bpy.data.objects.new(name, bpy.data.meshes.new(name))
        bmesh_cube(cube.data)
        cube.location = (x, 0.0, 0.5)
        collection.objects.link(cube)
        subdivision = cube.modifiers.new("Subdivision", "SUBSURF")
        subdivision.levels, subdivision.render_levels = 0, 1
    bpy.data.objects["Disabled"].hide_viewport = True
    hidden.hide_viewport = True
    scene.render.use_simplify = True
    scene.render.simplify_subdivision, scene.render.simplify_subdivision_render = 0, 6


def bmesh_cube(mesh):
    """A cube of side 0.5 into MESH, without operators (they need a visible object)."""
    import bmesh
    built = bmesh.new()
    bmesh.ops.create_cube(built, size=0.5)
    built.to_mesh(mesh)
    built.free()


def viewport_settings_after(directory):
    return {"viewport_after": [bpy.data.objects["Disabled"].hide_viewport,
                               bpy.data.collections["NotInViewports"].hide_viewport,
                               bpy.context.scene.render.simplify_subdivision]}


def vertex_colours(scene):
    """A cube with a colour attribute its material does not read."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    bpy.context.object.data.color_attributes.new("Col", "FLOAT_COLOR", "POINT")


def colour_reading_material(name, attribute):
    """A Principled BSDF whose Base Color a Color Attribute node of ATTRIBUTE feeds ("":
    the render colour attribute)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    node = tree.nodes.new("ShaderNodeVertexColor")
    node.layer_name = attribute
    tree.links.new(node.outputs["Color"], tree.nodes["Principled BSDF"].inputs["Base Color"])
    return material


def cube_with_colour_attributes(name, x, material, attributes):
    """A cube at X with MATERIAL and colour attributes of these names, each all of one grey
    (0.1 the first, 0.2 the second, ...); the first is the render colour attribute."""
    bpy.ops.mesh.primitive_cube_add(size=0.4, location=(x, 0.0, 0.5))
    cube = bpy.context.object
    cube.name = name
    cube.data.name = name
    for k, attribute in enumerate(attributes):
        values = cube.data.color_attributes.new(attribute, "FLOAT_COLOR", "POINT")
        for value in values.data:
            value.color = (0.1 * (k + 1),) * 3 + (1.0,)
    if attributes:
        cube.data.color_attributes.render_color_index = 0
    if material is not None:
        cube.data.materials.append(material)
    return cube


def read_colour_attributes(scene):
    """Cubes whose materials read a colour attribute: the render one (Rendered), another
    one (Named, whose render attribute must be set back after the export), one the mesh
    lacks (Missing), two at once (TwoRead, one material on each half of its faces), and
    each its own on two objects of one mesh (SharedA, SharedB); and a cube with an
    attribute no material reads (Unread)."""
    cube_with_colour_attributes("Rendered", -2.0, colour_reading_material("ReadsRender", ""), ["Col", "Other"])
    cube_with_colour_attributes("Named", -1.0, colour_reading_material("ReadsPaint", "Paint"), ["Col", "Paint"])
    cube_with_colour_attributes("Missing", 0.0, colour_reading_material("ReadsAbsent", "Absent"), ["Col"])
    cube_with_colour_attributes("Unread", 1.0, None, ["Col"])
    two = cube_with_colour_attributes("TwoRead", 2.0, colour_reading_material("ReadsA", "A"), ["A", "B"])
    two.data.materials.append(colour_reading_material("ReadsB", "B"))
    for polygon in two.data.polygons[:3]:
        polygon.material_index = 1
    # One mesh, two objects, each with a material of its own (linked to the object) that
    # reads the render colour attribute.
    shared = cube_with_colour_attributes("SharedA", 3.0, None, ["Col"])
    shared.data.name = "Shared"
    twin = shared.copy()
    twin.name = "SharedB"
    twin.location.x = 4.0
    bpy.context.scene.collection.objects.link(twin)
    for obj in (shared, twin):
        obj.data.materials.append(None)
        obj.material_slots[0].link = "OBJECT"
        obj.material_slots[0].material = colour_reading_material("Reads" + obj.name, "")


def painted_faces_colour(normal):
    """The colour corner_colour_attribute paints the face of this outward normal (Blender's
    axes), different for each face of a cube."""
    return tuple(0.5 + 0.4 * c for c in normal)


def corner_colour_attribute(scene):
    """A cube painted face by face as Vertex Paint stores it (a Face Corner, Byte Color
    attribute: a vertex's corners differ), read by its material; and a material slot no face
    uses, whose material reads another attribute (Unused)."""
    bpy.ops.mesh.primitive_cube_add(size=0.4, location=(0.0, 0.0, 0.5))
    cube = bpy.context.object
    cube.name = cube.data.name = "Painted"
    painted = cube.data.color_attributes.new("Paint", "BYTE_COLOR", "CORNER")
    cube.data.color_attributes.render_color_index = 0
    for polygon in cube.data.polygons:
        for corner in polygon.loop_indices:
            painted.data[corner].color = painted_faces_colour(polygon.normal) + (1.0,)
    cube.data.materials.append(colour_reading_material("ReadsPaint", "Paint"))
    cube.data.materials.append(colour_reading_material("Unused", "Absent"))


def fit_parameters(scene):
    """What the Fit panel offers: a grey and a pure red Diffuse (no log of red's 0 green), a
    material with a surface and a volume (a medium's boundary, no colour), a material only
    an object hidden from the render uses, a colour and a volume's Density that a Math
    node feeds, and area lamps of 100 W and of 0 W."""
    for name, colour, x in (("Grey", (0.5, 0.5, 0.5, 1.0), -1.0), ("Red", (1.0, 0.0, 0.0, 1.0), 0.0),
                            ("Foggy", (0.5, 0.5, 0.5, 1.0), 1.0), ("Computed", (0.5, 0.5, 0.5, 1.0), -2.0),
                            ("HiddenOnly", (0.5, 0.5, 0.5, 1.0), 2.0)):
        bpy.ops.mesh.primitive_cube_add(size=0.4, location=(x, 0.0, 0.5))
        material = bpy.data.materials.new(name)
        material.use_nodes = True
        material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = colour
        bpy.context.object.data.materials.append(material)
    bpy.context.object.hide_render = True  # HiddenOnly's cube
    foggy = bpy.data.materials["Foggy"].node_tree
    volume = foggy.nodes.new("ShaderNodeVolumePrincipled")
    foggy.links.new(volume.outputs["Volume"], foggy.nodes["Material Output"].inputs["Volume"])
    computed = bpy.data.materials["Computed"].node_tree
    computed.links.new(computed.nodes.new("ShaderNodeMath").outputs[0],
                       computed.nodes["Principled BSDF"].inputs["Base Color"])
    bpy.ops.mesh.primitive_cube_add(size=0.4, location=(-2.0, 1.0, 0.5))
    bpy.context.object.data.materials.append(volume_material("ComputedFog", 2.0))
    fog = bpy.data.materials["ComputedFog"].node_tree
    fog.links.new(fog.nodes.new("ShaderNodeMath").outputs[0], fog.nodes["Principled Volume"].inputs["Density"])
    add_light("AREA", "Lit", (0.0, 0.0, 2.5), 100.0, scene.collection)
    add_light("AREA", "Dark", (1.0, 0.0, 2.5), 0.0, scene.collection)


def light_write_back(scene):
    """Two point lamps whose names cross: object Key holds light data Light, and object
    Light holds data Light.001. The export names glTF lights after their data, so a fitted
    lights/Light/intensity belongs to Key."""
    add_light("POINT", "Key", (0.0, 0.0, 3.0), 100.0, scene.collection).data.name = "Light"
    add_light("POINT", "Light", (1.0, 0.0, 3.0), 100.0, scene.collection).data.name = "Light.001"


def medium_write_back(scene):
    """A volume cube whose Principled Volume reads its Density from an attribute: a fit of
    g alone writes the Anisotropy and leaves the other inputs as they are."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    material = volume_material("Smoke", 3.0)
    tree = material.node_tree
    attribute = tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "density"
    tree.links.new(attribute.outputs["Fac"], tree.nodes["Principled Volume"].inputs["Density"])
    bpy.context.object.data.materials.append(material)


def bright_colour_attribute(scene):
    """A cube whose material reads its colour attribute, one channel of which is beyond 1
    (a float attribute may hold any value)."""
    cube = cube_with_colour_attributes("Bright", 0.0, colour_reading_material("ReadsBright", ""), ["Col"])
    for value in cube.data.color_attributes["Col"].data:
        value.color = (0.5, 1.5, 0.5, 1.0)


def volume_cube(name, location):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    cube = bpy.context.object
    cube.name = name
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.links.new(tree.nodes.new("ShaderNodeVolumePrincipled").outputs[0],
                   tree.nodes["Material Output"].inputs["Volume"])
    cube.data.materials.append(material)


def added_volumes(scene):
    """A World fog and three volume cubes, two of them overlapping: Cycles adds up the
    volumes where they overlap and the World's inside every cube."""
    tree = new_world(scene, "Fog")
    tree.links.new(tree.nodes.new("ShaderNodeVolumeScatter").outputs[0], tree.nodes["World Output"].inputs["Volume"])
    volume_cube("Outer", (0.0, 0.0, 0.5))
    volume_cube("Overlapping", (0.5, 0.0, 0.5))
    volume_cube("Apart", (3.0, 0.0, 0.5))


def hidden_lights(scene):
    """Area lamps in a collection disabled for rendering and in one the view layer excludes,
    a light portal, and a mirrored one that renders."""
    off = bpy.data.collections.new("Off")
    scene.collection.children.link(off)
    off.hide_render = True
    add_light("AREA", "Disabled", (0.0, 0.0, 2.0), 300.0, off)
    excluded = bpy.data.collections.new("Excluded")
    scene.collection.children.link(excluded)
    add_light("AREA", "Excluded", (0.0, 0.0, 2.0), 300.0, excluded)
    bpy.context.view_layer.layer_collection.children["Excluded"].exclude = True
    mirrored = add_light("AREA", "Mirrored", (0.0, 0.0, 2.0), 300.0, scene.collection)
    mirrored.scale = (-1.0, 1.0, 1.0)
    portal = add_light("AREA", "Portal", (0.0, 0.0, 1.0), 300.0, scene.collection)
    portal.data.cycles.is_portal = True


def world_without_nodes(scene):
    scene.world = bpy.data.worlds.new("Plain")
    scene.world.use_nodes = False
    scene.world.color = (0.3, 0.2, 0.1)


def new_world(scene, name):
    """The scene's World, new, with nodes; returns its node tree."""
    scene.world = bpy.data.worlds.new(name)
    scene.world.use_nodes = True
    return scene.world.node_tree


def world_mix_shader(scene):
    tree = new_world(scene, "Mixed")
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(tree.nodes["Background"].outputs[0], mix.inputs[1])
    tree.links.new(mix.outputs[0], tree.nodes["World Output"].inputs["Surface"])


def volume_object(scene, name, path):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    volume = tree.nodes.new("ShaderNodeVolumePrincipled")
    tree.links.new(volume.outputs[0], tree.nodes.new("ShaderNodeOutputMaterial").inputs["Volume"])
    data = bpy.data.volumes.new(name)
    data.filepath = str(path)
    obj = bpy.data.objects.new(name, data)
    obj.data.materials.append(material)
    scene.collection.objects.link(obj)
    return obj


def same_file_names(scene):
    """Two Volume objects whose names differ only where a file name cannot hold them."""
    volume_object(scene, "Дым", SCENES / "cornell_plume.vdb").location.x = -1.0
    volume_object(scene, "Пар", SCENES / "cornell_fire_flame.vdb").location.x = 1.0
    for obj in scene.objects:
        if obj.type == "VOLUME":
            obj.active_material.node_tree.nodes["Principled Volume"].inputs["Density Attribute"].default_value = \
                "density" if obj.name == "Дым" else "flame"


def shared_grid_file(scene):
    """Two Volume objects of one file (two clouds of one asset)."""
    volume_object(scene, "CloudA", SCENES / "cornell_plume.vdb").location.x = -1.0
    volume_object(scene, "CloudB", SCENES / "cornell_plume.vdb").location.x = 1.0


def smoke_domain(scene):
    """A smoke domain whose cache is in Mantaflow's own format, which the export cannot read."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    bpy.ops.object.quick_smoke()
    domain = next(o for o in scene.objects if o.name.startswith("Smoke Domain"))
    domain.modifiers["Fluid"].domain_settings.cache_data_format = "UNI"
    add_light("SUN", "Sun", (0.0, 0.0, 5.0), 3.0, scene.collection).data.angle = 0.0


def baked_smoke(scene, out):
    """Smoke from a cube, simulated at a resolution of 16 for 6 frames into OUT/cache,
    exported at frame 6 with the emitting cube hidden."""
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0.3, -0.2, 0.5))
    flow = bpy.context.object
    bpy.ops.object.quick_smoke()
    domain = next(o for o in scene.objects if o.name.startswith("Smoke Domain"))
    settings = domain.modifiers["Fluid"].domain_settings
    settings.cache_directory = str(out / "cache")
    settings.resolution_max = 16
    settings.cache_type = "ALL"
    settings.cache_frame_end = scene.frame_end = 6
    with bpy.context.temp_override(object=domain, active_object=domain):
        bpy.ops.fluid.bake_all()
    flow.hide_render = True
    scene.frame_set(6)
    add_light("SUN", "Sun", (0.0, 0.0, 5.0), 3.0, scene.collection).data.angle = 0.0
    cache = bpy.data.volumes.new("cache")
    cache.filepath = str(out / "cache" / "data" / "fluid_data_0006.vdb")
    cache.grids.load()
    facts = {"dimensions": list(domain.dimensions), "matrix_world": [list(row) for row in domain.matrix_world],
             "voxel": [list(row) for row in cache.grids["density"].matrix_object]}
    (out / "baked_smoke.json").write_text(json.dumps(facts))


def glass(scene):
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Glass")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Transmission"].default_value = 1.0
    bpy.context.object.data.materials.append(material)
    add_light("POINT", "Bulb", (0.0, -1.0, 2.0), 100.0, scene.collection)
    # Beside it, a Principled BSDF whose Base Color is a procedural texture.
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(1.0, 0.0, 0.5))
    noisy = bpy.data.materials.new("Noisy")
    noisy.use_nodes = True
    nodes = noisy.node_tree.nodes
    nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.2, 0.4, 0.6, 1.0)
    noisy.node_tree.links.new(nodes.new("ShaderNodeTexNoise").outputs["Color"],
                              nodes["Principled BSDF"].inputs["Base Color"])
    bpy.context.object.data.materials.append(noisy)


def light_nodes(scene):
    """Point lamps without nodes, with the default Emission node, and with Strength 5."""
    for name, strength in (("Plain", None), ("Default", 1.0), ("Five", 5.0)):
        light = add_light("POINT", name, (0.0, 0.0, 3.0), 100.0, scene.collection)
        if strength is not None:
            light.data.use_nodes = True
            light.data.node_tree.nodes["Emission"].inputs["Strength"].default_value = strength


def hidden_collections(scene):
    """A cube and a bulb in a collection nested inside one disabled for rendering, and in a
    collection the view layer excludes: Cycles renders none of them."""
    off = bpy.data.collections.new("Off")
    scene.collection.children.link(off)
    off.hide_render = True
    nested = bpy.data.collections.new("Nested")
    off.children.link(nested)
    excluded = bpy.data.collections.new("Excluded")
    scene.collection.children.link(excluded)
    bpy.context.view_layer.layer_collection.children["Excluded"].exclude = True
    for collection in (nested, excluded):
        cube = bpy.data.objects.new(f"{collection.name}Cube", bpy.data.meshes.new(f"{collection.name}Cube"))
        cube.data.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [(0, 1, 2)])
        collection.objects.link(cube)
        add_light("POINT", f"{collection.name}Bulb", (0.0, 0.0, 3.0), 100.0, collection)


def animated(scene):
    """A cube moving from x = -2 at frame 1 to x = 2 at frame 21, exported at frame 21."""
    bpy.ops.mesh.primitive_cube_add(size=0.5)
    cube = bpy.context.object
    cube.name = "Moving"
    for frame, x in ((1, -2.0), (21, 2.0)):
        cube.location = (x, 0.0, 0.5)
        cube.keyframe_insert("location", frame=frame)
    scene.frame_set(21)


def world_named_like_a_material(scene):
    """A World fog and a fog cube's material, both named Fog."""
    tree = new_world(scene, "Fog")
    fog = tree.nodes.new("ShaderNodeVolumeScatter")
    tree.links.new(fog.outputs[0], tree.nodes["World Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_cube_add(size=0.5)
    material = bpy.data.materials.new("Fog")
    material.use_nodes = True
    material.node_tree.nodes.clear()
    scatter = material.node_tree.nodes.new("ShaderNodeVolumeScatter")
    output = material.node_tree.nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(scatter.outputs[0], output.inputs["Volume"])
    bpy.context.object.data.materials.append(material)


def image_texture(name, colour_space="sRGB"):
    image = bpy.data.images.new(name, 4, 4)
    image.pixels = [value for i in range(16) for value in ((1.0, 0.2, 0.1, 1.0) if i % 3 else (0.1, 0.3, 0.9, 1.0))]
    image.colorspace_settings.name = colour_space
    return image


def textured_emitter(nodes, links, image, colour):
    """An Emission shader whose Color is the image, its unlinked Color `colour`."""
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = colour
    emission.inputs["Strength"].default_value = 2.0
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    links.new(texture.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    return texture


def textured_materials(scene):
    """Two planes whose Emission shaders are image textures: one looked up as glTF can
    carry (an sRGB image, linear, repeated, by the UV map); one clipped, nearest-texel, of
    Non-Color data, by generated coordinates through a Mapping node turned about X. Both
    Emission shaders' unlinked colours are red, which Cycles does not use."""
    for name, location in (("Plain", (-1.0, 0.0, 0.5)), ("Odd", (1.0, 0.0, 0.5))):
        bpy.ops.mesh.primitive_plane_add(size=1.0, location=location)
        material = bpy.data.materials.new(name)
        material.use_nodes = True
        nodes, links = material.node_tree.nodes, material.node_tree.links
        nodes.remove(nodes["Principled BSDF"])
        texture = textured_emitter(nodes, links, image_texture(name, "sRGB" if name == "Plain" else "Non-Color"),
                                   (1.0, 0.0, 0.0, 1.0))
        if name == "Odd":
            texture.extension, texture.interpolation, texture.projection = "CLIP", "Closest", "BOX"
            coordinates, mapping = nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeMapping")
            mapping.inputs["Rotation"].default_value = (0.3, 0.0, 0.0)
            links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
            links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
        bpy.context.object.data.materials.append(material)


def orthographic_camera(scene):
    """An orthographic camera whose Orthographic Scale spans the height of a wide image
    (Sensor Fit Vertical), which Blender's glTF exporter would span over the width."""
    scene.camera.data.type = "ORTHO"
    scene.camera.data.ortho_scale, scene.camera.data.sensor_fit = 3.0, "VERTICAL"
    scene.render.resolution_x, scene.render.resolution_y = 200, 100


def panoramic_camera(scene):
    scene.camera.data.type = "PANO"


def volume_material(name, density):
    """A material whose Volume is a Principled Volume of DENSITY, with no Surface."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    volume = nodes.new("ShaderNodeVolumePrincipled")
    volume.inputs["Density"].default_value = density
    material.node_tree.links.new(volume.outputs[0], nodes["Material Output"].inputs["Volume"])
    return material


def nan_density(scene):
    """A NaN, as a driver or a script can give a socket."""
    bpy.ops.mesh.primitive_cube_add(size=0.5)
    bpy.context.object.data.materials.append(volume_material("NanFog", float("nan")))


def missing_image(scene):
    """A plane textured with an image whose file is gone."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Gone")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.new("gone", 4, 4)
    texture.image.source = "FILE"
    texture.image.filepath = "/nonexistent/gone.png"
    material.node_tree.links.new(texture.outputs["Color"],
                                 material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    bpy.context.object.data.materials.append(material)


def muted_volume(scene):
    """A cube whose Principled Volume is muted, which Cycles renders empty, and one whose
    Volume is a node group's, which the export cannot read."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    material = volume_material("Muted", 3.0)
    material.node_tree.nodes["Principled Volume"].mute = True
    bpy.context.object.data.materials.append(material)
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(1.0, 0.0, 0.5))
    material = volume_material("Grouped", 3.0)
    group = bpy.data.node_groups.new("Fog group", "ShaderNodeTree")
    group.outputs.new("NodeSocketShader", "Volume")
    group.links.new(group.nodes.new("ShaderNodeVolumePrincipled").outputs[0],
                    group.nodes.new("NodeGroupOutput").inputs[0])
    grouped = material.node_tree.nodes.new("ShaderNodeGroup")
    grouped.node_tree = group
    material.node_tree.links.new(grouped.outputs[0], material.node_tree.nodes["Material Output"].inputs["Volume"])
    bpy.context.object.data.materials.append(material)


def cycles_output(scene):
    """A volume cube whose material has two Material Outputs: the active one for all
    renderers (density 3) and another for Cycles alone (density 1), which Cycles uses."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    material = volume_material("TwoOutputs", 3.0)
    tree = material.node_tree
    cycles = tree.nodes.new("ShaderNodeOutputMaterial")
    cycles.target = "CYCLES"
    volume = tree.nodes.new("ShaderNodeVolumePrincipled")
    volume.inputs["Density"].default_value = 1.0
    tree.links.new(volume.outputs[0], cycles.inputs["Volume"])
    tree.nodes["Material Output"].is_active_output = True
    bpy.context.object.data.materials.append(material)


def rerouted_volumes(scene):
    """Three volume cubes of one Principled Volume: linked to the output directly, through
    two Reroute nodes, and by a muted link, which Cycles renders empty."""
    for name, x in (("Direct", -1.0), ("Rerouted", 0.0), ("MutedLink", 1.0)):
        bpy.ops.mesh.primitive_cube_add(size=0.5, location=(x, 0.0, 0.5))
        material = volume_material(name, 3.0)
        tree = material.node_tree
        volume, output = tree.nodes["Principled Volume"], tree.nodes["Material Output"]
        volume.inputs["Anisotropy"].default_value = 0.4
        if name == "Rerouted":
            first, second = tree.nodes.new("NodeReroute"), tree.nodes.new("NodeReroute")
            tree.links.new(volume.outputs[0], first.inputs[0])
            tree.links.new(first.outputs[0], second.inputs[0])
            tree.links.new(second.outputs[0], output.inputs["Volume"])
        if name == "MutedLink":
            output.inputs["Volume"].links[0].is_muted = True
        bpy.context.object.data.materials.append(material)


def blinding_light(scene):
    add_light("POINT", "Blinding", (0.0, 0.0, 2.0), 1e30, scene.collection)


def blinding_volume(scene):
    """A volume cube emitting 1e13: the medium's emission, not a surface's."""
    bpy.ops.mesh.primitive_cube_add(size=0.5)
    material = volume_material("BlindingFog", 1.0)
    material.node_tree.nodes["Principled Volume"].inputs["Emission Strength"].default_value = 1e13
    bpy.context.object.data.materials.append(material)


def open_volume(scene):
    """A plane, which encloses nothing, with a volume material."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 1.0))
    bpy.context.object.name = "Sheet"
    bpy.context.object.data.materials.append(volume_material("OpenFog", 1.0))


def nan_light_power(scene):
    add_light("POINT", "Bulb", (0.0, 0.0, 2.0), float("nan"), scene.collection)


def area_light_of_no_size(scene):
    add_light("AREA", "Panel", (0.0, 0.0, 2.0), 100.0, scene.collection)
    bpy.data.objects["Panel"].data.size = 0.0


def area_emitter_named_like_a_material(scene):
    add_light("AREA", "Lamp", (0.0, 0.0, 2.0), 100.0, scene.collection)
    bpy.ops.mesh.primitive_cube_add(size=0.5)
    material = bpy.data.materials.new("Lamp.area")
    bpy.context.object.data.materials.append(material)


def world_named_like_two_materials(scene):
    """A World fog named World, and fog cubes whose materials are World and World (World)."""
    tree = new_world(scene, "World")
    fog = tree.nodes.new("ShaderNodeVolumeScatter")
    fog.inputs["Density"].default_value = 0.01
    tree.links.new(fog.outputs[0], tree.nodes["World Output"].inputs["Volume"])
    for name, x in (("World", -1.0), ("World (World)", 1.0)):
        bpy.ops.mesh.primitive_cube_add(size=0.5, location=(x, 0.0, 0.5))
        bpy.context.object.data.materials.append(volume_material(name, 1.0))


def packed_texture(scene, colour=None):
    """A plane textured with a packed image named photo, which the export writes as
    photo.png; all of COLOUR where given."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Photo")
    material.use_nodes = True
    texture = material.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = image_texture("photo")
    if colour is not None:
        texture.image.pixels = list(colour) * 16
    texture.image.pack()
    material.node_tree.links.new(texture.outputs["Color"],
                                 material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    bpy.context.object.data.materials.append(material)


def negative_lamp(scene):
    add_light("POINT", "Drain", (0.0, 0.0, 2.0), -100.0, scene.collection)


def negative_emission(scene):
    """A plane whose Emission shader has Strength -2."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Sink")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = -2.0
    material.node_tree.links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    bpy.context.object.data.materials.append(material)


def negative_world(scene):
    tree = new_world(scene, "Dark")
    tree.nodes["Background"].inputs["Strength"].default_value = -1.0


def unexported_geometry(scene):
    """A metaball with a volume material, and a mesh of three points whose Geometry Nodes
    instance a cube on each: Cycles renders both, Blender's glTF exporter neither. A lamp
    whose shadows are off."""
    bpy.ops.object.metaball_add(location=(0.0, 0.0, 1.0))
    bpy.context.object.name = "Blob"
    bpy.context.object.data.materials.append(volume_material("BlobFog", 2.0))
    points = bpy.data.meshes.new("Points")
    points.from_pydata([(-1.0, 0.0, 0.5), (1.0, 0.0, 0.5), (0.0, 1.0, 0.5)], [], [])
    scatter = bpy.data.objects.new("Scatter", points)
    scene.collection.objects.link(scatter)
    cube = bpy.data.objects.new("Pebble", bpy.data.meshes.new("Pebble"))
    bmesh_cube(cube.data)
    tree = bpy.data.node_groups.new("Scatter", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    on_points, info = tree.nodes.new("GeometryNodeInstanceOnPoints"), tree.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = cube
    tree.links.new(tree.nodes.new("NodeGroupInput").outputs[0], on_points.inputs["Points"])
    tree.links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    tree.links.new(on_points.outputs[0], tree.nodes.new("NodeGroupOutput").inputs[0])
    scatter.modifiers.new("Scatter", "NODES").node_group = tree
    add_light("POINT", "Shadowless", (0.0, 0.0, 2.0), 100.0, scene.collection).data.cycles.cast_shadow = False
    # Text, whose mesh Blender hands out as an instance of its object: no node tree's.
    bpy.ops.object.text_add(location=(0.0, 1.0, 0.2))
    bpy.context.object.name = "Label"
    # A cube whose node tree sets its faces' material: the glTF exporter writes its own
    # slot's material, Painted, not the tree's.
    cube = bpy.data.objects.new("Painted", bpy.data.meshes.new("Painted"))
    bmesh_cube(cube.data)
    cube.location = (2.0, 0.0, 0.5)
    scene.collection.objects.link(cube)
    for name in ("Painted", "FromNodes"):
        material = bpy.data.materials.new(name)
        material.use_nodes = True
    cube.data.materials.append(bpy.data.materials["Painted"])
    tree = bpy.data.node_groups.new("Paint", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    paint = tree.nodes.new("GeometryNodeSetMaterial")
    paint.inputs["Material"].default_value = bpy.data.materials["FromNodes"]
    tree.links.new(tree.nodes.new("NodeGroupInput").outputs[0], paint.inputs["Geometry"])
    tree.links.new(paint.outputs[0], tree.nodes.new("NodeGroupOutput").inputs[0])
    cube.modifiers.new("Paint", "NODES").node_group = tree


def unused_slot(scene):
    """The floor with a second material in a slot no face uses; a panoramic camera and one
    hidden from the render beside the scene camera."""
    floor = bpy.data.objects["Plane"]
    for name, colour in (("Floor", (0.5, 0.5, 0.5, 1.0)), ("Unused", (0.8, 0.1, 0.1, 1.0))):
        material = bpy.data.materials.new(name)
        material.use_nodes = True
        material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = colour
        floor.data.materials.append(material)
    add_light("SUN", "Sun", (0.0, 0.0, 3.0), 3.0, scene.collection)
    for name, hidden in (("Pano", False), ("Off", True)):
        camera = bpy.data.objects.new(name, bpy.data.cameras.new(name))
        camera.location, camera.rotation_euler, camera.hide_render = (0.0, -4.0, 1.0), (1.5708, 0.0, 0.0), hidden
        camera.data.type = "PANO" if name == "Pano" else "PERSP"
        scene.collection.objects.link(camera)


def see_through(scene):
    """A plane of a Principled BSDF with Alpha 0.3, whose Base Color a Noise Texture feeds."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Veil")
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Alpha"].default_value = 0.3
    noise = material.node_tree.nodes.new("ShaderNodeTexNoise")
    material.node_tree.links.new(noise.outputs["Fac"], principled.inputs["Base Color"])
    bpy.context.object.data.materials.append(material)


def negative_principled_emission(scene):
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.5))
    material = bpy.data.materials.new("Hole")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Emission Strength"].default_value = -5.0
    material.node_tree.nodes["Principled BSDF"].inputs["Emission"].default_value = (1.0, 1.0, 1.0, 1.0)
    bpy.context.object.data.materials.append(material)


def split_volume_cube(scene):
    """A volume cube whose faces an Edge Split modifier splits apart: its vertices differ,
    its surface is closed."""
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.5))
    bpy.context.object.data.materials.append(volume_material("SplitFog", 2.0))
    bpy.context.object.modifiers.new("Split", "EDGE_SPLIT").split_angle = 0.0
    add_light("POINT", "Bulb", (0.0, 0.0, 2.0), 100.0, scene.collection)


def backface_culled_emitter(scene):
    """An emissive panel whose material has Backface Culling on, its back to the camera:
    Cycles emits from both sides all the same."""
    mesh = bpy.data.meshes.new("Panel")
    mesh.from_pydata([(-1.0, 0.0, 0.0), (-1.0, 0.0, 2.0), (1.0, 0.0, 2.0), (1.0, 0.0, 0.0)], [], [(0, 1, 2, 3)])
    panel = bpy.data.objects.new("Panel", mesh)
    scene.collection.objects.link(panel)
    material = bpy.data.materials.new("CulledGlow")
    material.use_nodes = True
    material.use_backface_culling = True
    emission = material.node_tree.nodes.new("ShaderNodeEmission")
    material.node_tree.links.new(emission.outputs[0], material.node_tree.nodes["Material Output"].inputs["Surface"])
    mesh.materials.append(material)
    if mesh.polygons[0].normal.y < 0.0:  # its front away from the camera, at -y
        mesh.flip_normals()


def film_and_pixels(scene):
    """Film settings and pixels that make Cycles' image differ from vkdiffrender's."""
    scene.render.engine = "CYCLES"
    scene.cycles.film_exposure = 4.0
    scene.render.film_transparent = True
    scene.render.resolution_x, scene.render.resolution_y = 160, 80
    scene.render.resolution_percentage = 50
    scene.render.pixel_aspect_x = 2.0


def clipped_objects(scene):
    """A cube in view before the camera's Clip Start, one beyond its Clip End, one between
    them and one behind the camera, seen by a scaled camera (Cycles' clipping distances are
    in the world's units whatever the camera's scale)."""
    scene.camera.data.clip_start, scene.camera.data.clip_end = 1.0, 6.0
    scene.camera.scale = (3.0, 3.0, 3.0)
    for name, location, size in (("Near", (0.0, -4.5, 1.0), 0.2), ("Far", (1.5, 10.0, 1.0), 2.0),
                                 ("Between", (0.0, 0.0, 1.0), 0.5), ("Behind", (0.0, -7.0, 1.0), 0.5)):
        bpy.ops.mesh.primitive_cube_add(size=size, location=location)
        bpy.context.object.name = name


CASES = {"instanced_lights": instanced_lights, "vertex_instanced_lights": vertex_instanced_lights,
         "render_modifiers": render_modifiers, "vertex_colours": vertex_colours,
         "read_colour_attributes": read_colour_attributes, "bright_colour_attribute": bright_colour_attribute,
         "corner_colour_attribute": corner_colour_attribute, "fit_parameters": fit_parameters,
         "cycles_output": cycles_output, "medium_write_back": medium_write_back,
         "shared_grid_file": shared_grid_file, "light_write_back": light_write_back,
         "added_volumes": added_volumes, "hidden_lights": hidden_lights,
         "world_without_nodes": world_without_nodes, "world_mix_shader": world_mix_shader,
         "same_file_names": same_file_names, "smoke_domain": smoke_domain, "glass": glass,
         "light_nodes": light_nodes, "hidden_collections": hidden_collections, "animated": animated,
         "world_named_like_a_material": world_named_like_a_material, "orthographic_camera": orthographic_camera,
         "panoramic_camera": panoramic_camera,
         "textured_materials": textured_materials, "nan_density": nan_density, "open_volume": open_volume, "missing_image": missing_image,
         "muted_volume": muted_volume, "rerouted_volumes": rerouted_volumes, "blinding_light": blinding_light,
         "blinding_volume": blinding_volume,
         "nan_light_power": nan_light_power,
         "area_light_of_no_size": area_light_of_no_size,
         "area_emitter_named_like_a_material": area_emitter_named_like_a_material,
         "world_named_like_two_materials": world_named_like_two_materials,
         "negative_lamp": negative_lamp, "negative_emission": negative_emission, "negative_world": negative_world,
         "unexported_geometry": unexported_geometry, "unused_slot": unused_slot,
         "split_volume_cube": split_volume_cube, "see_through": see_through,
         "negative_principled_emission": negative_principled_emission,
         "backface_culled_emitter": backface_culled_emitter, "film_and_pixels": film_and_pixels,
         "clipped_objects": clipped_objects}


def failing_export(scene, directory):
    """A folder where the export's buffer goes: the export fails once the glTF exporter
    has run and the scene is complete, as it moves its files in."""
    (directory / "scene.bin").mkdir()
    (directory / "scene.bin" / "keep").write_text("a file of the user's")
    bpy.ops.mesh.primitive_cube_add(size=0.5)


def offered_for_fit(directory):
    return {"fittable": write_back.fittable_parameters(bpy.context.scene, bpy.context.view_layer),
            "cameras": [c.name for c in export_scene.exported_cameras(bpy.context.scene, bpy.context.view_layer)]}


def g_written_back(directory):
    volume = bpy.data.materials["Smoke"].node_tree.nodes["Principled Volume"]
    before = {name: list(volume.inputs[name].default_value) for name in ("Color", "Absorption Color")}
    fitted = {"media/Smoke/g": [0.5], "media/Smoke/density": {"count": 8, "mean": 0.1}}
    warnings = write_back.apply_fitted_values(bpy.context.scene, bpy.context.view_layer, fitted)
    return {"write_back_warnings": warnings,
            "volume_after": {"anisotropy": volume.inputs["Anisotropy"].default_value,
                             "density": volume.inputs["Density"].default_value,
                             "unchanged": all(list(volume.inputs[name].default_value) == value
                                              for name, value in before.items())}}


def light_written_back(directory):
    lights = json.loads((directory / "scene.gltf").read_text())["extensions"]["KHR_lights_punctual"]["lights"]
    write_back.apply_fitted_values(bpy.context.scene, bpy.context.view_layer,
                                   {"lights/Light/intensity": [1.0, 1.0, 1.0]})
    return {"exported_lights": sorted(light["name"] for light in lights),
            "light_watts": {name: bpy.data.objects[name].data.energy for name in ("Key", "Light")}}


def instanced_light_written_back(directory):
    """A fitted emission of one of a lamp's instances, which all take it."""
    return {"instanced_write_back_warnings": write_back.apply_fitted_values(
        bpy.context.scene, bpy.context.view_layer, {"lights/Row.0.Panel.area/emission": [1.0, 1.0, 1.0]})}


# What some cases read or do once they are exported: the Fit's view of the scene.
AFTER_EXPORT = {"fit_parameters": offered_for_fit, "unexported_geometry": offered_for_fit,
                "unused_slot": offered_for_fit, "medium_write_back": g_written_back,
                "light_write_back": light_written_back, "vertex_instanced_lights": instanced_light_written_back,
                "render_modifiers": viewport_settings_after}


def export_case(out, case, build, target=None):
    scene = empty_scene()
    directory = out / case
    directory.mkdir()
    build(scene)
    result = {}
    try:
        result["warnings"] = export_scene.export_scene(bpy.context, str(target or directory / "scene.gltf"))
    except (export_scene.ExportError, OSError) as error:
        result["error"] = str(error)
    if case in AFTER_EXPORT:
        result.update(AFTER_EXPORT[case](directory))
    result["modifiers_after"] = {obj.name: [[m.name, m.show_viewport, m.show_render, getattr(m, "levels", None)]
                                            for m in obj.modifiers] for obj in bpy.data.objects if obj.modifiers}
    result["render_colour_attributes_after"] = {
        obj.name: obj.data.color_attributes.render_color_index for obj in bpy.data.objects
        if obj.type == "MESH" and len(obj.data.color_attributes) > 0}
    umask = os.umask(0)
    os.umask(umask)
    result["new_file_mode"] = 0o666 & ~umask
    (directory / "result.json").write_text(json.dumps(result))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", required=True)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = pathlib.Path(args.out)
    for case, build in CASES.items():
        export_case(out, case, build)
    export_case(out, "baked_smoke", lambda scene: baked_smoke(scene, out / "baked_smoke"))
    (out / "elsewhere.gltf").write_text("the user's file")
    failing = out / "failing"
    failing.mkdir()
    (failing / "scene.gltf").write_text("the previous export")
    export_case(out, "failing_export", lambda scene: failing_export(scene, failing), failing / "scene.gltf")
    # A file of the user's where the export would write a texture; then the same scene,
    # its texture repainted, exported twice into a folder of its own, the second export
    # replacing the first's texture.
    users = out / "users_folder"
    users.mkdir()
    (users / "photo.png").write_text("the user's photo")
    export_case(out, "users_photo", packed_texture, users / "scene.gltf")
    twice = out / "twice_folder"
    twice.mkdir()
    export_case(out, "exported_once", packed_texture, twice / "scene.gltf")
    export_case(out, "exported_twice", lambda scene: packed_texture(scene, (0.2, 0.9, 0.1, 1.0)), twice / "scene.gltf")
    (out / "link.gltf").symlink_to(out / "elsewhere.gltf")
    export_case(out, "symbolic_link", lambda scene: None, out / "link.gltf")
    export_case(out, "missing_directory", lambda scene: None, out / "no such directory" / "scene.gltf")
    export_case(out, "glb_path", lambda scene: None, out / "glb_path" / "scene.glb")
    (out / "percent_name").mkdir()
    export_case(out, "percent_in_name", lambda scene: add_light("SUN", "Sun", (0.0, 0.0, 3.0), 3.0, scene.collection),
                out / "percent_name" / "a%20b.gltf")


main()
