"""A cycle of the tension as a load programme (``[load] kind = "tension_cycle"``): the end
force the run records swings over the range asked, the wires' stress ranges follow the
fibre model, and the fatigue report's strand-level T–N damage is DNV-OS-E301's closed form for
that range; alone or with a saddle load held at midspan; bad settings refused; and the example
case file read as its comments say."""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest

from strand.analytical.fibre import fibre_model
from strand.app.case import CaseError, case_from_dict, load_case
from strand.app.cli import main
from strand.app.fatigue.tension_check import strand_tension
from strand.app.history import read_history
from strand_cases import SEVEN_WIRE

MEAN, SWING = 10e3, 2e3  # N
CYCLE = [
    "--set",
    'load.kind="tension_cycle"',
    "--set",
    f"load.tension_swing={SWING}",
    "--set",
    "load.cycle=[1.0, -1.0, 0.0]",
    "--set",
    "steps.tension_swing=1e3",
    "--set",
    "steps.tension_swing_max=2e3",
    "--set",
    "output.fields=false",
]


def _rows(path) -> list[dict[str, str]]:
    with open(path) as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def seven(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tension_cycle")
    path = folder / "seven.toml"
    path.write_text(SEVEN_WIRE)  # [contact] same_layer = "off": crossings only
    return path


@pytest.fixture(scope="module")
def cycle_run(seven):
    """The 1+6 (0.1 m) at 10 kN, its end force cycled 10 → 12 → 8 → 10 kN."""
    out = seven.parent / "out"
    assert main(["run", str(seven), "--out", str(out), *CYCLE]) == 0
    return out


@pytest.fixture(scope="module")
def held_run(seven):
    """The same cycle with a 300 N saddle load held at midspan."""
    out = seven.parent / "held"
    assert (
        main(
            [
                "run",
                str(seven),
                "--out",
                str(out),
                *CYCLE,
                "--set",
                "load.fixed_lateral=300.0",
                "--set",
                "output.plots=false",
            ]
        )
        == 0
    )
    return out


def _end_forces(run) -> dict[int, float]:
    """The end force (N) of every step of ``run``'s steps.csv, by step number."""
    return {int(s["step"]): float(s["end_force_N"]) for s in _rows(run / "steps.csv")}


def test_the_recorded_tension_range_is_the_one_asked(cycle_run):
    """steps.csv: the end force from the tensioned state through the cycle spans T ± swing
    exactly, the mean tension held; the midspan section carries the end force (1e-5)."""
    steps = _rows(cycle_run / "steps.csv")
    tensioned = [s for s in steps if s["stage"] == "tension"][-1]
    cycle = [s for s in steps if s["stage"].startswith("leg")]
    force = np.array([float(s["end_force_N"]) for s in [tensioned, *cycle]])
    assert force.max() == MEAN + SWING and force.min() == MEAN - SWING
    assert {float(s["tension_N"]) for s in cycle} == {MEAN}
    np.testing.assert_array_equal(force[1:], [MEAN + float(s["tension_swing_N"]) for s in cycle])
    for s in _rows(cycle_run / "moment_curvature.csv"):
        assert float(s["axial_sum_N"]) == pytest.approx(float(s["end_force_N"]), rel=1e-5)


def test_wire_stress_ranges_follow_the_fibre_model(cycle_run, seven):
    """Each layer's surface stress range over the middle half of the span is E cos²α ΔT/EA (the
    fibre model's ε cos²α, ΔT = 2 swing) within 1 % (measured: core +0.15 %, layer 1 +0.65 %:
    the helical wires' bending adds at their surface); the summary's end displacement change
    at the peak is L ΔT/EA within 1 %."""
    cable = load_case(seven).cable
    ea = fibre_model(cable, 1.0)["EA"]
    rows = _rows(cycle_run / "wire_stresses.csv")
    for i, lay in enumerate(cable.layers):
        expected = lay.wire.E * math.cos(lay.alpha) ** 2 * 2 * SWING / ea
        ranges = np.array(
            [
                float(r["range_MPa"]) * 1e6
                for r in rows
                if int(r["layer"]) == i and 0.025 <= float(r["z_m"]) <= 0.075
            ]
        )
        assert len(ranges) > 10
        np.testing.assert_allclose(ranges, expected, rtol=0.01)
    summary = (cycle_run / "summary.txt").read_text()
    change = re.search(
        r"end displacement change \+([\d.]+) µm, fibre model .* \+([\d.]+) µm", summary
    )
    assert change and float(change[1]) == pytest.approx(float(change[2]), rel=0.01)
    assert float(change[2]) == pytest.approx(1e6 * SWING * 0.1 / ea, rel=1e-3)


def test_the_t_n_damage_is_dnvs_closed_form_for_the_range(cycle_run):
    """fatigue.txt: a tension cycle is seen; the largest range of the strand's tension rebuilt at
    midspan is 2 swing within 0.5 %, and the DNV-OS-E301 damage printed per cycle is the closed
    form (ΔT/A)^4.8 / 1.7e17 of one steady repetition of 10 → 12 → 8 → 10 kN (one full cycle of
    ΔT = 2 swing), within 2.5 % (4.8 × the range's tolerance)."""
    text = (cycle_run / "fatigue.txt").read_text()
    assert "no tension cycle" not in text
    largest = re.search(r"largest range ([\d.]+) kN", text)
    assert float(largest[1]) * 1e3 == pytest.approx(2 * SWING, rel=5e-3)
    area = 7 * math.pi * 3.34e-3**2 / 4  # m², the 1+6's metallic area
    s = 2 * SWING / area / 1e6  # MPa
    closed = s**4.8 / 1.7e17
    printed = re.search(r"DNV-OS-E301 spiral rope .*: damage ([\d.e+-]+) per cycle", text)
    assert float(printed[1]) == pytest.approx(closed, rel=0.025)


@pytest.mark.parametrize("run", ["cycle_run", "held_run"])
def test_the_midspan_section_carries_the_end_force(run, request):
    """Equilibrium of the half strand z < L/2, with no saddle load and with 300 N held: the
    saddle load is lateral and, without same-layer contact, every contact pair joins nodes at
    one z, so the z resultant of the wires' full section forces (axial and shear) over the
    section z = L/2 is the end force at every step, up to Newton's leftover (residual norms up
    to 0.2 N; 2e-6, 0.02 N at 10 kN; measured ≤ 5.4e-7): in the kind's record
    (moment_curvature.csv) and in the fatigue history the T–N check reads (``midspan_force``).
    The axial forces alone, Σ N cos α over the wires' elements nearest midspan, fall short of
    it by 1.5–2.9e-5 (the helical wires' shear forces have axial components)."""
    out = request.getfixturevalue(run)
    force = _end_forces(out)
    for s in _rows(out / "moment_curvature.csv"):
        assert float(s["axial_sum_N"]) == pytest.approx(force[int(s["step"])], rel=2e-6)
    sections = read_history(out / "wire_sections.h5")
    end = np.array([force[k] for k in sections.numbers])
    np.testing.assert_allclose(strand_tension(sections), end, rtol=2e-6)
    st, case = sections.static, load_case(out / "case.toml")
    cos = np.cos([lay.alpha for lay in case.cable.layers])
    mid = case.mesh.length / 2
    nearest = [
        np.flatnonzero(st["wire"] == w)[np.argmin(np.abs(st["z"][st["wire"] == w] - mid))]
        for w in np.unique(st["wire"])
    ]
    axial_only = sections["axial"][:, nearest] @ cos[st["layer"][nearest]]
    assert np.max(np.abs(axial_only / end - 1)) > 5e-6
    # a history written before midspan_force was recorded: the axial sum stands in
    del sections.arrays["midspan_force"]
    np.testing.assert_array_equal(strand_tension(sections, case.cable), axial_only)
    np.testing.assert_allclose(axial_only, end, rtol=1e-4)


@pytest.mark.parametrize("run", ["cycle_run", "held_run"])
def test_the_t_n_mean_is_the_cycles_not_the_steps(run, request):
    """fatigue.txt's T–N mean tension is the largest cycle's, (max + min)/2 = 10 kN, within the
    four digits printed. The recorded steps sample the legs unevenly (10 → 12 by 1 kN, 12 → 8
    by 1, 1.5 and 1.5 kN, 8 → 10 by 1 kN), so that their plain mean is 10.06 kN: what the
    report must not give."""
    out = request.getfixturevalue(run)
    text = (out / "fatigue.txt").read_text()
    mean = re.search(r"on the strand's tension at midspan \(mean ([\d.]+) kN", text)
    assert float(mean[1]) * 1e3 == pytest.approx(MEAN, rel=5e-4)
    plain = strand_tension(read_history(out / "wire_sections.h5")).mean()
    assert abs(plain - MEAN) > 1e-3 * MEAN


def test_a_saddle_load_held_through_the_tension_cycle(held_run):
    """With ``fixed_lateral``: the saddle load is applied after the tension and held at every
    cycle step, the strand deflects under it, and the end force still spans T ± swing."""
    steps = _rows(held_run / "steps.csv")
    assert [s["stage"] for s in steps][:3] == ["tension", "tension", "lateral"]
    cycle = [s for s in steps if s["stage"].startswith("leg")]
    assert {float(s["lateral_N"]) for s in cycle} == {300.0}
    assert all(float(s["deflection_m"]) > 1e-6 for s in cycle)
    force = [float(s["end_force_N"]) for s in cycle]
    assert (min(force), max(force)) == (MEAN - SWING, MEAN + SWING)


def _after_tension(run) -> list[str]:
    """The summary's block on the state after tension: its wire force and contact lines."""
    lines = (run / "summary.txt").read_text().splitlines()
    first = next(i for i, line in enumerate(lines) if line.startswith("after tension"))
    return [line for line in lines[first : first + 12] if "wire force" in line or "contact" in line]


def test_the_summary_after_tension_is_before_the_held_saddle_load(cycle_run, held_run):
    """The summary compares the state at the tension's end with the fibre model: with a saddle
    load held after the tension, it is the same state as without one (the same tension steps),
    not the state under the saddle load (whose bending moves the middle half's wire forces)."""
    plain, held = _after_tension(cycle_run), _after_tension(held_run)
    assert len(plain) >= 3 and held == plain


def test_a_tension_cycle_that_compresses_the_strand_is_refused():
    """One line each: the lowest end force T − swing at or below 0; a held saddle shorter than
    the mesh's elements."""
    with pytest.raises(
        CaseError,
        match=r"tension_swing = 12000 N takes the end force down to "
        r"-2000 N .* must stay above 0",
    ):
        case_from_dict({"load": {"kind": "tension_cycle", "tension": 10e3, "tension_swing": 12e3}})
    with pytest.raises(CaseError, match=r"saddle_length = 0.001 m"):
        case_from_dict(
            {"load": {"kind": "tension_cycle", "fixed_lateral": 100.0, "saddle_length": 1e-3}}
        )
    ok = case_from_dict({"load": {"kind": "tension_cycle", "saddle_length": 1e-3}})
    assert ok.load.tension_swing == 10e3 and ok.load.fixed_lateral == 0.0


def test_the_tension_cycle_case_file_reads_as_its_comments_say():
    """cases/quick_1x6_tension_cycle.toml: the kind, 10 kN ± 3 kN with a 300 N saddle held, and
    the programme tension → saddle → legs to 13, 7 and 10 kN of end force."""
    from pathlib import Path

    from strand.app.kinds import kind_of

    case = load_case(Path(__file__).parents[1] / "cases" / "quick_1x6_tension_cycle.toml")
    kind = kind_of(case)
    assert kind.name == "tension_cycle" and case.unset_loads == ()
    assert (case.load.tension, case.load.tension_swing, case.load.fixed_lateral) == (
        10e3,
        3e3,
        300.0,
    )
    stages = kind.programme(case).stages
    assert [s.parameter for s in stages] == ["tension", "lateral"] + ["tension_swing"] * 3
    assert [case.load.tension + s.target for s in stages[2:]] == [13e3, 7e3, 10e3]
