"""Shared fixtures of the Python module's tests. ctest runs them with the module on
PYTHONPATH, VKDIFFRENDER_CLI naming the command line, and the Vulkan validation layer
on (VKDR_VALIDATION=1: any validation message raises vkdiffrender.Error)."""
import os
import pathlib

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
SCENES = REPOSITORY / "scenes"


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("VKDIFFRENDER_CLI", str(REPOSITORY / "build" / "src" / "cli" / "vkdiffrender"))
    assert pathlib.Path(path).is_file(), f"no command line at {path}; set VKDIFFRENDER_CLI"
    return path


@pytest.fixture(scope="session")
def fog_scene_file():
    return SCENES / "cornell_fog.gltf"
