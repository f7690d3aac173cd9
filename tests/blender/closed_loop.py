"""Run inside Blender, in two steps, for test_closed_loop.py.

  --step target --out DIR: build the Principled Volume cube, render the Cycles target
      (seeds 1 and 2), then set the volume to a wrong start, save start.blend, render it
      (seeds 1 and 2) and export scene.gltf with the add-on.
  --step fitted --out DIR: open start.blend, write DIR/run/params.json back with the
      add-on, save fitted.blend, the medium its nodes now give (fitted_medium.json), and
      render it with Cycles (seeds 1 and 2).
Renders are stored as .npy (linear RGB, rows from the top)."""
import argparse
import json
import pathlib
import sys

import bpy
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[1] / "tools" / "blender")]
import render_both  # noqa: E402  (its main() runs only as a script)
import scenes  # noqa: E402
import vkdiffrender_blender  # noqa: E402
from vkdiffrender_blender import export_scene, node_graph, write_back  # noqa: E402

SIZE, SPP, MAX_DEPTH = 32, 512, 2
START = {"Color": (0.5, 0.5, 0.5, 1.0), "Density": 1.0, "Absorption Color": (0.0, 0.0, 0.0, 1.0)}


def render(scene, out, name, seeds):
    for seed in seeds:
        scene.cycles.seed = seed
        np.save(out / f"{name}_{seed}.npy", render_both.render_cycles(scene, out / f"{name}_{seed}.exr"))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--step", choices=("target", "fitted"), required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    out = pathlib.Path(args.out)
    if args.step == "target":
        scene = scenes.build("principled_cube")
        scenes.configure_cycles(scene, SIZE, SPP, MAX_DEPTH, 1)
        render(scene, out, "target", (1, 2))
        node = bpy.data.materials["smoke"].node_tree.nodes["Principled Volume"]
        for key, value in START.items():
            node.inputs[key].default_value = value
        bpy.ops.wm.save_as_mainfile(filepath=str(out / "start.blend"))
        render(scene, out, "start", (1, 2))
        vkdiffrender_blender.register()
        export_scene.export_scene(bpy.context, str(out / "scene.gltf"))
    else:
        bpy.ops.wm.open_mainfile(filepath=str(out / "start.blend"))
        vkdiffrender_blender.register()
        warnings = write_back.apply_params_file(bpy.context.scene, bpy.context.view_layer,
                                                str(out / "run" / "params.json"))
        if warnings:
            raise SystemExit("\n".join(warnings))
        bpy.ops.wm.save_as_mainfile(filepath=str(out / "fitted.blend"))
        medium = node_graph.medium_of(bpy.data.materials["smoke"], [], "smoke")
        (out / "fitted_medium.json").write_text(json.dumps({"sigma_a": medium.sigma_a, "sigma_s": medium.sigma_s}))
        render(bpy.context.scene, out, "fitted", (1, 2))


if __name__ == "__main__":
    main()
