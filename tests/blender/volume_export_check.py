"""Run inside Blender for test_volume_export.py: build the box with the smoke plume read
from an OpenVDB file as a Volume object (scenes.py, "vdb_plume"), export OUT/scene.gltf
with the add-on, and write the export's warnings to OUT/warnings.json and the Volume
object's world matrix (glTF's Y-up) to OUT/placement.json.

With --fire the scene is "vdb_fire" instead (the plume burning, its material reading the
file's density and flame grids as colour and emission strength), exported again to
OUT/<case>/scene.gltf (warnings in OUT/<case>/warnings.json) with one change each:
"swapped", Density Attribute "flame"; "absorbing", a grey Absorption Color beside the
Color Attribute; "vector_emission", Emission Strength reading the vector grid
`grad_density` (its unlinked value 2); "vector_density", Density Attribute
`grad_density`; "modified", a Volume Displace and a Geometry Nodes modifier on the
object; "flattened", the object scaled by 0 along z.

  blender -b --factory-startup --python volume_export_check.py -- --out DIR [--fire]"""
import argparse
import json
import pathlib
import sys

import bpy

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[1] / "tools" / "blender")]
import scenes  # noqa: E402
from vkdiffrender_blender import axes, export_scene  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", required=True)
    parser.add_argument("--fire", action="store_true")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = pathlib.Path(args.out)
    scenes.build("vdb_fire" if args.fire else "vdb_plume")
    plume = bpy.data.objects["plume"]
    warnings = export_scene.export_scene(bpy.context, str(out / "scene.gltf"))
    (out / "warnings.json").write_text(json.dumps(warnings))
    placement = axes.Z_UP_TO_Y_UP @ plume.matrix_world
    (out / "placement.json").write_text(json.dumps([list(row) for row in placement]))
    if args.fire:
        tree = plume.active_material.node_tree
        node = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
        attribute = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeAttribute")

        def export_case(case, change, undo):
            change()
            (out / case).mkdir()
            case_warnings = export_scene.export_scene(bpy.context, str(out / case / "scene.gltf"))
            (out / case / "warnings.json").write_text(json.dumps(case_warnings))
            undo()

        export_case("swapped", lambda: setattr(node.inputs["Density Attribute"], "default_value", "flame"),
                    lambda: setattr(node.inputs["Density Attribute"], "default_value", "density"))
        export_case("absorbing",
                    lambda: setattr(node.inputs["Absorption Color"], "default_value", (0.2, 0.2, 0.2, 1.0)),
                    lambda: setattr(node.inputs["Absorption Color"], "default_value", (0.0, 0.0, 0.0, 1.0)))

        def read_vector_grid():
            attribute.attribute_name = "grad_density"
            node.inputs["Emission Strength"].default_value = 2.0

        export_case("vector_density", lambda: setattr(node.inputs["Density Attribute"], "default_value", "grad_density"),
                    lambda: setattr(node.inputs["Density Attribute"], "default_value", "density"))

        def add_modifiers():
            plume.modifiers.new("Displace", "VOLUME_DISPLACE")
            plume.modifiers.new("Shift", "NODES").node_group = bpy.data.node_groups.new("Shift", "GeometryNodeTree")

        export_case("modified", add_modifiers, plume.modifiers.clear)
        scale = plume.scale.copy()
        export_case("flattened", lambda: setattr(plume, "scale", (scale.x, scale.y, 0.0)),
                    lambda: setattr(plume, "scale", scale))
        export_case("vector_emission", read_vector_grid, lambda: None)


if __name__ == "__main__":
    main()
