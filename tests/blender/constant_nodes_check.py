"""Run inside Blender for test_constant_nodes.py: for each case, an Emission plane that
fills an orthographic camera's view, its Strength or Color fed by constant nodes (Value,
RGB and Math nodes), rendered by Cycles; OUT/constant_nodes.json holds, per case, the
pixel Cycles renders and the value the add-on's export reads from the same input
(node_graph.constant), with its warnings.

  blender -b --factory-startup --python constant_nodes_check.py -- --out DIR"""
import argparse
import json
import pathlib
import sys

import bpy

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE.parents[1] / "tools" / "blender")]
import cycles_reference  # noqa: E402
from vkdiffrender_blender import node_graph  # noqa: E402

# (name, Math operation, its three inputs, Use Clamp): each feeds the Emission's Strength.
MATH_CASES = [
    ("add", "ADD", (0.3, 0.45, 0.0), False),
    ("subtract", "SUBTRACT", (2.0, 0.75, 0.0), False),
    ("multiply", "MULTIPLY", (1.5, 0.6, 0.0), False),
    ("divide", "DIVIDE", (1.0, 4.0, 0.0), False),
    ("divide_by_zero", "DIVIDE", (1.0, 0.0, 0.0), False),
    ("multiply_add", "MULTIPLY_ADD", (0.5, 3.0, 0.25), False),
    ("power", "POWER", (2.0, 1.5, 0.0), False),
    ("power_of_negative_fraction", "POWER", (-2.0, 0.5, 0.0), False),
    ("power_of_negative_integer", "POWER", (-2.0, 2.0, 0.0), False),
    ("logarithm", "LOGARITHM", (8.0, 2.0, 0.0), False),
    ("logarithm_of_negative", "LOGARITHM", (-1.0, 2.0, 0.0), False),
    ("sqrt", "SQRT", (2.25, 0.0, 0.0), False),
    ("sqrt_of_negative", "SQRT", (-4.0, 0.0, 0.0), False),
    ("exponent", "EXPONENT", (0.5, 0.0, 0.0), False),
    ("absolute", "ABSOLUTE", (-0.7, 0.0, 0.0), False),
    ("minimum", "MINIMUM", (0.3, 0.8, 0.0), False),
    ("maximum", "MAXIMUM", (0.3, 0.8, 0.0), False),
    ("clamped_add", "ADD", (0.8, 0.9, 0.0), True),
    ("unused_third_input", "ADD", (0.25, 0.5, 7.0), False),
]


def emission_plane():
    """An empty scene whose orthographic camera sees only an Emission plane; returns the
    Emission node."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 1.0
    camera.location = (0.0, 0.0, 2.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    bpy.ops.mesh.primitive_plane_add(size=4.0)
    material = bpy.data.materials.new("Glow")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(emission.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    bpy.context.object.data.materials.append(material)
    world = bpy.data.worlds.new("Dark")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    cycles_reference.configure_cycles(scene, 2, 1, 1, 0, threads=2)
    return emission


def value_node(tree, value):
    node = tree.nodes.new("ShaderNodeValue")
    node.outputs[0].default_value = value
    return node.outputs[0]


def math_node(tree, operation, inputs, clamp=False):
    node = tree.nodes.new("ShaderNodeMath")
    node.operation = operation
    node.use_clamp = clamp
    for socket, value in zip(node.inputs, inputs):
        socket.default_value = value
    return node


def math_case(operation, inputs, clamp):
    emission = emission_plane()
    tree = emission.id_data
    tree.links.new(math_node(tree, operation, inputs, clamp).outputs[0], emission.inputs["Strength"])
    return emission


def chain_case():
    """A Value node times 2.5 by one Math node, plus 0.1 by a second, through a Reroute."""
    emission = emission_plane()
    tree = emission.id_data
    times = math_node(tree, "MULTIPLY", (0.0, 2.5, 0.0))
    tree.links.new(value_node(tree, 0.4), times.inputs[0])
    plus = math_node(tree, "ADD", (0.0, 0.1, 0.0))
    tree.links.new(times.outputs[0], plus.inputs[0])
    reroute = tree.nodes.new("NodeReroute")
    tree.links.new(plus.outputs[0], reroute.inputs[0])
    tree.links.new(reroute.outputs[0], emission.inputs["Strength"])
    return emission


def rgb_colour_case():
    """An RGB node feeding the Color."""
    emission = emission_plane()
    tree = emission.id_data
    rgb = tree.nodes.new("ShaderNodeRGB")
    rgb.outputs[0].default_value = (0.2, 0.5, 0.8, 1.0)
    tree.links.new(rgb.outputs[0], emission.inputs["Color"])
    return emission


def grey_colour_case():
    """A Math node's float feeding the Color (Cycles takes it as that grey)."""
    emission = emission_plane()
    tree = emission.id_data
    tree.links.new(math_node(tree, "MULTIPLY", (0.5, 0.7, 0.0)).outputs[0], emission.inputs["Color"])
    return emission


def texture_case():
    """A Math node of a Noise Texture: not constant, so not evaluated."""
    emission = emission_plane()
    tree = emission.id_data
    times = math_node(tree, "MULTIPLY", (0.0, 2.0, 0.0))
    tree.links.new(tree.nodes.new("ShaderNodeTexNoise").outputs["Fac"], times.inputs[0])
    tree.links.new(times.outputs[0], emission.inputs["Strength"])
    return emission


def measure(emission, out, name):
    """Cycles' pixel and the exported value of the Emission's Color times Strength."""
    bpy.context.scene.render.filepath = str(out / f"{name}.exr")
    bpy.ops.render.render(write_still=True)
    pixel = cycles_reference.load_exr(out / f"{name}.exr")[0, 0]
    warnings = []
    colour = node_graph.constant(emission, "Color", warnings, name)
    strength = node_graph.constant(emission, "Strength", warnings, name)
    return {"cycles": [float(c) for c in pixel], "exported": [c * strength for c in colour[:3]],
            "warnings": warnings}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", required=True)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = pathlib.Path(args.out)
    results = {}
    for name, operation, inputs, clamp in MATH_CASES:
        results[name] = measure(math_case(operation, inputs, clamp), out, name)
    for name, case in (("chain", chain_case), ("rgb_colour", rgb_colour_case), ("grey_colour", grey_colour_case),
                       ("texture", texture_case)):
        results[name] = measure(case(), out, name)
    (out / "constant_nodes.json").write_text(json.dumps(results, indent=1))


main()
