"""Scenes built in Blender, exported with the add-on, rendered by Cycles and by
vkdiffrender: image means and 4 x 4 block means agree within both renders' noise.

Each renderer renders two seeds; image_stats estimates each block mean's standard error
from the per-pixel sample variance over the seeds. Per scene 51 z-scores are tested
(16 blocks and the image mean, 3 channels). |z| < 5: with ~64 pixels per block the
estimated error has ~64 degrees of freedom, for which P(|t| > 5) is about 5e-6, so a
scene whose renderers agree fails with probability about 3e-4.

Max depth 2 (one bounce): Cycles' max_bounces 1. At depth 4 the box differs by 0.8 %
(docs/blender.md, what is still open)."""
import pathlib
import subprocess

import numpy as np
import pytest

import image_stats

HERE = pathlib.Path(__file__).resolve().parent
K = 5.0
SEEDS = (1, 2)
# A scene that needs a renderer feature still missing is skipped when its render warns so.
NEEDS = {"point_light": "KHR_lights_punctual", "smooth_sphere": "vertex normals are ignored"}
SCENES = ("box_area", "principled_cube", "absorption_cube", "world_fog", "point_light", "smooth_sphere")


@pytest.fixture(scope="module")
def renders(blender, cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("cycles_agreement")
    subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1",
                    "--python", str(HERE / "render_both.py"), "--", "--scenes", ",".join(SCENES),
                    "--out", str(out), "--cli", cli, "--size", "32", "--cycles-spp", "256", "--vkdr-spp", "256",
                    "--seeds", ",".join(map(str, SEEDS)), "--max-depth", "2"],
                   check=True, stdout=subprocess.DEVNULL)
    return out


# vkdiffrender renders the world fog 1.0 % darker than Cycles (z about 7, measured): an
# open difference (docs/blender.md). strict: the test reports when the two come to agree.
KNOWN_DIFFERENCES = {"world_fog": "vkdiffrender is 1.0 % darker than Cycles in a scene-wide fog"}


@pytest.mark.parametrize("scene", [pytest.param(s, marks=pytest.mark.xfail(strict=True, raises=AssertionError,
                                                                    reason=KNOWN_DIFFERENCES[s]))
                                   if s in KNOWN_DIFFERENCES else s for s in SCENES])
def test_vkdiffrender_matches_cycles(renders, scene):
    directory = renders / scene
    needed = NEEDS.get(scene)
    messages = (directory / "vkdr_warnings.txt").read_text()
    if needed and needed in messages:
        pytest.skip(f"the renderer does not support this yet: {messages.strip()}")
    assert (directory / f"vkdr_{SEEDS[-1]}.npy").is_file(), f"vkdiffrender failed: {messages}"
    cycles = [np.load(directory / f"cycles_{s}.npy") for s in SEEDS]
    vkdr = [np.load(directory / f"vkdr_{s}.npy") for s in SEEDS]
    block_z, image_z, cycles_mean, vkdr_mean = image_stats.z_scores(cycles, vkdr, blocks=4)
    assert cycles_mean.min() > 0.01, "the view is black: nothing to compare"
    worst = np.unravel_index(np.abs(block_z).argmax(), block_z.shape)
    assert np.abs(image_z).max() < K, f"image means: Cycles {cycles_mean}, vkdiffrender {vkdr_mean}, z {image_z}"
    assert np.abs(block_z).max() < K, f"block {worst}: z {block_z[worst]:.2f}"
