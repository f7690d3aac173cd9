"""Cycles' shader and light formulas, both ways, for the values vkdiffrender can express.

Pure Python (no bpy), so it is tested outside Blender. vkdiffrender's medium is RGB
absorption sigma_a and scattering sigma_s per scene unit plus one Henyey-Greenstein g
and an RGB emission (radiance per scene unit, Cycles' volume emission);
its emitters are radiance (emissive triangles, emission 1 = radiance 1) and, for
KHR_lights_punctual, radiant intensity per steradian (point, spot) or irradiance (sun),
in the same units. The forward formulas follow Cycles 3.4 (kernel/svm/closure.h and the
light sampling code); docs/blender.md lists them.
"""
import math
from dataclasses import dataclass

# vkdiffrender accepts |g| <= 0.99 (Cycles clamps at 0.999).
G_LIMIT = 0.99


@dataclass(frozen=True)
class Medium:
    sigma_a: tuple  # RGB absorption per scene unit
    sigma_s: tuple  # RGB scattering per scene unit
    g: float        # Henyey-Greenstein anisotropy
    emission: tuple = (0.0, 0.0, 0.0)  # RGB radiance emitted per scene unit


def _rgb(value):
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    return tuple(float(c) for c in value[:3])


def _positive(x):
    return max(x, 0.0)


# --- constant nodes --------------------------------------------------------------------

def _safe_divide(a, b):
    return a / b if b != 0.0 else 0.0


def _safe_power(a, b):
    if a < 0.0 and b != int(b):
        return 0.0
    if a == 0.0 and b < 0.0:
        return math.inf
    try:
        return math.pow(a, b)
    except OverflowError:
        return math.inf


def _safe_log(a, base):
    if a <= 0.0 or base <= 0.0:
        return 0.0
    return _safe_divide(math.log(a), math.log(base))


def _exponent(a):
    try:
        return math.exp(a)
    except OverflowError:
        return math.inf


# Cycles' svm_math (kernel/svm/math_util.h) for the Math node's operations whose result
# an export can take as a constant, with its safe functions' values at their edges
# (a division by 0 gives 0, a power of a negative base and a fractional exponent 0).
_MATH_OPERATIONS = {
    "ADD": lambda a, b, c: a + b,
    "SUBTRACT": lambda a, b, c: a - b,
    "MULTIPLY": lambda a, b, c: a * b,
    "DIVIDE": lambda a, b, c: _safe_divide(a, b),
    "MULTIPLY_ADD": lambda a, b, c: a * b + c,
    "POWER": lambda a, b, c: _safe_power(a, b),
    "LOGARITHM": lambda a, b, c: _safe_log(a, b),
    "SQRT": lambda a, b, c: math.sqrt(max(a, 0.0)),
    "EXPONENT": lambda a, b, c: _exponent(a),
    "ABSOLUTE": lambda a, b, c: abs(a),
    "MINIMUM": lambda a, b, c: min(a, b),
    "MAXIMUM": lambda a, b, c: max(a, b),
}


def math_operation(operation, operands):
    """A Math node's result for OPERATION (Blender's enum name) on its three inputs' values,
    or None for an operation not evaluated here."""
    function = _MATH_OPERATIONS.get(operation)
    return float(function(*operands)) if function else None


# --- volumes: Blender node inputs -> vkdiffrender medium ----------------------------

def principled_volume_to_medium(color, density, absorption_color, anisotropy, emission_color=0.0,
                                emission_strength=0.0):
    """Cycles' svm_node_principled_volume: the scattering closure weighs color * density,
    and the extinction is (color + absorption) * density where
    absorption = max(1 - color, 0) * max(1 - sqrt(absorption_color), 0).
    Absorption Color enters through its square root. The emission is Emission Color x
    Emission Strength, not scaled by the density."""
    color, absorption_color = _rgb(color), _rgb(absorption_color)
    density = _positive(float(density))
    sigma_s = tuple(_positive(c) * density for c in color)
    sigma_a = tuple(_positive(1.0 - c) * _positive(1.0 - math.sqrt(_positive(a))) * density
                    for c, a in zip(color, absorption_color))
    emission = tuple(_positive(c) * _positive(float(emission_strength)) for c in _rgb(emission_color))
    return Medium(sigma_a, sigma_s, float(anisotropy), emission)


def volume_absorption_to_medium(color, density):
    """Cycles' Volume Absorption: extinction (1 - color) * density, no scattering."""
    density = _positive(float(density))
    return Medium(tuple(_positive(1.0 - c) * density for c in _rgb(color)), (0.0, 0.0, 0.0), 0.0)


def volume_scatter_to_medium(color, density, anisotropy):
    """Cycles' Volume Scatter: scattering and extinction color * density, no absorption."""
    density = _positive(float(density))
    return Medium((0.0, 0.0, 0.0), tuple(_positive(c) * density for c in _rgb(color)), float(anisotropy))


def scale_medium(medium, weight):
    """A Mix Shader's factor scales its input's scattering and absorption. A Principled
    Volume's emission, the only emission of the volume nodes the export reads, Cycles 3.4
    adds at full strength wherever the factor is not 0 (svm_node_principled_volume skips
    only a weight of 0)."""
    return Medium(tuple(weight * c for c in medium.sigma_a), tuple(weight * c for c in medium.sigma_s), medium.g,
                  medium.emission if weight > 0.0 else (0.0, 0.0, 0.0))


def add_media(media):
    """Cycles sums the closures of an Add Shader. The sum of several Henyey-Greenstein
    lobes is one lobe only when their g agree; otherwise the scattering-weighted mean g
    (the same mean cosine) is returned with exact=False."""
    media = list(media)
    sigma_a = tuple(sum(m.sigma_a[i] for m in media) for i in range(3))
    sigma_s = tuple(sum(m.sigma_s[i] for m in media) for i in range(3))
    scatterers = [m for m in media if sum(m.sigma_s) > 0.0]
    total = sum(sum(m.sigma_s) for m in scatterers)
    g = sum(m.g * sum(m.sigma_s) for m in scatterers) / total if total > 0.0 else 0.0
    exact = len({m.g for m in scatterers}) <= 1
    emission = tuple(sum(m.emission[i] for m in media) for i in range(3))
    return Medium(sigma_a, sigma_s, g, emission), exact


def clamp_g(g):
    """vkdiffrender's range for g; returns (value, whether it was clamped)."""
    clamped = min(max(g, -G_LIMIT), G_LIMIT)
    return clamped, clamped != g


# --- volumes: vkdiffrender medium -> Blender node inputs ----------------------------

def medium_to_principled_volume(medium):
    """Principled Volume inputs that give exactly this medium. Not unique: the Density
    written is the largest channel of sigma_t = sigma_a + sigma_s (the smallest density
    that keeps Color and Absorption Color in [0, 1]); then Color = sigma_s / Density and
    Absorption Color = (1 - sigma_a / (Density - sigma_s))^2. Where Density - sigma_s is 0
    the channel absorbs nothing whatever Absorption Color is, and 0 is written. The
    emission splits as a surface's does (radiance_to_emission)."""
    sigma_a, sigma_s = _rgb(medium.sigma_a), _rgb(medium.sigma_s)
    emission = radiance_to_emission(medium.emission)
    density = max(a + s for a, s in zip(sigma_a, sigma_s))
    if density <= 0.0:
        return {"density": 0.0, "color": (1.0, 1.0, 1.0), "absorption_color": (0.0, 0.0, 0.0),
                "anisotropy": float(medium.g), "emission_color": emission["color"],
                "emission_strength": emission["strength"]}
    color = tuple(min(s / density, 1.0) for s in sigma_s)
    absorption_color = []
    for a, s in zip(sigma_a, sigma_s):
        room = density - s
        absorption_color.append(min(max(1.0 - a / room, 0.0), 1.0) ** 2 if room > 0.0 else 0.0)
    return {"density": density, "color": color, "absorption_color": tuple(absorption_color),
            "anisotropy": float(medium.g), "emission_color": emission["color"],
            "emission_strength": emission["strength"]}


def medium_to_volume_absorption(sigma_a):
    """Volume Absorption inputs for an absorption-only medium: Density is the largest
    channel of sigma_a, Color = 1 - sigma_a / Density (unique up to that choice)."""
    sigma_a = _rgb(sigma_a)
    density = max(sigma_a)
    if density <= 0.0:
        return {"density": 0.0, "color": (1.0, 1.0, 1.0)}
    return {"density": density, "color": tuple(1.0 - a / density for a in sigma_a)}


def medium_to_volume_scatter(sigma_s, g):
    """Volume Scatter inputs for a scattering-only medium: Density is the largest channel
    of sigma_s, Color = sigma_s / Density."""
    sigma_s = _rgb(sigma_s)
    density = max(sigma_s)
    if density <= 0.0:
        return {"density": 0.0, "color": (1.0, 1.0, 1.0), "anisotropy": float(g)}
    return {"density": density, "color": tuple(s / density for s in sigma_s), "anisotropy": float(g)}


# --- surfaces ------------------------------------------------------------------------

def emission_to_radiance(color, strength):
    """Cycles' Emission (and Principled BSDF Emission): radiance color * strength, the
    same on both sides of a mesh."""
    return tuple(c * float(strength) for c in _rgb(color))


def radiance_to_emission(radiance):
    """Color and Strength for a radiance: Strength is the brightest channel, so that
    Color stays in [0, 1] (glTF's emissiveFactor and emissiveStrength split alike)."""
    radiance = _rgb(radiance)
    strength = max(radiance)
    if strength <= 0.0:
        return {"color": (0.0, 0.0, 0.0), "strength": 0.0}
    return {"color": tuple(c / strength for c in radiance), "strength": strength}


def base_color_to_albedo(color):
    """Base Color (Principled BSDF) or Color (Diffuse BSDF) -> Lambertian albedo in [0, 1]."""
    return tuple(min(max(c, 0.0), 1.0) for c in _rgb(color))


# --- lights --------------------------------------------------------------------------
# Cycles 3.4: a point or spot light evaluates strength / (4 pi) per unit projected area of
# its disk (ls->eval_fac = M_1_PI_F * 0.25 * invarea), so its radiant intensity is
# Power / (4 pi) per steradian whatever its radius; a sun's Strength is its irradiance; an
# area light's radiance is Power / (4 * area) (ls->eval_fac = 0.25 * invarea).

def point_light_intensity(color, power):
    """Radiant intensity (per steradian) of a point or spot light of Power watts."""
    return tuple(c * float(power) / (4.0 * math.pi) for c in _rgb(color))


def intensity_to_point_light(intensity):
    """Color and Power of a point or spot light of this radiant intensity."""
    intensity = _rgb(intensity)
    peak = max(intensity)
    if peak <= 0.0:
        return {"color": (1.0, 1.0, 1.0), "power": 0.0}
    return {"color": tuple(c / peak for c in intensity), "power": 4.0 * math.pi * peak}


def sun_irradiance(color, strength):
    """Irradiance of a sun of Strength (W/m^2) on a surface facing it."""
    return tuple(c * float(strength) for c in _rgb(color))


def irradiance_to_sun(irradiance):
    irradiance = _rgb(irradiance)
    peak = max(irradiance)
    if peak <= 0.0:
        return {"color": (1.0, 1.0, 1.0), "strength": 0.0}
    return {"color": tuple(c / peak for c in irradiance), "strength": peak}


def area_light_radiance(color, power, area):
    """Radiance of the front of an area light of Power watts and this area."""
    return tuple(c * float(power) / (4.0 * area) for c in _rgb(color))


def radiance_to_area_light(radiance, area):
    radiance = _rgb(radiance)
    peak = max(radiance)
    if peak <= 0.0:
        return {"color": (1.0, 1.0, 1.0), "power": 0.0}
    return {"color": tuple(c / peak for c in radiance), "power": 4.0 * area * peak}


def spot_cone_angles(spot_size, spot_blend):
    """glTF's outer and inner cone angles for a Blender spot: the outer cone is half of
    Spot Size; Cycles fades over cosines from cos(outer) to cos(outer) + (1 - cos(outer))
    * Blend, and the inner angle has that cosine. Cycles' fade is a smoothstep times the
    cosine to the axis, glTF's a square of the linear ramp: an approximation. glTF needs
    the inner angle below the outer one: a Blend of 0 (a hard edge) gives an inner cone a
    millionth narrower."""
    outer = 0.5 * float(spot_size)
    cos_outer = math.cos(outer)
    inner = math.acos(min(cos_outer + (1.0 - cos_outer) * float(spot_blend), 1.0))
    return outer, min(inner, outer * (1.0 - 1e-6))


def spot_size_and_blend(outer, inner):
    """Blender's Spot Size and Blend for glTF's cone angles: the inverse of
    spot_cone_angles."""
    cos_outer = math.cos(float(outer))
    blend = (math.cos(float(inner)) - cos_outer) / (1.0 - cos_outer) if cos_outer < 1.0 else 0.0
    return 2.0 * float(outer), min(max(blend, 0.0), 1.0)


def orthographic_half_extents(ortho_scale, sensor_fit, width, height):
    """glTF's xmag and ymag (half the view's width and height) for a Blender orthographic
    camera rendering an image WIDTH x HEIGHT (pixels times their aspect): Cycles spans
    Orthographic Scale over the width for Sensor Fit Horizontal, the height for Vertical,
    and the longer side for Auto (Blender's BKE_camera_params_compute_viewplane)."""
    if sensor_fit == "AUTO":
        sensor_fit = "HORIZONTAL" if width >= height else "VERTICAL"
    half = 0.5 * float(ortho_scale)
    if sensor_fit == "HORIZONTAL":
        return half, half * height / width
    return half * width / height, half
