"""The strand's own reactions at both ends (``strand.model.reactions``, columns of steps.csv and
lines of the summary): balance under tension alone, Costello's tension–torque coupling, and the
uniform bending set-up's own end couples, computed there another way."""

from __future__ import annotations

import csv
import io

import pytest

from strand.analytical import held_end_torque
from strand.app.case import load_case
from strand.app.run import run_case
from strand_cases import SEVEN_WIRE

QUIET = ["output.fields=false", "fatigue.outputs=false"]
#: contacts 100× stiffer than the seed paper's penalty, as tests/test_tension.py takes them
STIFF = 'same_layer = "off"\ncompliance = "penalty"\nk_point = 5e9\nk_line = 5e11\ng_lim = 5e-8'


def rows(path) -> list[dict[str, float]]:
    with open(path) as f:
        return [{k: float(v) for k, v in r.items() if k != "stage"} for r in csv.DictReader(f)]


def test_tension_alone_balances_and_gives_costellos_torque(tmp_path):
    """A 1+6 at 12° (0.1 m) pulled to 10 kN, ends held against rotation: both end tensions
    equal the applied one (measured within 1e-5), the two torques are equal and opposite
    (measured within 3e-7), no bending moment, and the torque is Costello's within 3 %
    (measured +1.1 %; tests/test_tension.py finds the midspan section's within 3 % too)."""
    path = tmp_path / "seven.toml"
    path.write_text(
        SEVEN_WIRE.replace("lay_angle = 6.06", "lay_angle = 12.0").replace(
            'same_layer = "off"', STIFF
        )
    )
    case = load_case(path, ["load.cycle=[0.0]", *QUIET])
    run_case(case, tmp_path / "out", stream=io.StringIO())
    steps = rows(tmp_path / "out" / "steps.csv")
    for s in steps:
        T = s["tension_N"]
        assert s["end_tension_0_N"] == pytest.approx(T, rel=1e-4)
        assert s["end_tension_L_N"] == pytest.approx(T, rel=1e-4)
        assert s["end_torque_0_Nm"] == pytest.approx(-s["end_torque_L_Nm"], rel=1e-5)
        for name in ("x_0", "y_0", "x_L", "y_L"):
            assert abs(s[f"end_moment_{name}_Nm"]) < 1e-6 * abs(s["end_torque_L_Nm"])
    last = steps[-1]
    torque = held_end_torque(case.cable, last["tension_N"])
    assert last["end_torque_L_Nm"] == pytest.approx(torque, rel=0.03)
    summary = (tmp_path / "out" / "summary.txt").read_text()
    assert "end reactions: tension 10.000 kN (z = 0), 10.000 kN (z = L)" in summary
    assert f"Costello, straight strand with ends held against rotation: torque {torque:+.3f}" in (
        summary
    )


def test_bending_end_moments_are_the_set_ups_own_end_couples(tmp_path):
    """In uniform bending (about y, the direction being x), the reactions' moments about y are
    the end couples the set-up computes from its own links and supports (``ZoneBending``,
    positive when they stretch the +x fibre: minus the couple on the strand at z = L)."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    bending = [
        'load.kind="bending"',
        "load.curvature=0.05",
        "load.zone=0.04",
        "steps.curvature=0.02",
        "steps.curvature_max=0.05",
    ]
    case = load_case(path, [*bending, *QUIET, "output.plots=false"])
    run_case(case, tmp_path / "out", stream=io.StringIO())
    steps = {int(s["step"]): s for s in rows(tmp_path / "out" / "steps.csv")}
    zone = rows(tmp_path / "out" / "moment_curvature.csv")
    assert len(zone) >= 3
    for z in zone:
        s = steps[int(z["step"])]
        m0, mL = z["moment_end_reaction_0_Nm"], z["moment_end_reaction_L_Nm"]
        assert s["end_moment_y_0_Nm"] == pytest.approx(m0, rel=1e-9)
        assert s["end_moment_y_L_Nm"] == pytest.approx(-mL, rel=1e-9)
        assert s["end_tension_L_N"] == pytest.approx(10e3, rel=1e-4)
