"""Shared fixtures of the Blender add-on's tests. ctest runs them with VKDIFFRENDER_CLI
naming the command line; the tests that need Blender skip where it is absent."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPOSITORY / "tools" / "blender"))


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("VKDIFFRENDER_CLI", str(REPOSITORY / "build" / "src" / "cli" / "vkdiffrender"))
    assert pathlib.Path(path).is_file(), f"no command line at {path}; set VKDIFFRENDER_CLI"
    return path


@pytest.fixture(scope="session")
def blender():
    path = shutil.which("blender")
    if path is None:
        pytest.skip("blender is not installed (Debian: apt-get install blender); the Cycles comparisons need it")
    return path


def run_blender_script(blender, script, *arguments):
    """Runs tests/blender/SCRIPT in headless Blender, with ARGUMENTS after its `--`; a
    Python error in it fails the run."""
    subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                    str(REPOSITORY / "tests" / "blender" / script), "--", *arguments], check=True,
                   stdout=subprocess.DEVNULL)
