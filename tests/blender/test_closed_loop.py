"""The closed loop: a Cycles render of a Principled Volume cube is the target;
vkdiffrender fits the cube's sigma_a and sigma_s from a wrong start; the add-on writes them
back into the same node; Cycles renders the fitted .blend.

Checked: the written-back node gives exactly the fitted medium (float32 sockets: 1e-5
relative), and Cycles' render of the fitted file matches the target within noise: the
chi-square of the 4 x 4 block z-scores of the three channels (render noise of both images,
image_stats) stays below chi-square(48)'s 0.999 quantile, where the start's is above 10^5."""
import json
import subprocess

import numpy as np
import pytest
from conftest import run_blender_script

import image_stats

BLOCKS = 4


def chi_square_quantile(degrees, z):
    """Wilson and Hilferty's approximation of the chi-square quantile at the standard
    normal quantile z (within 0.5 % of the exact value for 48 degrees at z = 3.09)."""
    h = 2.0 / (9.0 * degrees)
    return degrees * (1.0 - h + z * h ** 0.5) ** 3


# 48 z-scores (16 blocks x 3 channels); z = 3.09 is the normal's 0.999 quantile.
MATCHES_WITHIN_NOISE = chi_square_quantile(BLOCKS * BLOCKS * 3, 3.09)


def blender_step(blender, step, out):
    run_blender_script(blender, "closed_loop.py", "--step", step, "--out", str(out))


def chi_square(a, b):
    block_z, _, _, _ = image_stats.z_scores(a, b, blocks=BLOCKS)
    return float((block_z ** 2).sum())


def test_fit_written_back_into_blender_renders_the_target_in_cycles(blender, cli, tmp_path):
    blender_step(blender, "target", tmp_path)
    subprocess.run([cli, "optimize", str(tmp_path / "scene.gltf"), "--target", f"camera={tmp_path / 'target_1.exr'}",
                    "--param", "media/smoke/sigma_a", "--param", "media/smoke/sigma_s",
                    "--log-param", "media/smoke/sigma_a", "--log-param", "media/smoke/sigma_s",
                    "--iters", "150", "--spp", "16", "--max-depth", "2", "--lr", "0.08", "--lr-decay", "0.03",
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
    print(f"chi-square of the block z-scores over 48: start {before:.0f}, fitted {after:.0f}, "
          f"0.999 quantile {MATCHES_WITHIN_NOISE:.1f}")
    assert before > MATCHES_WITHIN_NOISE, "the start already matches: the loop proves nothing"
    assert after < MATCHES_WITHIN_NOISE
