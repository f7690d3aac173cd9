"""tools/compare_with_cycles.py, run as its docstring says on a shipped scene at a tiny
size: it completes and writes finite figures, and refuses bad input with one `error:`
line and exit code 2."""
import json
import math
import subprocess

from conftest import REPOSITORY

TOOL = REPOSITORY / "tools" / "compare_with_cycles.py"


def run_tool(blender, *arguments):
    return subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", str(TOOL),
                           "--", *map(str, arguments)], capture_output=True, text=True)


def test_the_comparison_runs_and_writes_finite_figures(blender, cli, tmp_path):
    run = run_tool(blender, "--cli", cli, REPOSITORY / "scenes" / "cornell_fog.gltf", "--size", 8, "--spp", 4,
                   "--max-depth", 2, "--threads", 1, "--out", tmp_path)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    comparison = json.loads((tmp_path / "comparison.json").read_text())
    (scene,) = comparison["scenes"]
    ratios = [scene["ratios"][key] for key in ("time", "noise", "efficiency", "mean")]
    for value in (*ratios, *comparison["overall"].values()):
        assert math.isfinite(value) and value > 0.0
    assert math.isfinite(scene["ratios"]["mean_z"])
    assert sorted(p.name for p in (tmp_path / "cornell_fog").glob("*.exr")) == [
        "cycles_1.exr", "cycles_2.exr", "vkdr_1.exr", "vkdr_2.exr"]


def test_a_missing_scene_is_one_error_line(blender, cli, tmp_path):
    run = run_tool(blender, "--cli", cli, tmp_path / "absent.gltf", "--out", tmp_path)
    assert run.returncode == 2
    assert [line for line in run.stderr.splitlines() if line.startswith("error:")] == [
        f"error: {tmp_path / 'absent.gltf'}: no such file"]
