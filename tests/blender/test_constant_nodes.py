"""Inputs fed by constant nodes (Value, RGB and Math nodes, chained, through a Reroute)
are exported as the values Cycles computes from them: each case's Emission plane, seen
by Cycles at one sample a pixel (a uniform emitter: the pixel is its radiance, without
noise), against the add-on's reading of the same inputs (constant_nodes_check.py)."""
import json

import pytest
from conftest import run_blender_script

# Cycles evaluates the nodes in single precision, the add-on in double: a few roundings
# of a float's relative 6e-8 apart.
FLOAT_ROUNDING = 1e-6


@pytest.fixture(scope="module")
def measured(blender, tmp_path_factory):
    out = tmp_path_factory.mktemp("constant_nodes")
    run_blender_script(blender, "constant_nodes_check.py", "--out", str(out))
    return json.loads((out / "constant_nodes.json").read_text())


def test_constant_nodes_are_exported_as_cycles_evaluates_them(measured):
    constant = {name: case for name, case in measured.items() if name != "texture"}
    assert len(constant) == 22
    for name, case in constant.items():
        assert case["exported"] == pytest.approx(case["cycles"], rel=FLOAT_ROUNDING, abs=1e-7), name
        assert case["warnings"] == [], name


def test_a_math_node_of_a_texture_is_not_evaluated_and_is_warned_of(measured):
    case = measured["texture"]
    assert case["exported"] == [1.0, 1.0, 1.0]  # the Strength's unlinked value
    assert case["cycles"][0] != pytest.approx(1.0, rel=FLOAT_ROUNDING)
    assert case["warnings"] == ["texture: 'Emission' input 'Strength' is linked from 'Math' (ShaderNodeMath), "
                                "which the export does not evaluate; its unlinked value is used"]
