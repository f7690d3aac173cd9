"""The add-on's export of a Volume object (an OpenVDB file, as a smoke simulation's
cache) in headless Blender: the file is copied beside the scene, its Principled
Volume's Density Attribute names the density grid, placed by a node holding the
object's world matrix, inside a closed box that holds the grid; vkdiffrender loads and
renders the exported scene with the plume in view. docs/blender.md gives the figures of
the same scene against Cycles. A burning variant (a file with density and flame grids)
exports the grids its Color Attribute, Emission Strength attribute and Density Attribute
name as albedo, emission and density grids, and renders."""
import json
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
from conftest import run_blender_script

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def exported(blender, tmp_path_factory):
    out = tmp_path_factory.mktemp("volume")
    run_blender_script(blender, "volume_export_check.py", "--out", str(out))
    return out


def grid_media(doc):
    return [m for m in doc["materials"] if "density" in m.get("extensions", {}).get("VKDR_participating_media", {})]


def plume_medium(doc):
    media = grid_media(doc)
    assert len(media) == 1, "one medium with a density grid"
    return media[0]["extensions"]["VKDR_participating_media"]


def test_volume_object_becomes_a_grid_medium(exported):
    doc = json.loads((exported / "scene.gltf").read_text())
    # Only the warning of Blender's default bounce limits, which the scene keeps.
    assert [w for w in json.loads((exported / "warnings.json").read_text()) if "bounce limits" not in w] == []
    medium = plume_medium(doc)
    density = medium["density"]
    assert density["grid"] == "density"
    copy = exported / density["uri"]
    assert copy.is_file() and copy.read_bytes() == (HERE.parents[1] / "scenes" / "cornell_plume.vdb").read_bytes()
    node = doc["nodes"][density["node"]]
    placement = np.array(json.loads((exported / "placement.json").read_text()))
    assert np.allclose(np.array(node["matrix"]).reshape(4, 4).T, placement, atol=1e-6)
    # PLUME's Density 10 times Color and Absorption Color (Cycles' Principled Volume).
    assert medium["sigma_s"] == pytest.approx([8.0, 7.0, 6.0], rel=1e-6)


def test_exported_plume_renders(exported, cli):
    """Rendered as exported and with its medium emptied: grad's L2 loss of the one against
    the other is their mean squared difference, which the plume must make visible."""
    doc = json.loads((exported / "scene.gltf").read_text())
    medium = plume_medium(doc)
    medium["sigma_a"] = medium["sigma_s"] = [0.0, 0.0, 0.0]
    (exported / "clear.gltf").write_text(json.dumps(doc))
    settings = ["--spp", "4", "--width", "16", "--max-depth", "2"]  # the height from the camera's aspect
    render = subprocess.run([cli, "render", str(exported / "clear.gltf"), "-o", str(exported / "clear.exr"),
                             *settings], capture_output=True, text=True)
    assert render.returncode == 0, render.stderr
    name = next(m["name"] for m in json.loads((exported / "scene.gltf").read_text())["materials"]
                if "density" in m.get("extensions", {}).get("VKDR_participating_media", {}))
    grad = subprocess.run([cli, "grad", str(exported / "scene.gltf"), "--target", str(exported / "clear.exr"),
                           "--param", f"media/{name}/sigma_a", "--json", *settings], capture_output=True, text=True)
    assert grad.returncode == 0, grad.stderr
    assert "warning" not in grad.stderr
    assert json.loads(grad.stdout)["loss"] > 1e-4, "the plume changes the image"


@pytest.fixture(scope="module")
def fire(blender, tmp_path_factory):
    """The burning plume (scenes.py, "vdb_fire": its density and flame grids in one file,
    merged by vdb_tool), exported."""
    if shutil.which("vdb_tool") is None:
        pytest.skip("vdb_tool (Debian's libopenvdb-tools) is not on PATH")
    out = tmp_path_factory.mktemp("fire")
    run_blender_script(blender, "volume_export_check.py", "--out", str(out), "--fire")
    return out


def test_grid_attributes_become_albedo_and_emission_grids(fire, cli):
    assert [w for w in json.loads((fire / "warnings.json").read_text()) if "bounce limits" not in w] == []
    medium = plume_medium(json.loads((fire / "scene.gltf").read_text()))
    assert medium["density"]["grid"] == "density"
    assert medium["albedoGrid"]["grid"] == "density"
    assert medium["emissionGrid"]["grid"] == "flame"
    assert {medium[k]["uri"] for k in ("density", "albedoGrid", "emissionGrid")} == {medium["density"]["uri"]}
    assert {medium[k]["node"] for k in ("density", "albedoGrid", "emissionGrid")} == {medium["density"]["node"]}
    # Emission Color x the attribute: the colour alone, the grid giving the strength.
    assert medium["emission"] == pytest.approx([1.0, 0.5, 0.1], rel=1e-6)
    # Absorption Color black: Color (0.8, 0.7, 0.6) x Density 10 scatters, the rest absorbs.
    assert medium["sigma_s"] == pytest.approx([8.0, 7.0, 6.0], rel=1e-6)
    assert medium["sigma_a"] == pytest.approx([2.0, 3.0, 4.0], rel=1e-6)
    swapped = plume_medium(json.loads((fire / "swapped" / "scene.gltf").read_text()))
    assert swapped["density"]["grid"] == "flame", "the Density Attribute names the density grid"
    # A Color Attribute beside a non-black Absorption Color is exported, with a warning that
    # the albedo grid differs from Cycles there.
    absorbing = plume_medium(json.loads((fire / "absorbing" / "scene.gltf").read_text()))
    assert absorbing["albedoGrid"]["grid"] == "density"
    absorbing_warnings = json.loads((fire / "absorbing" / "warnings.json").read_text())
    assert any("Absorption Color other than black" in w for w in absorbing_warnings), absorbing_warnings
    # Emission Strength reading a vector grid: no emission grid, the input's unlinked value.
    vector = plume_medium(json.loads((fire / "vector_emission" / "scene.gltf").read_text()))
    assert "emissionGrid" not in vector
    assert vector["emission"] == pytest.approx([2.0, 1.0, 0.2], rel=1e-6)
    vector_warnings = json.loads((fire / "vector_emission" / "warnings.json").read_text())
    assert any("vector grid 'grad_density'" in w for w in vector_warnings), vector_warnings
    # A vector grid as the density: the Volume object is skipped, saying why.
    assert grid_media(json.loads((fire / "vector_density" / "scene.gltf").read_text())) == []
    density_warnings = json.loads((fire / "vector_density" / "warnings.json").read_text())
    assert any("its density reads the vector grid 'grad_density', and a density grid must be scalar; skipped" in w
               for w in density_warnings), density_warnings
    # Modifiers Cycles applies and the export does not: each named.
    modified_warnings = json.loads((fire / "modified" / "warnings.json").read_text())
    for name, kind in (("Displace", "VOLUME_DISPLACE"), ("Shift", "NODES")):
        assert any(f"its modifier '{name}' ({kind}) is not applied" in w for w in modified_warnings), modified_warnings
    # A Volume object scaled flat has no volume: skipped (its placement would be singular).
    assert grid_media(json.loads((fire / "flattened" / "scene.gltf").read_text())) == []
    flat_warnings = json.loads((fire / "flattened" / "warnings.json").read_text())
    assert any("its transform flattens it" in w for w in flat_warnings), flat_warnings
    render = subprocess.run([cli, "render", str(fire / "flattened" / "scene.gltf"), "-o", str(fire / "flat.exr"),
                             "--spp", "1", "--width", "8", "--height", "8", "--max-depth", "1"],
                            capture_output=True, text=True)
    assert render.returncode == 0, render.stderr
    # Which is a constant strength: Cycles emits it evenly, vkdiffrender times the density.
    assert any("a constant Emission Strength, which Cycles emits evenly" in w for w in vector_warnings), vector_warnings
    render = subprocess.run([cli, "render", str(fire / "scene.gltf"), "-o", str(fire / "fire.exr"), "--spp", "2",
                             "--width", "16", "--height", "16", "--max-depth", "2"], capture_output=True, text=True)
    assert render.returncode == 0, render.stderr
    assert "warning" not in render.stderr
