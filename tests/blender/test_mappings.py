"""The add-on's mappings (pure Python) both ways on random values, and the forward
formulas against values worked out by hand from Cycles' code."""
import math
import random

import pytest

from vkdiffrender_blender import mappings

TRIALS = 2000


def random_medium(rng):
    return mappings.Medium(tuple(rng.uniform(0, 5) for _ in range(3)), tuple(rng.uniform(0, 5) for _ in range(3)),
                           rng.uniform(-0.99, 0.99), tuple(rng.uniform(0, 3) for _ in range(3)))


def assert_close(a, b, tolerance=1e-9):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert abs(x - y) <= tolerance * max(1.0, abs(y)), (a, b)


def test_principled_volume_by_hand():
    # Color 0.5, Density 2, Absorption Color 0.25: sqrt gives 0.5, absorption (1-0.5)(1-0.5) = 0.25.
    medium = mappings.principled_volume_to_medium((0.5, 0.5, 0.5), 2.0, (0.25, 0.25, 0.25), 0.3)
    assert_close(medium.sigma_s, (1.0, 1.0, 1.0))
    assert_close(medium.sigma_a, (0.5, 0.5, 0.5))
    assert medium.g == 0.3


def test_principled_volume_black_absorption_colour_absorbs_one_minus_colour():
    medium = mappings.principled_volume_to_medium((0.2, 0.6, 1.0), 3.0, (0, 0, 0), 0.0)
    assert_close(medium.sigma_a, (2.4, 1.2, 0.0))


def test_absorption_and_scatter_by_hand():
    assert_close(mappings.volume_absorption_to_medium((0.25, 0.5, 1.0), 2.0).sigma_a, (1.5, 1.0, 0.0))
    scatter = mappings.volume_scatter_to_medium((0.25, 0.5, 1.0), 2.0, -0.4)
    assert_close(scatter.sigma_s, (0.5, 1.0, 2.0))
    assert scatter.sigma_a == (0.0, 0.0, 0.0) and scatter.g == -0.4


@pytest.mark.parametrize("seed", range(3))
def test_principled_volume_inverse_reproduces_any_medium(seed):
    rng = random.Random(seed)
    for _ in range(TRIALS):
        medium = random_medium(rng)
        values = mappings.medium_to_principled_volume(medium)
        assert all(0.0 <= c <= 1.0 for c in values["color"] + values["absorption_color"])
        back = mappings.principled_volume_to_medium(values["color"], values["density"], values["absorption_color"],
                                                    values["anisotropy"], values["emission_color"],
                                                    values["emission_strength"])
        assert_close(back.sigma_a, medium.sigma_a)
        assert_close(back.sigma_s, medium.sigma_s)
        assert back.g == pytest.approx(medium.g)
        assert_close(back.emission, medium.emission)


def test_principled_volume_emits_emission_color_times_strength_whatever_the_density():
    medium = mappings.principled_volume_to_medium((0.5, 0.5, 0.5), 4.0, (0, 0, 0), 0.0, (1.0, 0.5, 0.25), 2.0)
    assert_close(medium.emission, (2.0, 1.0, 0.5))
    total, _ = mappings.add_media([medium, medium])
    assert_close(total.emission, (4.0, 2.0, 1.0))
    # A Mix Shader does not scale it: Cycles 3.4 emits it whole unless the factor is 0.
    assert_close(mappings.scale_medium(medium, 0.25).emission, (2.0, 1.0, 0.5))
    assert_close(mappings.scale_medium(medium, 0.25).sigma_s, tuple(0.25 * c for c in medium.sigma_s))
    assert_close(mappings.scale_medium(medium, 0.0).emission, (0.0, 0.0, 0.0))


@pytest.mark.parametrize("seed", range(3))
def test_principled_volume_forward_then_inverse_gives_the_same_medium(seed):
    """The inverse may pick other node values, but never another medium."""
    rng = random.Random(seed)
    for _ in range(TRIALS):
        color = tuple(rng.uniform(0, 1) for _ in range(3))
        absorption = tuple(rng.uniform(0, 1) for _ in range(3))
        medium = mappings.principled_volume_to_medium(color, rng.uniform(0, 10), absorption, rng.uniform(-0.9, 0.9))
        values = mappings.medium_to_principled_volume(medium)
        again = mappings.principled_volume_to_medium(values["color"], values["density"], values["absorption_color"],
                                                     values["anisotropy"])
        assert_close(again.sigma_a, medium.sigma_a)
        assert_close(again.sigma_s, medium.sigma_s)


def test_absorption_and_scatter_inverses_on_random_values():
    rng = random.Random(7)
    for _ in range(TRIALS):
        sigma = tuple(rng.uniform(0, 5) for _ in range(3))
        a = mappings.medium_to_volume_absorption(sigma)
        assert_close(mappings.volume_absorption_to_medium(a["color"], a["density"]).sigma_a, sigma)
        g = rng.uniform(-0.99, 0.99)
        s = mappings.medium_to_volume_scatter(sigma, g)
        back = mappings.volume_scatter_to_medium(s["color"], s["density"], s["anisotropy"])
        assert_close(back.sigma_s, sigma)
        assert back.g == g


def test_zero_media_invert_to_zero_density():
    zero = mappings.Medium((0, 0, 0), (0, 0, 0), 0.0)
    assert mappings.medium_to_principled_volume(zero)["density"] == 0.0
    assert mappings.medium_to_volume_absorption((0, 0, 0))["density"] == 0.0


def test_add_and_mix_of_closures():
    a = mappings.volume_absorption_to_medium((0.5, 0.5, 0.5), 2.0)
    s = mappings.volume_scatter_to_medium((1, 1, 1), 3.0, 0.5)
    total, exact = mappings.add_media([a, s])
    assert exact and total.g == 0.5
    assert_close(total.sigma_a, (1, 1, 1))
    assert_close(total.sigma_s, (3, 3, 3))
    other = mappings.volume_scatter_to_medium((1, 1, 1), 1.0, -0.5)
    mixed, exact = mappings.add_media([s, other])
    assert not exact
    assert mixed.g == pytest.approx((3 * 0.5 - 1 * 0.5) / 4)
    assert_close(mappings.scale_medium(s, 0.25).sigma_s, (0.75, 0.75, 0.75))


def test_g_is_clamped_to_the_renderer_range():
    assert mappings.clamp_g(0.995) == (0.99, True)
    assert mappings.clamp_g(-0.5) == (-0.5, False)


def test_lights_both_ways_on_random_values():
    rng = random.Random(11)
    for _ in range(TRIALS):
        color = tuple(rng.uniform(0.01, 1) for _ in range(3))
        power, area = rng.uniform(0.1, 1e4), rng.uniform(0.01, 10)
        intensity = mappings.point_light_intensity(color, power)
        assert_close(intensity, tuple(c * power / (4 * math.pi) for c in color))
        point = mappings.intensity_to_point_light(intensity)
        assert_close(mappings.point_light_intensity(point["color"], point["power"]), intensity)
        radiance = mappings.area_light_radiance(color, power, area)
        assert_close(radiance, tuple(c * power / (4 * area) for c in color))
        area_light = mappings.radiance_to_area_light(radiance, area)
        assert_close(mappings.area_light_radiance(area_light["color"], area_light["power"], area), radiance)
        sun = mappings.irradiance_to_sun(mappings.sun_irradiance(color, power))
        assert_close(mappings.sun_irradiance(sun["color"], sun["strength"]), mappings.sun_irradiance(color, power))
        emission = mappings.radiance_to_emission(mappings.emission_to_radiance(color, power))
        assert max(emission["color"]) == pytest.approx(1.0)
        assert_close(mappings.emission_to_radiance(emission["color"], emission["strength"]),
                     mappings.emission_to_radiance(color, power))


def test_spot_cone_angles():
    outer, inner = mappings.spot_cone_angles(math.radians(90), 0.0)
    assert outer == pytest.approx(math.radians(45)) and inner == pytest.approx(outer)
    # glTF (and vkdiffrender's loader) require inner < outer, also for a hard edge.
    for degrees in range(1, 181):
        outer, inner = mappings.spot_cone_angles(math.radians(degrees), 0.0)
        assert 0.0 <= inner < outer <= math.pi / 2
    outer, inner = mappings.spot_cone_angles(math.radians(90), 1.0)
    assert inner == pytest.approx(0.0, abs=1e-6)
    _, inner = mappings.spot_cone_angles(math.radians(60), 0.5)
    assert math.cos(inner) == pytest.approx(math.cos(math.radians(30)) + 0.5 * (1 - math.cos(math.radians(30))))


def test_spot_size_and_blend_invert_the_cone_angles():
    rng = random.Random(4)
    for _ in range(TRIALS):
        size, blend = rng.uniform(0.01, math.pi), rng.uniform(0.0, 1.0)
        back_size, back_blend = mappings.spot_size_and_blend(*mappings.spot_cone_angles(size, blend))
        assert back_size == pytest.approx(size, rel=1e-12)
        assert back_blend == pytest.approx(blend, abs=1e-5)  # a Blend of 0 keeps the inner cone a millionth in


@pytest.mark.parametrize("fit, width, height, expected", [
    ("AUTO", 200, 100, (2.0, 1.0)), ("AUTO", 100, 200, (1.0, 2.0)), ("AUTO", 100, 100, (2.0, 2.0)),
    ("HORIZONTAL", 100, 200, (2.0, 4.0)), ("VERTICAL", 200, 100, (4.0, 2.0)), ("VERTICAL", 100, 200, (1.0, 2.0))])
def test_orthographic_scale_spans_the_side_sensor_fit_names(fit, width, height, expected):
    assert mappings.orthographic_half_extents(4.0, fit, width, height) == pytest.approx(expected)
