"""Equal-time comparison of vkdiffrender with Cycles, in one Blender process on the same cores.

blender -b --factory-startup --python-exit-code 1 --python tools/compare_with_cycles.py --
    --cli build/src/cli/vkdiffrender SCENE.gltf [SCENE.gltf ...] [--size 128] [--spp 256]
    [--max-depth 9] [--seeds 1,2] [--threads 2] [--out DIR]

For each scene, at each of the two seeds in turn, vkdiffrender renders it (a subprocess; set
LP_NUM_THREADS for lavapipe) and then Cycles renders it: imported with the project's add-on
(media as Principled Volumes, the background), surfaces made Lambertian as vkdiffrender
renders them, and configured as an unbiased reference (tools/blender/cycles_reference.py).
Materials must be constant: a scene with textures is refused, naming the material.
From each renderer's pair of images: the per-pixel relative noise of one render (as
src/bench/image_noise.cpp computes it), its efficiency 1 / (noise^2 x seconds), and the
image mean with its standard error. Prints a markdown table and writes DIR/comparison.json;
the renders are DIR/<scene>/vkdr_<seed>.exr and cycles_<seed>.exr.
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import time

import bpy
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "blender"))
import cycles_reference  # noqa: E402
import vkdiffrender_blender  # noqa: E402
from vkdiffrender_blender import import_scene, node_graph  # noqa: E402

CLI_TIME_LINE = re.compile(r"^([0-9.eE+-]+) s, ")


class InputError(Exception):
    """Bad input: reported as one `error:` line, exit code 2."""


# --- arguments ---------------------------------------------------------------------------

def parse_args(argv):
    parser = argparse.ArgumentParser(prog="compare_with_cycles.py", description=__doc__.split("\n")[0])
    parser.add_argument("scenes", nargs="+", type=pathlib.Path)
    parser.add_argument("--cli", required=True, type=pathlib.Path, help="the vkdiffrender executable")
    parser.add_argument("--size", type=int, default=128, help="image width and height")
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--max-depth", type=int, default=9)
    parser.add_argument("--seeds", default="1,2", help="two different seeds")
    parser.add_argument("--threads", type=int, default=2, help="Cycles' render threads")
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("cycles_comparison"))
    args = parser.parse_args(argv)
    for name in ("size", "spp", "max_depth", "threads"):
        if getattr(args, name) < 1:
            raise InputError(f"--{name.replace('_', '-')}: must be at least 1, got {getattr(args, name)}")
    try:
        args.seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        raise InputError(f"--seeds: expected two integers like 1,2, got {args.seeds!r}") from None
    if len(args.seeds) != 2 or args.seeds[0] == args.seeds[1]:
        raise InputError(f"--seeds: expected two different seeds, got {args.seeds}")
    if not os.access(args.cli, os.X_OK) or args.cli.is_dir():
        raise InputError(f"--cli: {args.cli} is not an executable file")
    for scene in args.scenes:
        if not scene.is_file():
            raise InputError(f"{scene}: no such file")
    stems = [scene.stem for scene in args.scenes]
    if len(set(stems)) != len(stems):
        raise InputError(f"scenes: two files share a name ({', '.join(stems)}); their renders would share a folder")
    if args.out.exists() and not args.out.is_dir():
        raise InputError(f"--out: {args.out} exists and is not a folder")
    return args


# --- the two renderers ---------------------------------------------------------------------

def render_vkdiffrender(args, scene, seed, path):
    """Renders with the command line; returns (wall seconds of the process, render seconds
    the command line reports)."""
    command = [str(args.cli), "render", str(scene), "-o", str(path), "--width", str(args.size),
               "--height", str(args.size), "--spp", str(args.spp), "--max-depth", str(args.max_depth),
               "--seed", str(seed)]
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        message = (result.stderr.strip().splitlines() or ["(no message)"])[-1]
        raise InputError(f"{scene}: vkdiffrender render failed (exit {result.returncode}): {message}")
    reported = [m for m in map(CLI_TIME_LINE.match, result.stdout.splitlines()) if m]
    if not reported:
        raise RuntimeError(f"vkdiffrender printed no 'X s, ... paths/s' line: {result.stdout!r}")
    return wall, float(reported[-1].group(1))


def render_cycles(scene, seed, path):
    """Renders the current Blender scene; returns the wall seconds of the render alone."""
    scene.cycles.seed = seed
    start = time.perf_counter()
    bpy.ops.render.render()
    wall = time.perf_counter() - start
    bpy.data.images["Render Result"].save_render(str(path), scene=scene)
    return wall


# --- the Cycles scene ----------------------------------------------------------------------

def principled_values(material):
    """Base colour and emitted radiance of an imported glTF material's Principled BSDF."""
    bsdf = node_graph.surface_node(material)
    if bsdf is None or bsdf.bl_idname != "ShaderNodeBsdfPrincipled":
        raise InputError(f"material '{material.name}': the glTF importer made no Principled BSDF for it")
    for name in ("Base Color", "Emission", "Emission Strength"):
        if bsdf.inputs[name].is_linked:
            raise InputError(f"material '{material.name}': a texture on {name}; the comparison takes constants only")
    base = tuple(bsdf.inputs["Base Color"].default_value)[:3]
    strength = bsdf.inputs["Emission Strength"].default_value
    radiance = tuple(c * strength for c in bsdf.inputs["Emission"].default_value[:3])
    return base, radiance


def make_lambertian(material):
    """vkdiffrender's surface: a Lambertian BSDF of the base colour on both sides, plus, for
    an emitter, its emission, from the front only unless glTF's doubleSided (which the
    importer turns into Backface Culling off). Medium boundaries (no Surface) stay clear."""
    tree = material.node_tree
    out = node_graph.output_node(tree, "OUTPUT_MATERIAL")
    if out is None or not out.inputs["Surface"].is_linked:
        return
    base, radiance = principled_values(material)
    tree.nodes.remove(node_graph.surface_node(material))
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*base, 1.0)
    surface = diffuse.outputs[0]
    if max(radiance) > 0.0:
        if material.use_backface_culling:
            emission = cycles_reference.front_only_emission(tree, radiance)
        else:
            node = tree.nodes.new("ShaderNodeEmission")
            node.inputs["Color"].default_value = (*radiance, 1.0)
            emission = node.outputs[0]
        add = tree.nodes.new("ShaderNodeAddShader")
        tree.links.new(surface, add.inputs[0])
        tree.links.new(emission, add.inputs[1])
        surface = add.outputs[0]
    tree.links.new(surface, out.inputs["Surface"])


def default_material():
    """glTF's default material, as vkdiffrender reads it: white, not emissive."""
    material = bpy.data.materials.new("default")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    return material


def first_camera(gltf_path, scene):
    """The camera vkdiffrender renders from: the first glTF node with a camera."""
    doc = import_scene.read_gltf_json(gltf_path)
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    for node in doc.get("nodes", []):
        if "camera" in node:
            camera = import_scene.match(cameras, node.get("name", ""), renamed=[])
            if camera is not None:
                return camera
    if cameras:
        return cameras[0]
    raise InputError(f"{gltf_path}: no camera")


def build_cycles_scene(gltf_path, args):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    vkdiffrender_blender.register()
    scene = bpy.context.scene
    try:
        for warning in import_scene.import_scene(bpy.context, str(gltf_path)):
            print(f"warning: {gltf_path}: {warning}", file=sys.stderr)
    except (OSError, ValueError, RuntimeError) as error:
        raise InputError(f"{gltf_path}: the import failed: {error}") from None
    finally:
        vkdiffrender_blender.unregister()
    for obj in scene.objects:
        if obj.type == "MESH" and not obj.data.materials:
            obj.data.materials.append(default_material())
    for material in bpy.data.materials:
        if material.use_nodes:
            make_lambertian(material)
    if scene.world is None:  # no background and no scene-wide medium: black, as in vkdiffrender
        scene.world = bpy.data.worlds.new("World")
        scene.world.use_nodes = True
        scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.camera = first_camera(gltf_path, scene)
    # Cycles starts camera rays at Clip Start; vkdiffrender starts them at the camera.
    scene.camera.data.clip_start = 1e-4
    cycles_reference.configure_cycles(scene, args.size, args.spp, args.max_depth, args.seeds[0], args.threads)
    return scene


# --- statistics ----------------------------------------------------------------------------

def luminance(image):
    return image.astype(np.float64).mean(axis=2)


def relative_noise(a, b):
    """One render's per-pixel relative noise, from two renders that differ in the seed:
    over the pixels with light, the root mean square of |a - b| / sqrt(2) over their mean
    (src/bench/image_noise.cpp)."""
    la, lb = luminance(a), luminance(b)
    mean = 0.5 * (la + lb)
    lit = (mean > 0.0) & np.isfinite(mean)
    if not lit.any():
        return None
    deviation = (la[lit] - lb[lit]) / math.sqrt(2.0)
    return float(np.sqrt(np.mean((deviation / mean[lit]) ** 2)))


def image_mean(a, b):
    """The mean luminance of the two renders and its standard error. Pixels are independent
    estimates, so one render's mean has variance sum over pixels of (a - b)^2 / 2, over the
    pixel count squared; the two renders' average has half of it."""
    la, lb = luminance(a), luminance(b)
    count = la.size
    return float(0.5 * (la.mean() + lb.mean())), float(np.sqrt(np.sum((la - lb) ** 2)) / (2.0 * count))


def efficiency(noise, seconds):
    return 1.0 / (noise * noise * seconds) if noise and seconds > 0.0 else None


def renderer_figures(images, seconds):
    noise = relative_noise(*images)
    mean, error = image_mean(*images)
    return {"seconds": seconds, "noise": noise, "efficiency": efficiency(noise, float(np.mean(seconds))),
            "mean": mean, "mean_error": error}


def ratio(a, b):
    return a / b if a is not None and b else None


def compare(vkdr, cycles):
    """The ratios vkdiffrender / Cycles, and the z-score of the image means' difference."""
    error = math.hypot(vkdr["mean_error"], cycles["mean_error"])
    return {"time": ratio(float(np.mean(vkdr["seconds"])), float(np.mean(cycles["seconds"]))),
            "noise": ratio(vkdr["noise"], cycles["noise"]),
            "efficiency": ratio(vkdr["efficiency"], cycles["efficiency"]),
            "mean": ratio(vkdr["mean"], cycles["mean"]),
            "mean_z": (vkdr["mean"] - cycles["mean"]) / error if error > 0.0 else None}


def geometric_mean(values):
    values = [v for v in values if v]
    return float(np.exp(np.mean(np.log(values)))) if values else None


# --- one scene -----------------------------------------------------------------------------

def measure_scene(gltf_path, args):
    """Both renderers at both seeds, alternately: vkdiffrender, Cycles, vkdiffrender, Cycles."""
    scene = build_cycles_scene(gltf_path, args)
    out = args.out / gltf_path.stem
    out.mkdir(parents=True, exist_ok=True)
    images = {"vkdiffrender": [], "cycles": []}
    seconds = {"vkdiffrender": [], "vkdiffrender_reported": [], "cycles": []}
    for seed in args.seeds:
        path = out / f"vkdr_{seed}.exr"
        wall, reported = render_vkdiffrender(args, gltf_path, seed, path)
        seconds["vkdiffrender"].append(wall)
        seconds["vkdiffrender_reported"].append(reported)
        images["vkdiffrender"].append(cycles_reference.load_exr(path))
        path = out / f"cycles_{seed}.exr"
        seconds["cycles"].append(render_cycles(scene, seed, path))
        images["cycles"].append(cycles_reference.load_exr(path))
        print(f"{gltf_path.stem} seed {seed}: vkdiffrender {seconds['vkdiffrender'][-1]:.2f} s "
              f"(reports {reported:.2f} s), Cycles {seconds['cycles'][-1]:.2f} s", file=sys.stderr)
    vkdr = renderer_figures(images["vkdiffrender"], seconds["vkdiffrender"])
    vkdr["reported_seconds"] = seconds["vkdiffrender_reported"]
    vkdr["reported_efficiency"] = efficiency(vkdr["noise"], float(np.mean(vkdr["reported_seconds"])))
    cycles = renderer_figures(images["cycles"], seconds["cycles"])
    return {"scene": str(gltf_path), "vkdiffrender": vkdr, "cycles": cycles, "ratios": compare(vkdr, cycles)}


# --- report --------------------------------------------------------------------------------

def number(value, digits=3):
    return "-" if value is None else f"{value:.{digits}g}"


def markdown_table(results, overall):
    lines = ["| scene | seconds, vkdiffrender (its own count) / Cycles | time ratio | noise, vkdiffrender / Cycles "
             "| noise ratio | efficiency ratio | image mean, vkdiffrender / Cycles | mean ratio (z) |",
             "|---|--:|--:|--:|--:|--:|--:|--:|"]
    for result in results:
        v, c, r = result["vkdiffrender"], result["cycles"], result["ratios"]
        lines.append(
            f"| {pathlib.Path(result['scene']).stem} "
            f"| {np.mean(v['seconds']):.2f} ({np.mean(v['reported_seconds']):.2f}) / {np.mean(c['seconds']):.2f} "
            f"| {number(r['time'])} | {number(v['noise'])} / {number(c['noise'])} | {number(r['noise'])} "
            f"| {number(r['efficiency'])} | {number(v['mean'], 4)} / {number(c['mean'], 4)} "
            f"| {number(r['mean'], 4)} ({number(r['mean_z'], 2)}) |")
    lines.append(f"| overall (geometric mean) | | {number(overall['time'])} | | {number(overall['noise'])} "
                 f"| {number(overall['efficiency'])} | | |")
    return "\n".join(lines)


def write_json(path, data):
    """Atomically: a reader never sees half a file."""
    partial = path.with_name(path.name + ".partial")
    partial.write_text(json.dumps(data, indent=1) + "\n")
    partial.replace(path)


def main(argv):
    args = parse_args(argv)
    results = [measure_scene(scene, args) for scene in args.scenes]
    overall = {key: geometric_mean([r["ratios"][key] for r in results]) for key in ("time", "noise", "efficiency")}
    settings = {"size": args.size, "spp": args.spp, "max_depth": args.max_depth, "seeds": args.seeds,
                "cycles_threads": args.threads, "lp_num_threads": os.environ.get("LP_NUM_THREADS"),
                "blender": bpy.app.version_string, "date": time.strftime("%Y-%m-%d")}
    print(f"{args.size}x{args.size}, {args.spp} spp, max depth {args.max_depth}, seeds {args.seeds}; "
          f"Cycles threads {args.threads}, LP_NUM_THREADS {settings['lp_num_threads']}\n")
    print(markdown_table(results, overall))
    write_json(args.out / "comparison.json", {"settings": settings, "scenes": results, "overall": overall})


if __name__ == "__main__":
    try:
        main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    except InputError as error:
        print(f"error: {error}", file=sys.stderr)
        sys.exit(2)
