"""Run inside Blender: build test scenes, export each with the add-on, render it with
Cycles and with vkdiffrender at several seeds, and store every render as a .npy array
(linear RGB, rows from the top) in OUT/<scene>/. vkdiffrender's messages go to
OUT/<scene>/vkdr_warnings.txt; a scene it refuses has no vkdr_*.npy.

blender -b --factory-startup --python-exit-code 1 --python tests/blender/render_both.py --
    --scenes box_area,principled_cube --out DIR --cli VKDIFFRENDER [--size 32]
    [--cycles-spp 256] [--vkdr-spp 256] [--seeds 1,2] [--max-depth 4]
    [--cycles-area-lights lights|meshes] [--clip-start 1e-4] [--cycles-volume-bounces N]

--cycles-area-lights meshes renders Cycles with each area light replaced, after the
export, by the exported emitter as a mesh (scenes.area_lights_to_emissive_meshes), so that
both renderers see the same geometry; `lights` keeps Cycles' area lights. --clip-start
sets the camera's Clip Start (the scenes' own: 1e-4; Blender's default: 0.1);
--cycles-volume-bounces overrides Cycles' Volume bounces (otherwise max depth - 1).
compare_renders.py prints the ratios and z-scores of the stored renders.
"""
import argparse
import pathlib
import subprocess
import sys

import bpy
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[1] / "tools" / "blender")]
import cycles_reference  # noqa: E402
import scenes  # noqa: E402
import vkdiffrender_blender  # noqa: E402
from vkdiffrender_blender import axes, export_scene, mappings  # noqa: E402


def render_cycles(scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return cycles_reference.load_exr(path)


def render_vkdiffrender(cli, gltf, path, args, seed):
    """Renders with the command line; its warnings go to vkdr_warnings.txt beside the scene."""
    result = subprocess.run([cli, "render", str(gltf), "-o", str(path), "--spp", str(args.vkdr_spp),
                             "--seed", str(seed), "--width", str(args.size), "--height", str(args.size),
                             "--max-depth", str(args.max_depth)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    (path.parent / "vkdr_warnings.txt").write_text(result.stderr)
    return cycles_reference.load_exr(path) if result.returncode == 0 else None


def exported_radiance(obj):
    corners = [axes.blender_to_gltf(p) for p in export_scene.area_light_polygon(obj)]
    return mappings.area_light_radiance(obj.data.color, obj.data.energy, export_scene.polygon_area(corners))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scenes", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--cli", required=True)
    parser.add_argument("--size", type=int, default=32)
    parser.add_argument("--cycles-spp", type=int, default=256)
    parser.add_argument("--vkdr-spp", type=int, default=256)
    parser.add_argument("--seeds", default="1,2")
    parser.add_argument("--max-depth", type=int, default=4)
    parser.add_argument("--cycles-area-lights", choices=("lights", "meshes"), default="lights")
    parser.add_argument("--clip-start", type=float)
    parser.add_argument("--cycles-volume-bounces", type=int)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    seeds = [int(s) for s in args.seeds.split(",")]
    for name in args.scenes.split(","):
        out = pathlib.Path(args.out) / name
        out.mkdir(parents=True, exist_ok=True)
        scene = scenes.build(name)
        if args.clip_start is not None:
            scene.camera.data.clip_start = args.clip_start
        vkdiffrender_blender.register()
        cycles_reference.configure_cycles(scene, args.size, args.cycles_spp, args.max_depth, seeds[0])
        if args.cycles_volume_bounces is not None:
            scene.cycles.volume_bounces = args.cycles_volume_bounces
        bpy.ops.wm.save_as_mainfile(filepath=str(out / "scene.blend"))
        warnings = export_scene.export_scene(bpy.context, str(out / "scene.gltf"))
        (out / "warnings.txt").write_text("".join(w + "\n" for w in warnings))
        if args.cycles_area_lights == "meshes":
            scenes.area_lights_to_emissive_meshes(scene, exported_radiance, export_scene.area_light_polygon)
        for seed in seeds:
            scene.cycles.seed = seed
            np.save(out / f"cycles_{seed}.npy", render_cycles(scene, out / f"cycles_{seed}.exr"))
            image = render_vkdiffrender(args.cli, out / "scene.gltf", out / f"vkdr_{seed}.exr", args, seed)
            if image is None:
                break  # vkdr_warnings.txt says why; the test reports it
            np.save(out / f"vkdr_{seed}.npy", image)
        vkdiffrender_blender.unregister()


if __name__ == "__main__":
    main()
