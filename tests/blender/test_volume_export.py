"""The add-on's export of a Volume object (an OpenVDB file, as a smoke simulation's
cache) in headless Blender: the file is copied beside the scene, its Principled
Volume's Density Attribute names the density grid, placed by a node holding the
object's world matrix, inside a closed box that holds the grid; vkdiffrender loads and
renders the exported scene with the plume in view. docs/blender.md gives the figures of
the same scene against Cycles."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def exported(blender, tmp_path_factory):
    out = tmp_path_factory.mktemp("volume")
    subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                    str(HERE / "volume_export_check.py"), "--", "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL)
    return out


def plume_medium(doc):
    media = [m for m in doc["materials"] if "density" in m.get("extensions", {}).get("VKDR_participating_media", {})]
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
    settings = ["--spp", "4", "--width", "16", "--height", "16", "--max-depth", "2"]
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
