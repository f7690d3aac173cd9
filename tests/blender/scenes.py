"""Test scenes built with bpy (run inside Blender): a diffuse box lit by an area light,
seen from its open front, and variants with a volume cube (one of them emissive), a smoke plume read from an OpenVDB
file as a Volume object (and the same plume burning, its material reading the file's flame and density grids as
emission strength and colour), a world fog, a point light,
a smooth sphere and Principled BSDF walls. Also the emissive mesh that stands in for an
area light where Cycles' area lights and the exported emitter differ (docs/blender.md).
The Cycles settings come from tools/blender/cycles_reference.py; the tests reach them as
scenes.configure_cycles."""
import atexit
import pathlib
import shutil
import subprocess
import tempfile

import bpy
from cycles_reference import configure_cycles, front_only_emission  # noqa: F401

# The values the tests check against; the closed loop fits PRINCIPLED back from a wrong start.
PRINCIPLED = {"Color": (0.7, 0.5, 0.3, 1.0), "Density": 2.0, "Absorption Color": (0.2, 0.5, 0.8, 1.0),
              "Anisotropy": 0.3}
ABSORPTION = {"Color": (0.35, 0.6, 0.85, 1.0), "Density": 2.5}
GLOWING = {"Color": (0.6, 0.5, 0.4, 1.0), "Density": 1.5, "Absorption Color": (0.3, 0.5, 0.7, 1.0),
           "Anisotropy": 0.2, "Emission Color": (1.0, 0.5, 0.2, 1.0), "Emission Strength": 2.0}
PLUME = {"Color": (0.8, 0.7, 0.6, 1.0), "Density": 10.0, "Absorption Color": (0.3, 0.4, 0.5, 1.0),
         "Anisotropy": 0.3}
# The shipped 64^3 smoke plume (vkdr-make-plume --resolution 64 --seed 1), rising along
# the file's +y through [-0.5, 0.5]^3.
PLUME_VDB = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "cornell_plume.vdb"
# The plume burning: its Color Attribute reads the density (a darker smoke where it is
# thin), an Attribute node feeding Emission Strength reads the flame; Absorption Color
# black, where vkdiffrender's albedo grid is exact.
FIRE = {"Color": (0.8, 0.7, 0.6, 1.0), "Color Attribute": "density", "Density": 10.0,
        "Absorption Color": (0.0, 0.0, 0.0, 1.0), "Anisotropy": 0.3, "Emission Color": (1.0, 0.5, 0.1, 1.0)}
FLAME_VDB = PLUME_VDB.parent / "cornell_fire_flame.vdb"
FOG = {"Color": (0.9, 0.9, 0.9, 1.0), "Density": 0.12, "Absorption Color": (0.0, 0.0, 0.0, 1.0),
       "Anisotropy": 0.2}
SCENES = ("box_area", "principled_cube", "glowing_cube", "absorption_cube", "world_fog", "orthographic_fog",
          "point_light", "smooth_sphere", "principled_walls", "principled_walls_specular", "vdb_plume", "vdb_fire",
          "painted_cube")


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.world = bpy.data.worlds.new("World")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    return scene


def diffuse_material(name, color):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*color, 1.0)
    out = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(bsdf.outputs[0], out.inputs["Surface"])
    return material


def volume_material(name, node_type, inputs):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    node = nodes.new(node_type)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    out = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(node.outputs[0], out.inputs["Volume"])
    return material


def add_plane(name, location, rotation, size, material):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.object
    obj.name = name
    obj.data.materials.append(material)
    return obj


def add_box_walls(scene):
    """A 2 m box (x, z in [-1, 1], y in [-1, 1]) open towards the camera at -y."""
    white = diffuse_material("white", (0.75, 0.75, 0.75))
    add_plane("floor", (0, 0, -1), (0, 0, 0), 2, white)
    add_plane("ceiling", (0, 0, 1), (3.14159265, 0, 0), 2, white)
    add_plane("back", (0, 1, 0), (1.5707963, 0, 0), 2, white)
    add_plane("left", (-1, 0, 0), (0, 1.5707963, 0), 2, diffuse_material("red", (0.7, 0.15, 0.1)))
    add_plane("right", (1, 0, 0), (0, -1.5707963, 0), 2, diffuse_material("green", (0.15, 0.6, 0.15)))
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.lens_unit = "FOV"
    # Cycles 3.4 does not show area lights to camera rays; the emitter exported for one is
    # visible, so the view keeps the lamp out of frame.
    camera.data.angle = 0.5
    # Cycles starts camera rays at Clip Start (default 0.1 m), skipping the medium in front
    # of the lens; vkdiffrender starts them at the camera.
    camera.data.clip_start = 1e-4
    camera.location = (0, -3.2, -0.2)
    camera.rotation_euler = (1.5707963, 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera


def add_area_light(scene):
    light = bpy.data.lights.new("lamp", "AREA")
    light.shape = "SQUARE"
    light.size = 0.6
    light.energy = 60.0
    light.color = (1.0, 0.9, 0.75)
    obj = bpy.data.objects.new("lamp", light)
    obj.location = (0, 0, 0.995)  # emits down its local -Z
    scene.collection.objects.link(obj)


def principled_walls(specular):
    """The box's Diffuse BSDFs replaced by Principled BSDFs of the same Base Color
    (Roughness 0.5, the default), to measure what Cycles adds to the Lambertian export."""
    for name in ("white", "red", "green"):
        material = bpy.data.materials[name]
        nodes = material.node_tree.nodes
        diffuse = nodes["Diffuse BSDF"]
        color = tuple(diffuse.inputs["Color"].default_value)
        nodes.remove(diffuse)
        bsdf = nodes.new("ShaderNodeBsdfPrincipled")
        bsdf.inputs["Base Color"].default_value = color
        bsdf.inputs["Specular"].default_value = specular
        out = next(n for n in nodes if n.bl_idname == "ShaderNodeOutputMaterial")
        material.node_tree.links.new(bsdf.outputs[0], out.inputs["Surface"])


def area_lights_to_emissive_meshes(scene, radiance_of, polygon_of):
    """Replace every area light by the emitter the export writes for it: a polygon of the
    same corners and radiance, emitting from its front only and black behind. Cycles'
    area lights let rays through (what lies behind the lamp is lit and seen), the
    exported polygon stops them; with this mesh both renderers render one geometry.
    RADIANCE_OF(light object) and POLYGON_OF(light object) are the export's own."""
    for obj in [o for o in scene.objects if o.type == "LIGHT" and o.data.type == "AREA"]:
        radiance, corners = radiance_of(obj), polygon_of(obj)
        material = bpy.data.materials.new(obj.name + ".mesh")
        material.use_nodes = True
        nodes = material.node_tree.nodes
        nodes.clear()
        material.node_tree.links.new(front_only_emission(material.node_tree, radiance),
                                     nodes.new("ShaderNodeOutputMaterial").inputs["Surface"])
        mesh = bpy.data.meshes.new(obj.name + ".mesh")
        mesh.from_pydata([tuple(c) for c in corners], [], [list(range(len(corners)))])
        mesh.materials.append(material)
        name = obj.name
        bpy.data.objects.remove(obj)
        scene.collection.objects.link(bpy.data.objects.new(name + ".mesh", mesh))


def add_cube(name, material, location=(0, 0.1, -0.35), size=0.9):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location, rotation=(0, 0, 0.5))
    obj = bpy.context.object
    obj.name = name
    obj.data.materials.append(material)
    return obj


def painted_cube():
    """A cube whose Diffuse BSDF Color is its colour attribute 'Paint' (read by an Attribute
    node), 0.5 + the local position in each channel: linear, so that every triangulation
    interpolates it alike. The render colour attribute is another one, 'Unread'."""
    material = diffuse_material("painted", (0.3, 0.3, 0.3))
    attribute = material.node_tree.nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "Paint"
    bsdf = material.node_tree.nodes["Diffuse BSDF"]
    material.node_tree.links.new(attribute.outputs["Color"], bsdf.inputs["Color"])
    cube = add_cube("painted", material)
    unread = cube.data.color_attributes.new("Unread", "FLOAT_COLOR", "POINT")
    for value in unread.data:
        value.color = (0.0, 0.0, 0.0, 1.0)
    paint = cube.data.color_attributes.new("Paint", "BYTE_COLOR", "POINT")
    for vertex, value in zip(cube.data.vertices, paint.data):
        value.color = (*(0.5 + c for c in vertex.co), 1.0)
    cube.data.color_attributes.render_color_index = cube.data.color_attributes.find("Unread")


def add_vdb_volume(name, path, material, location, scale):
    """A Volume object reading an OpenVDB file, turned so that the file's +y is up (+z)."""
    volume = bpy.data.volumes.new(name)
    volume.filepath = str(path)
    volume.materials.append(material)
    obj = bpy.data.objects.new(name, volume)
    obj.location = location
    obj.rotation_euler = (1.5707963, 0.0, 0.4)
    obj.scale = (scale, scale, scale)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def fire_vdb():
    """The plume's density and flame grids in one file, as a fire simulation's cache holds
    them: the shipped cornell_fire grids merged by vdb_tool (Debian's libopenvdb-tools)
    into a new temporary directory, removed when Blender exits. The file also holds the
    density's gradient, a vector grid (`grad_density`), for the exports that must refuse
    a vector grid where a scalar one is read."""
    directory = tempfile.mkdtemp(prefix="vkdiffrender_fire")
    atexit.register(shutil.rmtree, directory, True)
    path = pathlib.Path(directory) / "fire.vdb"
    subprocess.run([shutil.which("vdb_tool") or "vdb_tool", "-read", str(PLUME_VDB), str(FLAME_VDB),
                    "-grad", "vdb=1", "keep=1", "-write", str(path)], check=True, stdout=subprocess.DEVNULL)
    return path


def burning_material(name):
    material = volume_material(name, "ShaderNodeVolumePrincipled", FIRE)
    tree = material.node_tree
    node = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
    flame = tree.nodes.new("ShaderNodeAttribute")
    flame.attribute_type = "GEOMETRY"
    flame.attribute_name = "flame"
    tree.links.new(flame.outputs["Fac"], node.inputs["Emission Strength"])
    return material


def build(name):
    """Builds the named test scene in a fresh file and returns the bpy scene."""
    scene = reset()
    add_box_walls(scene)
    if name != "point_light":
        add_area_light(scene)
    if name == "principled_cube":
        add_cube("smoke", volume_material("smoke", "ShaderNodeVolumePrincipled", PRINCIPLED))
    elif name == "glowing_cube":
        add_cube("glow", volume_material("glow", "ShaderNodeVolumePrincipled", GLOWING))
    elif name == "vdb_plume":
        add_vdb_volume("plume", PLUME_VDB, volume_material("plume", "ShaderNodeVolumePrincipled", PLUME),
                       (0.0, 0.1, -0.35), 1.2)
    elif name == "vdb_fire":
        add_vdb_volume("plume", fire_vdb(), burning_material("fire"), (0.0, 0.1, -0.35), 1.2)
    elif name == "absorption_cube":
        add_cube("ink", volume_material("ink", "ShaderNodeVolumeAbsorption", ABSORPTION))
    elif name in ("world_fog", "orthographic_fog"):
        nodes = scene.world.node_tree.nodes
        fog = nodes.new("ShaderNodeVolumePrincipled")
        for key, value in FOG.items():
            fog.inputs[key].default_value = value
        scene.world.node_tree.links.new(fog.outputs[0], nodes["World Output"].inputs["Volume"])
        if name == "orthographic_fog":
            # Parallel rays from across a view 1.6 m square, inside the box's open side.
            scene.camera.data.type, scene.camera.data.ortho_scale = "ORTHO", 1.6
    elif name == "point_light":
        light = bpy.data.lights.new("bulb", "POINT")
        light.energy = 40.0
        light.color = (1.0, 0.85, 0.7)
        light.shadow_soft_size = 0.0
        obj = bpy.data.objects.new("bulb", light)
        obj.location = (0.2, 0.1, 0.6)
        scene.collection.objects.link(obj)
    elif name == "smooth_sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(0, 0.1, -0.45), segments=16, ring_count=8)
        sphere = bpy.context.object
        sphere.name = "sphere"
        bpy.ops.object.shade_smooth()
        # Cycles lifts shadow rays off low-poly smooth meshes by default (a deliberate bias
        # against terminator artefacts); vkdiffrender does not.
        sphere.cycles.shadow_terminator_geometry_offset = 0.0
        sphere.data.materials.append(diffuse_material("sphere", (0.8, 0.8, 0.8)))
    elif name == "painted_cube":
        painted_cube()
    elif name in ("principled_walls", "principled_walls_specular"):
        principled_walls(0.5 if name == "principled_walls_specular" else 0.0)
    elif name != "box_area":
        raise ValueError(f"unknown test scene {name!r}; known: {', '.join(SCENES)}")
    return scene
