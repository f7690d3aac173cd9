"""vkdiffrender.torch.render's gradients, through a nonlinear loss, against central
finite differences with common random numbers, for every kind of parameter.

The loss is a masked, weighted L2 of the luminance: nonlinear in the image, and
quadratic, so that both sides estimate the gradient of the loss of the expected image
without bias. The backward pass replays with random numbers independent of the forward
image's, so E[dL/dI(I1) . dI2/dtheta] = dL/dI(E[I]) . dE[I]/dtheta (docs/python.md). The
finite differences evaluate the loss as the product of two independent images' residuals,
whose expectation is the loss of the expected image exactly, at theta +- h with the same
random numbers on both sides. Both are averaged over seeds and compared within their
standard errors (sample_means.py); the step h leaves a bias of O(h^2) in the
differences, far below their standard error at these steps."""
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import vkdiffrender

torch = pytest.importorskip("torch")
import vkdiffrender.torch as vt  # noqa: E402

from sample_means import assert_agree, mean_and_standard_error
from textured_scene import write_shared_texture_scene, write_textured_fog_scene

WIDTH, SPP, SEEDS = 32, 16, 16
LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)

# (parameter, value the gradient is taken at, finite-difference step); a single value
# sets every channel (and texel), so the gradient is the derivative along all of them.
PARAMETERS = [
    ("media/fog/sigma_a", 0.05, 0.005),
    ("media/fog/sigma_s", 0.1, 0.01),
    ("media/fog/g", 0.3, 0.05),
    ("materials/white/base_color", 0.6, 0.05),
    ("materials/poster/base_color_texture", 0.5, 0.05),
    ("lights/light/emission", 10.0, 1.0),
]


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    return vkdiffrender.Scene(write_textured_fog_scene(tmp_path_factory.mktemp("scene")))


@pytest.fixture(scope="module")
def loss_terms(scene):
    """The target luminance and the per-pixel weights: 0 on the top rows (the light),
    growing towards the bottom elsewhere."""
    target = scene.render(spp=64, width=WIDTH, seed=99) @ LUMINANCE
    rows = np.arange(WIDTH, dtype=np.float32)[:, None] * np.ones((1, WIDTH), dtype=np.float32)
    weights = np.where(rows < WIDTH // 4, 0.0, 1.0 + rows / WIDTH).astype(np.float32)
    return target, weights / weights.sum()


def masked_luminance_loss(image, target, weights):
    residual = image @ torch.from_numpy(LUMINANCE) - torch.from_numpy(target)
    return (torch.from_numpy(weights) * residual * residual).sum()


def loss_of_expected_image(scene, name, value, seed_a, seed_b, target, weights):
    scene[name] = value
    residual_a = scene.render(spp=SPP, width=WIDTH, seed=seed_a) @ LUMINANCE - target
    residual_b = scene.render(spp=SPP, width=WIDTH, seed=seed_b) @ LUMINANCE - target
    return float((weights * residual_a * residual_b).sum(dtype=np.float64))


@pytest.mark.parametrize("name,value,step", PARAMETERS, ids=[p[0] for p in PARAMETERS])
def test_torch_gradient_matches_finite_differences(scene, loss_terms, name, value, step):
    target, weights = loss_terms
    adjoint_samples, difference_samples = [], []
    for seed in range(SEEDS):
        parameter = torch.tensor(value, requires_grad=True)
        image = vt.render(scene, {name: parameter}, spp=SPP, width=WIDTH, seed=3 * seed)
        masked_luminance_loss(image, target, weights).backward()
        adjoint_samples.append(parameter.grad.item())
        seeds = (3 * seed + 1, 3 * seed + 2)
        above = loss_of_expected_image(scene, name, value + step, *seeds, target, weights)
        below = loss_of_expected_image(scene, name, value - step, *seeds, target, weights)
        difference_samples.append((above - below) / (2 * step))
    assert_agree(name, *mean_and_standard_error(adjoint_samples), *mean_and_standard_error(difference_samples))


def test_full_shaped_tensors_get_per_channel_gradients(scene, loss_terms):
    """A tensor of the parameter's shape gets Scene.backpropagate's gradient, channel by
    channel, for the upstream gradient the loss gives the image."""
    target, weights = loss_terms
    sigma_a = torch.tensor([0.02, 0.05, 0.08], requires_grad=True)
    texels = torch.full((4, 4, 3), 0.4, requires_grad=True)
    parameters = {"media/fog/sigma_a": sigma_a, "materials/poster/base_color_texture": texels}
    image = vt.render(scene, parameters, spp=4, width=WIDTH, seed=7)
    image.retain_grad()
    masked_luminance_loss(image, target, weights).backward()
    expected = scene.backpropagate(image.grad.numpy(), list(parameters), spp=4, width=WIDTH, seed=7)
    assert np.array_equal(sigma_a.grad.numpy(), expected["media/fog/sigma_a"].astype(np.float32))
    assert np.array_equal(texels.grad.numpy(), expected["materials/poster/base_color_texture"].astype(np.float32))
    assert np.any(texels.grad.numpy() != 0)


def test_backward_takes_the_values_of_its_forward_pass(scene):
    """Changing the scene between forward and backward, in the rendered tensor's parameter
    and in another (as a second view rendered with other values would), does not change
    the gradient."""
    scene["media/fog/g"] = 0.0
    sigma_a = torch.tensor(0.05, requires_grad=True)
    image = vt.render(scene, {"media/fog/sigma_a": sigma_a}, spp=4, width=WIDTH, seed=11)
    scene["media/fog/sigma_a"] = 0.5
    scene["media/fog/g"] = 0.9
    image.sum().backward()
    scene["media/fog/sigma_a"] = 0.05
    scene["media/fog/g"] = 0.0
    expected = scene.backpropagate(np.ones((WIDTH, WIDTH, 3), np.float32), ["media/fog/sigma_a"], spp=4,
                                   width=WIDTH, seed=11)
    assert sigma_a.grad.item() == pytest.approx(expected["media/fog/sigma_a"].sum(), rel=1e-6)


def test_a_light_set_to_zero_is_restored_for_the_backward_pass(scene):
    """A light whose emission a forward pass renders at 0 stays a parameter, so the backward
    pass sets it back to 0: the gradient is that of the black image (0), not of the lit
    scene set in between."""
    emission = scene["lights/light/emission"].copy()
    sigma_a = torch.tensor(0.05, requires_grad=True)
    image = vt.render(scene, {"lights/light/emission": torch.zeros(3), "media/fog/sigma_a": sigma_a}, spp=2,
                      width=WIDTH)
    assert "lights/light/emission" in scene
    scene["lights/light/emission"] = emission
    ((image - 1.0) ** 2).mean().backward()
    assert sigma_a.grad.item() == 0.0
    assert np.all(scene["lights/light/emission"] == 0.0)
    scene["lights/light/emission"] = emission


@pytest.mark.parametrize("parameters,settings", [
    ({"media/fog/sigma_a": torch.tensor(0.3), "media/nowhere/sigma_a": torch.tensor(0.1)}, {}),
    ({"media/fog/sigma_a": torch.tensor(0.3), "media/fog/sigma_s": torch.tensor(float("nan"))}, {}),
    ({"media/fog/sigma_a": torch.tensor(0.3)}, {"spp": 0}),
    ({"media/fog/sigma_a": torch.tensor(0.3)}, {"camera": "nobody"}),
])
def test_a_failing_forward_pass_leaves_the_scene_as_it_was(scene, parameters, settings):
    before = {parameter.name: scene[parameter.name].copy() for parameter in scene.parameters()}
    with pytest.raises(vkdiffrender.Error):
        vt.render(scene, parameters, width=WIDTH, **settings)
    for name, value in before.items():
        assert np.array_equal(scene[name], value), name


@pytest.mark.parametrize("call,message", [
    (lambda scene: vt.render(None, {"media/fog/sigma_a": torch.tensor(0.3)}), "scene: expected a vkdiffrender.Scene"),
    (lambda scene: vt.render(scene, [("media/fog/sigma_a", torch.tensor(0.3))]), "parameters: expected a dict"),
    (lambda scene: vt.render(scene, {"media/fog/sigma_a": None}), "media/fog/sigma_a: expected numbers, got None"),
    (lambda scene: vt.render(scene, {"media/fog/sigma_a": "0.3"}), "media/fog/sigma_a: expected numbers, got text"),
    (lambda scene: vt.render(scene, {"media/fog/sigma_a": torch.zeros(3, device="meta")}),
     "media/fog/sigma_a: a tensor on the meta device"),
    # A bytes name would render, and its gradient would be lost under the str name.
    (lambda scene: vt.render(scene, {b"media/fog/sigma_a": torch.tensor(0.3)}),
     "parameters: a name must be a str, got bytes"),
    (lambda scene: vt.render(scene, {"media/fog/sigma_a": torch.tensor([0.1, 0.2, 0.3]).to_sparse()}),
     "media/fog/sigma_a: expected a dense tensor"),
])
def test_arguments_of_the_wrong_kind_name_themselves(scene, call, message):
    before = scene["media/fog/sigma_a"].copy()
    with pytest.raises(TypeError, match=message):
        call(scene)
    assert np.array_equal(scene["media/fog/sigma_a"], before)


def test_a_gradient_beyond_a_half_precision_tensors_range_is_an_error_not_infinity(scene):
    sigma_a = torch.tensor(0.05, dtype=torch.float16, requires_grad=True)
    image = vt.render(scene, {"media/fog/sigma_a": sigma_a}, spp=2, width=WIDTH)
    with pytest.raises(OverflowError, match=r"media/fog/sigma_a: its gradient \(up to .*\) exceeds the range of the "
                                            r"tensor's torch.float16; pass it in a wider dtype"):
        (image.sum() * 1e6).backward()
    small = torch.tensor(0.05, dtype=torch.float16, requires_grad=True)
    vt.render(scene, {"media/fog/sigma_a": small}, spp=2, width=WIDTH).mean().backward()
    assert small.grad.dtype == torch.float16 and torch.isfinite(small.grad).all() and small.grad.item() != 0.0


def test_a_float64_value_beyond_float_range_is_named_as_such(scene):
    for value in (torch.tensor(1e300, dtype=torch.float64), 1e300, [1e300, 0.1, 0.1]):
        with pytest.raises(vkdiffrender.Error, match=r"media/fog/sigma_a: (value 0 of 3 \(counted from 0\): )?must be "
                                                     r"finite, got 1e\+300: beyond float range"):
            vt.render(scene, {"media/fog/sigma_a": value}, width=WIDTH)


@pytest.mark.parametrize("value", [Fraction(1, 20), Decimal("0.05"), [Fraction(1, 20), Decimal("0.05"), 0.05],
                                   np.array([0.05] * 3, np.float16), [torch.tensor(0.05), 0.05, 0.05]])
def test_values_that_are_not_tensors_are_taken_as_scene_item_assignment_takes_them(scene, value):
    before = scene["media/fog/sigma_a"].copy()
    scene["media/fog/sigma_a"] = value
    expected = scene.render(width=WIDTH, spp=2)
    scene["media/fog/sigma_a"] = before
    assert np.array_equal(vt.render(scene, {"media/fog/sigma_a": value}, width=WIDTH, spp=2).numpy(), expected)


def test_an_integer_beyond_64_bits_is_a_number(scene):
    """torch.as_tensor would refuse it (it holds 64 bits at most)."""
    vt.render(scene, {"media/fog/sigma_a": 2**70}, width=WIDTH, spp=1)
    assert np.array_equal(scene["media/fog/sigma_a"], np.full(3, np.float32(2.0**70)))


@pytest.mark.parametrize("value", [10**400, Fraction(10**400, 3)], ids=["integer", "fraction"])
def test_numbers_too_large_for_a_double_are_named_as_beyond_float_range(scene, value):
    """Converted to doubles first, they would overflow with Python's own OverflowError."""
    before = scene["media/fog/sigma_a"].copy()
    with pytest.raises(vkdiffrender.Error, match=r"^media/fog/sigma_a: must be finite, got \d{20}\.\.\. \(40\d "
                                                 r"digits\): beyond float range"):
        vt.render(scene, {"media/fog/sigma_a": value}, width=WIDTH, spp=1)
    assert np.array_equal(scene["media/fog/sigma_a"], before)


def test_tensors_torch_keeps_lazily_negated_or_quantized_are_taken_by_their_values(scene):
    before = scene["media/fog/sigma_a"].copy()
    negated = torch.tensor([1 - 0.05j] * 3).conj().imag  # 0.05, as a view with the negative bit set
    quantized = torch.quantize_per_tensor(torch.tensor([0.05, 0.05, 0.05]), 0.01, 0, torch.quint8)
    for value in (negated, quantized):
        image = vt.render(scene, {"media/fog/sigma_a": value}, spp=1, width=8)
        assert torch.isfinite(image).all()
        assert scene["media/fog/sigma_a"] == pytest.approx([0.05] * 3)
    scene["media/fog/sigma_a"] = before


@pytest.mark.parametrize("upstream,error", [(float("nan"), vkdiffrender.Error), (1e6, OverflowError)])
def test_a_failing_backward_pass_leaves_the_scene_as_it_was(scene, upstream, error):
    """The backward pass sets the forward pass's values; one that raises (an upstream
    gradient that is not finite, a gradient beyond a float16 tensor's range) puts back
    what was set in between."""
    before = scene["media/fog/sigma_a"].copy()
    sigma_a = torch.tensor(0.05, dtype=torch.float16, requires_grad=True)
    image = vt.render(scene, {"media/fog/sigma_a": sigma_a}, spp=2, width=WIDTH)
    scene["media/fog/sigma_a"] = 0.2
    with pytest.raises(error):
        (image.sum() * upstream).backward()
    assert np.all(scene["media/fog/sigma_a"] == np.float32(0.2))
    scene["media/fog/sigma_a"] = before


def test_two_names_of_one_texture_are_refused(tmp_path):
    shared = vkdiffrender.Scene(write_shared_texture_scene(tmp_path))
    assert shared.parameter("materials/poster/base_color_texture").aliases == ("materials/poster2/base_color_texture",)
    assert shared.parameter("materials/poster2/base_color_texture").aliases == ("materials/poster/base_color_texture",)
    assert shared.parameter("media/fog/sigma_a").aliases == ()
    with pytest.raises(ValueError, match="materials/poster/base_color_texture and "
                                         "materials/poster2/base_color_texture name the same values"):
        vt.render(shared, {"materials/poster/base_color_texture": torch.tensor(0.9),
                           "materials/poster2/base_color_texture": torch.tensor(0.2)}, width=8)
    # The module's own gradients refuse them too: each name would get the whole gradient.
    both = ["materials/poster/base_color_texture", "materials/poster2/base_color_texture"]
    with pytest.raises(vkdiffrender.Error, match="'materials/poster/base_color_texture' and "
                                                 "'materials/poster2/base_color_texture' name the same values"):
        shared.backpropagate(np.ones((8, 8, 3), np.float32), both, spp=2, width=8)
    with pytest.raises(vkdiffrender.Error, match="name the same values"):
        shared.loss_gradient(np.zeros((8, 8, 3), np.float32), both, spp=2, width=8)


def test_complex_values_are_refused_not_cut_to_their_real_part(scene):
    before = scene["media/fog/sigma_a"].copy()
    with pytest.raises(TypeError, match="media/fog/sigma_a: expected real numbers"):
        vt.render(scene, {"media/fog/sigma_a": torch.tensor([0.05 + 0.3j] * 3)}, width=WIDTH)
    assert np.array_equal(scene["media/fog/sigma_a"], before)
