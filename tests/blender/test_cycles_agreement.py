"""Scenes built in Blender, exported with the add-on, rendered by Cycles and by
vkdiffrender: image means and 4 x 4 block means agree within both renders' noise.

Each renderer renders two seeds; image_stats estimates each block mean's standard error
from the per-pixel sample variance over the seeds. Per scene 51 z-scores are tested
(16 blocks and the image mean, 3 channels). |z| < 5: with ~64 pixels per block the
estimated error has ~64 degrees of freedom, for which P(|t| > 5) is about 5e-6, so a
scene whose renderers agree fails with probability about 3e-4.

Two runs (docs/blender.md, "Measured figures"):
- every scene at max depth 4 (Cycles' Max Bounces 3), Cycles' area light replaced by the
  exported emitter as a mesh: Cycles' area lights let rays through, so the ceiling behind
  the lamp lights the box (0.8 % at depth 4), which the exported opaque emitter hides;
- the box with Cycles' own area light at max depth 2, where no path reaches what the lamp
  hides and is then lit: the area light's radiance mapping P / (4 A) itself."""

import numpy as np
import pytest
from conftest import run_blender_script

import image_stats

K = 5.0
SEEDS = (1, 2)
SCENES = ("box_area", "principled_cube", "glowing_cube", "absorption_cube", "world_fog", "orthographic_fog",
          "point_light", "smooth_sphere", "painted_cube")
RUNS = {"depth4": {"scenes": SCENES, "max_depth": 4, "area_lights": "meshes"},
        "area_light": {"scenes": ("box_area",), "max_depth": 2, "area_lights": "lights"}}


@pytest.fixture(scope="module")
def renders(blender, cli, tmp_path_factory):
    """Renders every run once; returns {run: its output directory}."""
    directories = {}
    for run, settings in RUNS.items():
        out = tmp_path_factory.mktemp(run)
        run_blender_script(blender, "render_both.py", "--scenes", ",".join(settings["scenes"]), "--out", str(out),
                           "--cli", cli, "--size", "32", "--cycles-spp", "256", "--vkdr-spp", "256",
                           "--seeds", ",".join(map(str, SEEDS)), "--max-depth", str(settings["max_depth"]),
                           "--cycles-area-lights", settings["area_lights"])
        directories[run] = out
    return directories


@pytest.mark.parametrize("run, scene", [(run, scene) for run, settings in RUNS.items() for scene in settings["scenes"]])
def test_vkdiffrender_matches_cycles(renders, run, scene):
    directory = renders[run] / scene
    messages = (directory / "vkdr_warnings.txt").read_text()
    assert (directory / f"vkdr_{SEEDS[-1]}.npy").is_file(), f"vkdiffrender failed: {messages}"
    cycles = [np.load(directory / f"cycles_{s}.npy") for s in SEEDS]
    vkdr = [np.load(directory / f"vkdr_{s}.npy") for s in SEEDS]
    block_z, image_z, cycles_mean, vkdr_mean = image_stats.z_scores(cycles, vkdr, blocks=4)
    assert cycles_mean.min() > 0.01, "the view is black: nothing to compare"
    worst = np.unravel_index(np.abs(block_z).argmax(), block_z.shape)
    assert np.abs(image_z).max() < K, f"image means: Cycles {cycles_mean}, vkdiffrender {vkdr_mean}, z {image_z}"
    assert np.abs(block_z).max() < K, f"block {worst}: z {block_z[worst]:.2f}"
