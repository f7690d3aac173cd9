"""Cycles set up as a reference for vkdiffrender (run inside Blender): render settings that
leave Cycles' image unbiased and comparable pixel for pixel, the front-only emitter that
stands for vkdiffrender's one-sided emissive triangles, and linear EXRs read as arrays.
Shared by tools/compare_with_cycles.py and the Blender tests (tests/blender)."""
import bpy
import numpy as np


def configure_cycles(scene, size, spp, max_depth, seed, threads=2):
    """Cycles as an unbiased reference: box pixel filter one pixel wide, no denoising,
    adaptive sampling, clamping or light threshold; vkdiffrender's max depth D counts
    scattering vertices, Cycles' bounces count the ones after the first, so D - 1."""
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = spp
    cycles.seed = seed
    cycles.use_denoising = False
    cycles.use_adaptive_sampling = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.blur_glossy = 0.0
    for name in ("max_bounces", "diffuse_bounces", "volume_bounces", "glossy_bounces", "transmission_bounces"):
        setattr(cycles, name, max_depth - 1)
    cycles.transparent_max_bounces = 64
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"


def front_only_emission(tree, radiance):
    """Adds to node TREE an emission of RADIANCE (linear RGB) from the front of a surface
    only, black behind it, as vkdiffrender's one-sided emitters; returns its shader
    output. Cycles' Emission shader emits from both sides."""
    nodes, links = tree.nodes, tree.links
    emission = nodes.new("ShaderNodeEmission")
    strength = max(radiance)
    emission.inputs["Color"].default_value = (*(c / strength for c in radiance), 1.0)
    emission.inputs["Strength"].default_value = strength
    black = nodes.new("ShaderNodeBsdfDiffuse")
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    facing = nodes.new("ShaderNodeNewGeometry")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(facing.outputs["Backfacing"], mix.inputs["Fac"])
    links.new(emission.outputs[0], mix.inputs[1])
    links.new(black.outputs[0], mix.inputs[2])
    return mix.outputs[0]


def load_exr(path):
    """A linear RGB image as a float32 array (height, width, 3), rows from the top."""
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(height, width, 4)
    bpy.data.images.remove(image)
    return pixels[::-1, :, :3].copy()
