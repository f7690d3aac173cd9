"""The add-on's import of a fitted scene.gltf in headless Blender: a scene with a
Principled Volume cube, a World fog and a point light is exported with the add-on,
`vkdiffrender optimize` moves its parameters for two iterations (so the values differ
from anything Blender held) and writes run/scene.gltf; the add-on's import operator
reads that into an empty file. The nodes and the light must give back params.json's
values to float precision (Blender's sockets and light properties are float32: 1e-6
relative, a few float32 roundings). Blender's own importer, run on the same file, must
fail on numpy.bool where numpy lacks it (Debian 12), which is what the add-on works
around, and the add-on must leave numpy as it found it."""
import json
import re
import subprocess

import pytest
from conftest import run_blender_script

FLOAT32 = 1e-6
PARAMS = ("media/smoke/sigma_a", "media/smoke/sigma_s", "media/smoke/g", "media/World/sigma_s",
          "lights/bulb/intensity")


def blender_step(blender, *args):
    run_blender_script(blender, "import_check.py", *args)


def run_cli(cli, *args):
    subprocess.run([cli, *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def imported(blender, cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("import")
    blender_step(blender, "--step", "export", "--out", str(out))
    run_cli(cli, "render", str(out / "scene.gltf"), "-o", str(out / "target.exr"), "--spp", "8", "--width", "16",
            "--height", "16", "--max-depth", "3",
            "--set", "media/smoke/sigma_a=0.5", "--set", "media/World/sigma_s=0.05",
            "--set", "lights/bulb/intensity=4")
    parameters = [argument for name in PARAMS for argument in ("--param", name)]
    run_cli(cli, "optimize", str(out / "scene.gltf"), "--target", f"camera={out / 'target.exr'}", *parameters,
            "--iters", "2", "--spp", "2", "--max-depth", "3", "--out", str(out / "run"))
    blender_step(blender, "--step", "import", "--gltf", str(out / "run" / "scene.gltf"), "--out", str(out))
    exported = json.loads((out / "scene.gltf").read_text())
    fitted = json.loads((out / "run" / "params.json").read_text())
    return exported, fitted, json.loads((out / "imported.json").read_text()), out


def test_import_restores_the_fitted_media_and_light(imported):
    exported, fitted, result, _ = imported
    smoke, world = result["media"]["smoke"], result["world"]
    assert world["name"] == "World"
    assert smoke["sigma_a"] == pytest.approx(fitted["media/smoke/sigma_a"], rel=FLOAT32)
    assert smoke["sigma_s"] == pytest.approx(fitted["media/smoke/sigma_s"], rel=FLOAT32)
    assert smoke["g"] == pytest.approx(fitted["media/smoke/g"][0], rel=FLOAT32)
    assert world["sigma_s"] == pytest.approx(fitted["media/World/sigma_s"], rel=FLOAT32)
    # Not fitted: the exported values, through the run's scene.gltf and back.
    fog = exported["extensions"]["VKDR_participating_media"]
    assert world["sigma_a"] == pytest.approx(fog["sigma_a"], rel=FLOAT32)
    assert world["g"] == pytest.approx(fog["g"], rel=FLOAT32)
    assert result["lights"]["bulb"] == pytest.approx(fitted["lights/bulb/intensity"], rel=FLOAT32)


def test_a_volume_behind_an_opaque_surface_is_not_imported_as_a_medium(imported):
    assert imported[2]["media_of_volume_materials"] == ["Clear", "Material_2"]


def test_lights_are_matched_by_the_names_blenders_importer_gives_their_objects(imported):
    # The node's name, else the light's, else its type's ("Point").
    assert imported[2]["light_objects"] == ["Point", "Lamp", "Named"]


def test_the_fit_moved_every_value(imported):
    """Two iterations change each value by far more than float precision, so the check
    above reads the fitted file, not the exported one."""
    exported, fitted, _, _ = imported
    start = exported["extensions"]["KHR_lights_punctual"]["lights"][0]
    first = start["intensity"] * start["color"][0]
    assert abs(fitted["lights/bulb/intensity"][0] / first - 1.0) > 100 * FLOAT32
    assert abs(fitted["media/World/sigma_s"][0] / exported["extensions"]["VKDR_participating_media"]["sigma_s"][0]
               - 1.0) > 100 * FLOAT32


def test_numpy_bool_failure_is_worked_around(imported):
    _, _, result, _ = imported
    if not result["numpy_bool_before"]:
        assert "has no attribute 'bool'" in (result["plain_importer_error"] or ""), \
            "Blender's own importer no longer fails on numpy.bool: the add-on's workaround may go"
    assert result["numpy_bool_after"] == result["numpy_bool_before"]


def test_export_warns_of_cycles_settings_vkdiffrender_cannot_follow(imported):
    """Clip Start skips the World volume in front of Cycles' camera, and Cycles' default
    per-kind bounce limits stop paths vkdiffrender continues (docs/blender.md)."""
    warnings = json.loads((imported[3] / "export_warnings.json").read_text())
    assert not [w for w in warnings["scene"] if "Clip Start" in w or "bounce limits" in w]
    clipping = [w for w in warnings["defaults"] if "Clip Start (0.1)" in w]
    assert len(clipping) == 1 and "1.2 % darker" in clipping[0]
    assert [w for w in warnings["defaults"] if "bounce limits Diffuse 4, Glossy 4, Volume 0" in w]


def test_a_file_that_is_not_gltf_is_missing_or_holds_a_medium_of_text_gives_one_line_naming_it(imported):
    unreadable = imported[2]["unreadable"]
    assert "not_gltf.gltf: not a glTF file (its JSON does not parse" in unreadable["not_gltf.gltf"]
    assert "missing.gltf: no such file" in unreadable["missing.gltf"]
    field = r"materials\[\d+\]\.extensions\.VKDR_participating_media\.sigma_a"
    assert re.search(r"text_medium\.gltf: " + field + r": expected a finite number or three within float range, "
                     r"got \"lots\"",
                     unreadable["text_medium.gltf"])
    assert re.search(r"light_index\.gltf: nodes\[\d+\]\.extensions\.KHR_lights_punctual\.light: expected the "
                     r"index of one of the \d+ lights, got 99", unreadable["light_index.gltf"])
    # Blender's importer's own failure is named by its exception, not by where the
    # operator was called from.
    assert re.search(r"half_made\.gltf: Blender's glTF importer cannot read it \(TypeError: .+\); nothing was "
                     r"imported", unreadable["half_made.gltf"]), unreadable["half_made.gltf"]
    # The values are checked before Blender's importer runs, and what it made of a file it
    # failed on is removed: the refused files added nothing.
    refused = imported[2]["refused_import"]
    assert refused["after"] == refused["before"]
    for message in unreadable.values():
        assert "Traceback" not in message and len(message.splitlines()) == 1, message


def test_an_orthographic_camera_keeps_the_height_vkdiffrender_keeps(imported):
    camera = imported[2]["orthographic_camera"]
    assert (camera["type"], camera["sensor_fit"]) == ("ORTHO", "VERTICAL")
    assert camera["ortho_scale"] == pytest.approx(1.5)


def test_a_file_of_another_unit_scale_imports_the_scene_at_the_size_it_was_exported(imported):
    # The export writes Blender units as they are; Blender's own importer would divide
    # the places by the Unit Scale, leaving the media's coefficients and the lights'
    # powers those of a scene 100 times smaller.
    placed = imported[2]["camera_location"]
    assert placed["0.01"]["location"] == pytest.approx(placed["1.0"]["location"], rel=1e-6)
    assert placed["0.01"]["unit_scale_after"] == pytest.approx(0.01)
