"""The add-on's checks of the glTF it has written and of the folder it writes to (plain
Python, without Blender): numbers that are not finite, emission beyond what vkdiffrender
takes, the entry a JSON path lies in, and which files of the folder an export may
replace."""
import json

from vkdiffrender_blender import export_checks

DOC = {
    "materials": [{"name": "Wall"},
                  {"name": "Lamp", "emissiveFactor": [1.0, 0.5, 0.0],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 10.0},
                                  "VKDR_participating_media": {"sigma_a": [0.1, 0.2, 0.3]}}}],
    "extensions": {"KHR_lights_punctual": {"lights": [{"name": "Bulb", "intensity": 5.0, "color": [1.0, 1.0, 1.0]}]}},
}


def with_value(path_keys, value):
    doc = json.loads(json.dumps(DOC))
    entry = doc
    for key in path_keys[:-1]:
        entry = entry[key]
    entry[path_keys[-1]] = value
    return doc


def test_the_first_number_that_is_not_finite_is_found_with_its_path_and_owner():
    assert export_checks.first_non_finite(DOC) is None
    doc = with_value(["materials", 1, "extensions", "VKDR_participating_media", "sigma_a", 2], float("nan"))
    path = export_checks.first_non_finite(doc)
    assert path == "materials[1].extensions.VKDR_participating_media.sigma_a[2]"
    assert export_checks.owner_of(doc, path) == " ('Lamp')"
    doc = with_value(["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], float("-inf"))
    path = export_checks.first_non_finite(doc)
    assert (path, export_checks.owner_of(doc, path)) == ("extensions.KHR_lights_punctual.lights[0].intensity",
                                                          " ('Bulb')")
    assert export_checks.owner_of(DOC, "extensions.KHR_lights_punctual") == ""


def test_emission_beyond_the_limit_is_found_in_lights_materials_media_and_the_background():
    assert export_checks.first_beyond_emission_limit(DOC) is None
    limit = export_checks.MAX_EMISSION
    doc = with_value(["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], 2.0 * limit)
    assert export_checks.first_beyond_emission_limit(doc) == ("extensions.KHR_lights_punctual.lights[0]", 2.0 * limit)
    doc = with_value(["materials", 1, "extensions", "KHR_materials_emissive_strength", "emissiveStrength"], 3.0 * limit)
    assert export_checks.first_beyond_emission_limit(doc) == ("materials[1]", 3.0 * limit)
    doc = with_value(["extensions", "VKDR_background"], {"radiance": [0.0, limit * 1.5, 0.0]})
    assert export_checks.first_beyond_emission_limit(doc) == ("extensions.VKDR_background", 1.5 * limit)
    doc = with_value(["materials", 1, "extensions", "VKDR_participating_media", "emission"], [0.0, 0.0, 4.0 * limit])
    assert export_checks.first_beyond_emission_limit(doc) == (
        "materials[1].extensions.VKDR_participating_media.emission", 4.0 * limit)
    doc = with_value(["extensions", "VKDR_participating_media"], {"emission": 5.0 * limit})
    assert export_checks.first_beyond_emission_limit(doc) == ("extensions.VKDR_participating_media.emission",
                                                              5.0 * limit)
    # At the limit itself, as vkdiffrender takes it.
    doc = with_value(["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], limit)
    assert export_checks.first_beyond_emission_limit(doc) is None


def test_an_export_replaces_only_its_own_files_or_the_same_bytes(tmp_path):
    folder, staging = tmp_path / "folder", tmp_path / "staging"
    folder.mkdir()
    staging.mkdir()
    for name in ("scene.gltf", "scene.bin", "my photo.png", "other.png", "same.png"):
        (staging / name).write_text(f"new {name}")
    # The earlier export refers to its buffer and to an image by a percent-encoded URI.
    (folder / "scene.gltf").write_text(json.dumps({"buffers": [{"uri": "scene.bin"}],
                                                   "images": [{"uri": "my%20photo.png"}]}))
    (folder / "scene.bin").write_text("old buffer")
    (folder / "my photo.png").write_text("old photo")
    (folder / "other.png").write_text("the user's own")
    (folder / "same.png").write_text("new same.png")
    assert export_checks.files_it_would_replace(staging, folder, "scene.gltf") == ["other.png"]
    (folder / "scene.gltf").write_text("not the JSON of a scene")
    assert export_checks.files_it_would_replace(staging, folder, "scene.gltf") == ["my photo.png", "other.png",
                                                                                  "scene.bin"]
