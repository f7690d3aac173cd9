"""The module against the command line: the same image bit for bit, the same gradient
within standard errors; and repeatability."""
import json
import subprocess
import warnings

import numpy as np
import pytest
import vkdiffrender

from conftest import SCENES
from sample_means import assert_agree, mean_and_standard_error

WIDTH, SPP = 32, 16


def test_render_is_bit_identical_to_the_command_line(cli, fog_scene_file, tmp_path):
    out = tmp_path / "cli.exr"
    subprocess.run([cli, "render", str(fog_scene_file), "-o", str(out), "--spp", "4", "--width", "24",
                    "--seed", "7", "--max-depth", "5", "--set", "media/fog/sigma_s=0.1,0.2,0.3"],
                   check=True, capture_output=True)
    scene = vkdiffrender.Scene(fog_scene_file)
    scene["media/fog/sigma_s"] = np.array([0.1, 0.2, 0.3], dtype=np.float32)
    image = scene.render(spp=4, width=24, seed=7, max_depth=5)
    assert image.shape == (24, 24, 3) and image.dtype == np.float32
    assert np.array_equal(image, vkdiffrender.read_image(out))
    # A renderer kept from an earlier call gives the same image as a fresh one.
    scene.render(spp=4, width=24, seed=8, max_depth=5)
    assert np.array_equal(image, scene.render(spp=4, width=24, seed=7, max_depth=5))


def test_equiangular_false_is_the_command_lines_no_equiangular(cli, fog_scene_file, tmp_path):
    out = tmp_path / "cli.exr"
    subprocess.run([cli, "render", str(fog_scene_file), "-o", str(out), "--spp", "4", "--width", "24",
                    "--seed", "7", "--max-depth", "5", "--no-equiangular"], check=True, capture_output=True)
    scene = vkdiffrender.Scene(fog_scene_file)
    with_equiangular = scene.render(spp=4, width=24, seed=7, max_depth=5)
    without = scene.render(spp=4, width=24, seed=7, max_depth=5, equiangular=False)
    assert np.array_equal(without, vkdiffrender.read_image(out))
    # The kept renderers are told apart by the setting too.
    assert not np.array_equal(without, with_equiangular)


def test_backpropagate_repeats_bit_for_bit(fog_scene_file):
    scene = vkdiffrender.Scene(fog_scene_file)
    adjoint = np.random.default_rng(3).normal(size=(WIDTH, WIDTH, 3)).astype(np.float32)
    names = ["media/fog/sigma_a", "media/fog/g", "materials/white/base_color"]
    first = scene.backpropagate(adjoint, names, spp=4, width=WIDTH, seed=5)
    second = scene.backpropagate(adjoint, names, spp=4, width=WIDTH, seed=5)
    assert list(first) == names
    for name in names:
        assert first[name].shape == scene.parameter(name).shape
        assert np.array_equal(first[name], second[name])


def test_a_gradient_does_not_depend_on_what_was_differentiated_before(fog_scene_file):
    # A fog that scatters no light: differentiating sigma_s samples its collisions, so a
    # set-up for sigma_s reused for sigma_a alone would give sigma_a other bits.
    scene = vkdiffrender.Scene(fog_scene_file)
    scene["media/fog/sigma_s"] = np.zeros(3, dtype=np.float32)
    adjoint = np.random.default_rng(4).normal(size=(WIDTH, WIDTH, 3)).astype(np.float32)
    settings = dict(spp=4, width=WIDTH, seed=5, max_depth=4)
    alone = scene.backpropagate(adjoint, ["media/fog/sigma_a"], **settings)
    scene.backpropagate(adjoint, ["media/fog/sigma_a", "media/fog/sigma_s"], **settings)
    after_more = scene.backpropagate(adjoint, ["media/fog/sigma_a"], **settings)
    assert np.array_equal(alone["media/fog/sigma_a"], after_more["media/fog/sigma_a"])
    target = scene.render(spp=4, width=WIDTH, seed=9)
    _, _, alone = scene.loss_gradient(target, ["media/fog/g"], **settings)
    scene.loss_gradient(target, ["media/fog/g", "media/fog/sigma_s"], **settings)
    _, _, after_more = scene.loss_gradient(target, ["media/fog/g"], **settings)
    assert np.array_equal(alone["media/fog/g"], after_more["media/fog/g"])


def test_l2_image_adjoint_gives_the_command_lines_gradient(cli, fog_scene_file, tmp_path):
    """grad's L2 loss is the mean over pixels and channels of (I - T)^2, so its dLoss/dI
    is 2 (I - T) / (3 pixels). Both estimators are unbiased for the gradient of the loss
    of the expected image (docs/gradients.md; docs/python.md): their means over seeds
    agree within standard errors. grad's estimator is Scene.loss_gradient's, bit for bit
    (the next test), so it is run in this process rather than as sixteen commands."""
    target_file = tmp_path / "target.exr"
    # A seed of its own: the gradients' renders must not share the target's samples.
    subprocess.run([cli, "render", str(fog_scene_file), "-o", str(target_file), "--spp", "64", "--width",
                    str(WIDTH), "--seed", "999", "--set", "media/fog/sigma_a=0.05", "--set", "media/fog/sigma_s=0.1"],
                   check=True, capture_output=True)
    names = ["media/fog/sigma_a", "media/fog/sigma_s", "media/fog/g", "materials/red/base_color",
             "lights/light/emission"]
    seeds = 16
    scene = vkdiffrender.Scene(fog_scene_file)
    target = vkdiffrender.read_image(target_file)
    grad_samples = {name: [] for name in names}
    for seed in range(seeds):
        _, _, gradients = scene.loss_gradient(target, names, loss="l2", spp=SPP, width=WIDTH, seed=seed)
        for name, gradient in gradients.items():
            grad_samples[name].append(gradient)

    samples = {name: [] for name in names}
    for seed in range(seeds):
        image = scene.render(spp=SPP, width=WIDTH, seed=1000 + seed)
        adjoint = 2.0 * (image - target) / image.size
        for name, gradient in scene.backpropagate(adjoint, names, spp=SPP, width=WIDTH, seed=1000 + seed).items():
            samples[name].append(gradient)
    for name in names:
        assert_agree(name, *mean_and_standard_error(samples[name]), *mean_and_standard_error(grad_samples[name]))


def test_loss_gradient_is_the_command_lines_bit_for_bit(cli, fog_scene_file, tmp_path):
    """Scene.loss_gradient runs grad's estimator on the same renderer: at seed 0 (which
    grad's single view renders with too) the loss and gradients have the same bits."""
    target_file = tmp_path / "target.exr"
    subprocess.run([cli, "render", str(fog_scene_file), "-o", str(target_file), "--spp", "8", "--width", "24",
                    "--set", "media/fog/sigma_a=0.05"], check=True, capture_output=True)
    names = ["media/fog/sigma_a", "media/fog/sigma_s", "media/fog/g", "media/fog/emission",
             "materials/white/base_color"]
    for loss in ["l2", "l1"]:
        command = [cli, "grad", str(fog_scene_file), "--target", str(target_file), "--spp", "4", "--seed", "0",
                   "--loss", loss, "--json"]
        for name in names:
            command += ["--param", name]
        expected = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
        scene = vkdiffrender.Scene(fog_scene_file)
        value, image, gradients = scene.loss_gradient(vkdiffrender.read_image(target_file), names, loss=loss,
                                                      spp=4, width=24, seed=0)
        assert value == expected["loss"]
        assert image.shape == (24, 24, 3)
        for name in names:
            assert gradients[name].tolist() == expected["gradients"][name], name


def test_paths_cut_short_are_a_runtime_warning():
    """A grid whose majorant cells each hold one voxel of density 1 among zeros, at a
    scattering of 3e5: free flight pauses more often than a path's segments allow, so
    camera rays far from the dense voxels are cut short (depth 0: no shadow rays through
    the grid). Each call that renders says so as the command line does; a faithful render
    says nothing."""
    scene = vkdiffrender.Scene(SCENES / "cornell_plume.gltf")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene.render(width=8, spp=1, max_depth=0)
    density = np.zeros(scene.parameter("media/plume/density").shape, dtype=np.float32)
    density[::8, ::8, ::8] = 1.0
    scene["media/plume/density"] = density
    scene["media/plume/sigma_s"] = 3e5
    settings = {"width": 8, "spp": 2, "max_depth": 0}
    with pytest.warns(RuntimeWarning, match="paths of the render .* were cut short"):
        image = scene.render(**settings)
    with pytest.warns(RuntimeWarning, match="were cut short"):
        scene.loss_gradient(image, ["media/plume/sigma_s"], **settings)
    with pytest.warns(RuntimeWarning, match="were cut short"):
        scene.backpropagate(np.ones_like(image), ["media/plume/sigma_s"], **settings)
