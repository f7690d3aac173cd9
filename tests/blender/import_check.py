"""Run inside Blender, in two steps, for test_import.py.

  --step export --out DIR: build the Principled Volume cube in the box, add a World fog
      and a point light 'bulb', and export DIR/scene.gltf with the add-on; then set the
      camera's Clip Start and Cycles' bounce limits to Blender's defaults and export
      DIR/defaults.gltf. The warnings of both go to DIR/export_warnings.json.
  --step import --gltf FILE --out DIR: in an empty file, run Blender's own glTF importer
      on FILE and record whether it fails on numpy.bool; then, in another empty file,
      import FILE with the add-on's operator and write DIR/imported.json: the medium each
      material's and the World's nodes now give, each light's radiant intensity or
      irradiance as the add-on's mappings read its Blender values, whether numpy.bool
      exists before and after, the camera a copy of FILE with an orthographic camera
      imports as, and where the camera lands in files of Unit Scale 1 and 0.01."""
import argparse
import json
import pathlib
import sys

import bpy
import numpy

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[1] / "tools" / "blender")]
import scenes  # noqa: E402
import vkdiffrender_blender  # noqa: E402
from vkdiffrender_blender import export_scene, import_scene, mappings, node_graph  # noqa: E402


def build_and_export(out):
    scene = scenes.build("principled_cube")
    nodes = scene.world.node_tree.nodes
    fog = nodes.new("ShaderNodeVolumePrincipled")
    for key, value in scenes.FOG.items():
        fog.inputs[key].default_value = value
    scene.world.node_tree.links.new(fog.outputs[0], nodes["World Output"].inputs["Volume"])
    light = bpy.data.lights.new("bulb", "POINT")
    light.energy, light.color, light.shadow_soft_size = 40.0, (1.0, 0.85, 0.7), 0.0
    obj = bpy.data.objects.new("bulb", light)
    obj.location = (0.2, -0.3, 0.6)
    scene.collection.objects.link(obj)
    vkdiffrender_blender.register()
    scenes.configure_cycles(scene, 16, 1, 4, 1)
    warnings = {"scene": export_scene.export_scene(bpy.context, str(out / "scene.gltf"))}
    scene.camera.data.clip_start = 0.1
    scene.cycles.diffuse_bounces, scene.cycles.glossy_bounces, scene.cycles.volume_bounces = 4, 4, 0
    scene.cycles.max_bounces = 12
    warnings["defaults"] = export_scene.export_scene(bpy.context, str(out / "defaults.gltf"))
    (out / "export_warnings.json").write_text(json.dumps(warnings, indent=1))


def plain_importer_error(gltf):
    """The message of Blender's own importer's failure on FILE, or None."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        bpy.ops.import_scene.gltf(filepath=str(gltf))
    except (AttributeError, RuntimeError) as error:
        return str(error)
    return None


def medium_values(owner):
    medium = node_graph.medium_of(owner, [], owner.name)
    return None if medium is None else {"sigma_a": medium.sigma_a, "sigma_s": medium.sigma_s, "g": medium.g}


def import_and_read(gltf, out):
    result = {"plain_importer_error": plain_importer_error(gltf)}
    bpy.ops.wm.read_factory_settings(use_empty=True)
    vkdiffrender_blender.register()
    result["numpy_bool_before"] = hasattr(numpy, "bool")
    result["unreadable"] = {}
    (out / "not_gltf.gltf").write_text("these are not the bytes of a glTF file")
    for name in ("not_gltf.gltf", "missing.gltf"):
        try:
            bpy.ops.import_scene.vkdiffrender(filepath=str(out / name))
        except RuntimeError as error:  # an operator's error report, as Python sees it
            result["unreadable"][name] = str(error)
    # A medium's coefficient as text and a light index past the lights, each in a copy
    # beside the file so that its buffer resolves.
    doc = json.loads(gltf.read_text())
    medium = next(m["extensions"]["VKDR_participating_media"] for m in doc["materials"]
                  if "VKDR_participating_media" in m.get("extensions", {}))
    medium["sigma_a"] = "lots"
    (gltf.parent / "text_medium.gltf").write_text(json.dumps(doc))
    doc = json.loads(gltf.read_text())
    next(n for n in doc["nodes"] if "KHR_lights_punctual" in n.get("extensions", {}))[
        "extensions"]["KHR_lights_punctual"]["light"] = 99
    (gltf.parent / "light_index.gltf").write_text(json.dumps(doc))
    # Values the add-on's checks pass, on which Blender's importer fails part way: after the
    # camera's object, at a node whose mesh the file lacks.
    (gltf.parent / "half_made.gltf").write_text(json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "Made", "camera": 0}, {"name": "Broken", "mesh": 5}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}]}))
    counts = lambda: {kind: len(getattr(bpy.data, kind)) for kind in ("objects", "materials", "cameras")}  # noqa: E731
    result["refused_import"] = {"before": counts()}
    for name in ("text_medium.gltf", "light_index.gltf", "half_made.gltf"):
        try:
            bpy.ops.import_scene.vkdiffrender(filepath=str(gltf.parent / name))
        except RuntimeError as error:
            result["unreadable"][name] = str(error)
    result["refused_import"]["after"] = counts()
    # The same scene through an orthographic camera twice as wide as it is high.
    doc = json.loads(gltf.read_text())
    doc["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 2.0, "ymag": 0.75, "znear": 0.0, "zfar": 100.0}}]
    (gltf.parent / "orthographic.gltf").write_text(json.dumps(doc))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.vkdiffrender(filepath=str(gltf.parent / "orthographic.gltf"))
    camera = bpy.context.scene.camera.data
    result["orthographic_camera"] = {"type": camera.type, "sensor_fit": camera.sensor_fit,
                                     "ortho_scale": camera.ortho_scale}
    # The camera's place imported into a file whose Unit Scale is 1, then 0.01.
    result["camera_location"] = {}
    for scale in (1.0, 0.01):
        bpy.ops.wm.read_factory_settings(use_empty=True)
        bpy.context.scene.unit_settings.scale_length = scale
        bpy.ops.import_scene.vkdiffrender(filepath=str(gltf))
        result["camera_location"][str(scale)] = {
            "location": list(bpy.context.scene.camera.matrix_world.translation),
            "unit_scale_after": bpy.context.scene.unit_settings.scale_length}
    bpy.ops.wm.read_factory_settings(use_empty=True)  # the add-on stays registered
    bpy.ops.import_scene.vkdiffrender(filepath=str(gltf))
    result["numpy_bool_after"] = hasattr(numpy, "bool")
    result["media"] = {m.name: medium_values(m) for m in bpy.data.materials if medium_values(m) is not None}
    world = bpy.context.scene.world
    result["world"] = {"name": world.name, **medium_values(world)} if world and medium_values(world) else None
    result["lights"] = {}
    for obj in bpy.context.scene.objects:
        if obj.type == "LIGHT":
            light = obj.data
            value = (mappings.sun_irradiance(light.color, light.energy) if light.type == "SUN"
                     else mappings.point_light_intensity(light.color, light.energy))
            result["lights"][obj.name] = list(value)
    # KHR_materials_volume counts behind a surface that transmits all light only, as
    # vkdiffrender reads it; an unnamed material is matched by the name Blender's importer
    # gives it.
    volume = {"attenuationDistance": 2.0, "attenuationColor": [0.5, 0.5, 0.5]}
    volumes = {"materials": [
        {"name": "Clear", "extensions": {"KHR_materials_volume": volume,
                                         "KHR_materials_transmission": {"transmissionFactor": 1.0}}},
        {"name": "Opaque", "extensions": {"KHR_materials_volume": volume}},
        {"extensions": {"VKDR_participating_media": {"sigma_a": 1.0}}}]}  # unnamed: Blender's importer's name
    result["media_of_volume_materials"] = [name for name, _, _ in import_scene.material_media(volumes)]
    lights = {"extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}, {"type": "spot", "name": "Lamp"}]}},
              "nodes": [{"extensions": {"KHR_lights_punctual": {"light": i}}} for i in (0, 1)] +
                       [{"name": "Named", "extensions": {"KHR_lights_punctual": {"light": 0}}}]}
    result["light_objects"] = [name for name, _, _ in import_scene.light_values(lights)]
    (out / "imported.json").write_text(json.dumps(result, indent=1))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--step", choices=("export", "import"), required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--gltf")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    if args.step == "export":
        build_and_export(pathlib.Path(args.out))
    else:
        import_and_read(pathlib.Path(args.gltf), pathlib.Path(args.out))


if __name__ == "__main__":
    main()
