"""benchmarks/wire_count.py's strands, loads and fits (no run: the benchmark runs them)."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from strand.cable.description import cable_from_dict

SCRIPT = Path(__file__).parents[1] / "benchmarks" / "wire_count.py"


@pytest.fixture(scope="module")
def wc():
    with pytest.MonkeyPatch.context() as mp:
        mp.syspath_prepend(str(SCRIPT.parent))  # the script imports its folder's harness
        spec = importlib.util.spec_from_file_location("wire_count", SCRIPT)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("wires", [7, 19, 37, 61, 91, 127])
def test_strands_have_their_wires_on_touching_layers(wc, wires):
    cable = cable_from_dict(wc.strand_cable(wires))
    d = wc.WIRE_DIAMETER
    assert cable.n_wires == wires
    for k, layer in enumerate(cable.layers[1:], start=1):
        assert layer.wires == 6 * k
        assert layer.radius == pytest.approx(k * d)  # each layer on the one below
        assert layer.fill == pytest.approx(3 / (math.pi * math.cos(math.radians(14.0))))
    hands = [layer.hand for layer in cable.layers[1:]]  # alternating, the outer layer Z
    assert hands[-1] == 1 and all(a == -b for a, b in zip(hands, hands[1:], strict=False))
    assert cable.outer_diameter == pytest.approx((2 * len(cable.layers) - 1) * d)


def test_loads_scale_with_the_breaking_strength(wc):
    mbs = 7 * math.pi * 3e-3**2 / 4 * 1770e6  # 87.6 kN
    assert wc.breaking_strength(7) == pytest.approx(mbs)
    case = wc.case_for(7, 0.2, ['contact.same_layer="off"'])
    assert case.load.tension == pytest.approx(0.2 * mbs)
    assert case.load.lateral == pytest.approx(0.02 * mbs)
    assert tuple(case.load.cycle) == (1.0, 0.0)
    assert case.steps.tension == pytest.approx(case.load.tension / 40)
    assert case.steps.lateral / case.load.lateral == pytest.approx(250 / 4300)
    assert case.mesh.length == 0.2 and case.contact.same_layer == "off"
    big = wc.case_for(127, 0.2, [])
    assert big.load.tension / case.load.tension == pytest.approx(127 / 7)


def test_other_wire_counts_are_refused(wc):
    with pytest.raises(SystemExit, match="7, 19, 37"):
        wc.layers_of(20)


def test_exponent_of_a_power_law(wc):
    wires = np.array([7, 19, 37, 61])
    assert wc.exponent(wires, 3.0 * wires**2.5) == pytest.approx(2.5)
    assert wc.exponent(wires, [1.0, math.nan, 4.0, 0.0]) == pytest.approx(
        math.log(4) / math.log(37 / 7)
    )
    assert math.isnan(wc.exponent([7], [1.0]))
