"""What the export refuses in the glTF it has written, or in the folder it writes to:
numbers that are not finite (json writes a NaN as a bare NaN, which no glTF reader
parses), emission beyond what vkdiffrender takes, and files in the export folder that
an export would replace without having written them. Plain Python on the JSON and the
files, testable without Blender; scene_checks.py checks the Blender scene."""
import filecmp
import json
import math
import os
from collections.abc import Mapping, Sequence
from urllib.parse import unquote

from .gltf_json import EXTENSION


def is_non_finite(value):
    """Whether VALUE is a float that is NaN or infinite."""
    return isinstance(value, float) and not math.isfinite(value)


def first_non_finite(value, path=""):
    """The JSON path of the first number in VALUE (a JSON document) that is not finite."""
    if is_non_finite(value):
        return path
    if isinstance(value, Mapping):
        items = ((f"{path}.{key}" if path else key, item) for key, item in value.items())
    elif isinstance(value, Sequence) and not isinstance(value, str):
        items = ((f"{path}[{i}]", item) for i, item in enumerate(value))
    else:
        return None
    for item_path, item in items:
        found = first_non_finite(item, item_path)
        if found is not None:
            return found
    return None


# The most vkdiffrender takes of an emitted radiance or a light's intensity, per channel
# (docs/scene-format.md).
MAX_EMISSION = 1e12


def _largest_channel(value):
    """The largest channel of an RGB list or a single number (a medium's emission)."""
    return max(value) if isinstance(value, list) and value else value if isinstance(value, (int, float)) else 0.0


def first_beyond_emission_limit(doc):
    """(JSON path, value) of the first light intensity, emission (of a surface or a
    medium) or background radiance of the document beyond MAX_EMISSION in some channel,
    or None."""
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    for i, light in enumerate(lights):
        value = light.get("intensity", 1.0) * max(light.get("color", [1.0, 1.0, 1.0]))
        if value > MAX_EMISSION:
            return f"extensions.KHR_lights_punctual.lights[{i}]", value
    for i, material in enumerate(doc.get("materials", [])):
        strength = material.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get(
            "emissiveStrength", 1.0)
        value = strength * max(material.get("emissiveFactor", [0.0, 0.0, 0.0]))
        if value > MAX_EMISSION:
            return f"materials[{i}]", value
        medium = material.get("extensions", {}).get("VKDR_participating_media", {})
        if _largest_channel(medium.get("emission", 0.0)) > MAX_EMISSION:
            return (f"materials[{i}].extensions.VKDR_participating_media.emission",
                    _largest_channel(medium["emission"]))
    scene_medium = doc.get("extensions", {}).get("VKDR_participating_media", {})
    if _largest_channel(scene_medium.get("emission", 0.0)) > MAX_EMISSION:
        return "extensions.VKDR_participating_media.emission", _largest_channel(scene_medium["emission"])
    background = doc.get("extensions", {}).get("VKDR_background", {}).get("radiance", [0.0])
    if max(background) > MAX_EMISSION:
        return "extensions.VKDR_background", max(background)
    return None


def owner_of(doc, path):
    """' (name)' of the innermost named array entry (a material, a node, a light) that
    the JSON path PATH lies in, or ''."""
    name, value = None, doc
    for segment in path.split("."):
        key, *indices = segment.replace("]", "").split("[")
        value = value.get(key) if isinstance(value, Mapping) else None
        for index in indices:
            value = value[int(index)] if isinstance(value, list) and int(index) < len(value) else None
            if isinstance(value, Mapping) and isinstance(value.get("name"), str):
                name = value["name"]
    return f" ('{name}')" if name else ""


def previous_export_files(gltf_path):
    """The files a scene already at GLTF_PATH refers to (its buffers, images and grids):
    an export there may replace them, as it replaces the scene."""
    try:
        with open(gltf_path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return set()
    uris = [entry.get("uri") for key in ("buffers", "images") for entry in doc.get(key, [])
            if isinstance(entry, Mapping)]
    owners = [doc.get("extensions", {})] + [m.get("extensions", {}) for m in doc.get("materials", [])
                                            if isinstance(m, Mapping)]
    for extensions in owners:
        medium = extensions.get(EXTENSION, {}) if isinstance(extensions, Mapping) else {}
        for reference in medium.values() if isinstance(medium, Mapping) else []:
            if isinstance(reference, Mapping):
                uris.append(reference.get("uri"))
    return {os.path.normpath(unquote(uri)) for uri in uris if isinstance(uri, str) and not uri.startswith("data:")}


def files_it_would_replace(staging, directory, gltf_name):
    """The files of STAGING whose names are taken in DIRECTORY by a file that is neither
    the scene GLTF_NAME, nor one its previous export there refers to, nor the same bytes."""
    ours = previous_export_files(os.path.join(directory, gltf_name)) | {gltf_name}
    taken = []
    for name in sorted(os.listdir(staging)):
        existing = os.path.join(directory, name)
        if name in ours or not os.path.lexists(existing):
            continue
        if os.path.isfile(existing) and not os.path.islink(existing) and filecmp.cmp(
                existing, os.path.join(staging, name), shallow=False):
            continue
        taken.append(name)
    return taken
