"""The closed loop: a Cycles render of a Principled Volume cube is the target;
vkdiffrender fits the cube's sigma_a and sigma_s from a wrong start; the add-on writes them
back into the same node; Cycles renders the fitted .blend.

Checked: the written-back node gives exactly the fitted medium (float32 sockets: 1e-5
relative), and the fitted render is far closer to the target than the start, measured as
the chi-square of the 4 x 4 block z-scores (render noise of both images, image_stats)."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

import image_stats

HERE = pathlib.Path(__file__).resolve().parent
# A fit that reached the target leaves chi-square near its 48 degrees of freedom, plus the
# fit's own error; the start's is above 10^4. A factor 20 separates a fit from no fit.
IMPROVEMENT = 20.0


def blender_step(blender, step, out):
    subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                    str(HERE / "closed_loop.py"), "--", "--step", step, "--out", str(out)],
                   check=True, stdout=subprocess.DEVNULL)


def chi_square(a, b):
    block_z, _, _, _ = image_stats.z_scores(a, b, blocks=4)
    return float((block_z ** 2).sum())


def test_fit_written_back_into_blender_renders_the_target_in_cycles(blender, cli, tmp_path):
    blender_step(blender, "target", tmp_path)
    subprocess.run([cli, "optimize", str(tmp_path / "scene.gltf"), "--target", f"camera={tmp_path / 'target_1.exr'}",
                    "--param", "media/smoke/sigma_a", "--param", "media/smoke/sigma_s",
                    "--log-param", "media/smoke/sigma_a", "--log-param", "media/smoke/sigma_s",
                    "--iters", "60", "--spp", "8", "--max-depth", "2", "--lr", "0.08", "--lr-decay", "0.1",
                    "--lr-decay-start", "0.3", "--out", str(tmp_path / "run")],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    blender_step(blender, "fitted", tmp_path)

    fitted = json.loads((tmp_path / "run" / "params.json").read_text())
    written = json.loads((tmp_path / "fitted_medium.json").read_text())
    for kind in ("sigma_a", "sigma_s"):
        assert written[kind] == pytest.approx(fitted[f"media/smoke/{kind}"], rel=1e-5)

    target = [np.load(tmp_path / f"target_{s}.npy") for s in (1, 2)]
    fitted_renders = [np.load(tmp_path / f"fitted_{s}.npy") for s in (1, 2)]
    start = [np.load(tmp_path / f"start_{s}.npy") for s in (1, 2)]
    before, after = chi_square(target, start), chi_square(target, fitted_renders)
    print(f"chi-square of the block z-scores over 48: start {before:.0f}, fitted {after:.0f}")
    assert after * IMPROVEMENT < before
