"""The built-in all-steel spiral strand ``judge120``: the 120-wire strand of
Judge et al. (2012), Construction and Building Materials 35, 452–459, as transcribed by RTE's
pallas-stranded-cable (strand/cable/data/judge120.toml names both). The numbers below are typed from
that transcription, not read from the data file: the data file is checked against them, its stated
assumptions against what they change, and the mooring case against its comments; one cheap run
of the case writes the wire-level versus T–N comparison."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from strand.analytical.costello import costello_stiffness
from strand.analytical.fibre import fibre_model
from strand.app.case import load_case
from strand.app.cli import main
from strand.cable.description import CableError, cable_from_dict, judge120
from strand.fatigue.zones import free_span, lock_reach

CASE = Path(__file__).parents[1] / "cases" / "mooring_judge120.toml"

# Judge et al. (2012) as transcribed (pallas-stranded-cable, examples/example_cable_traction.py)
WIRES = [1, 7, 17, 14, 21, 27, 33]
DIAMETERS = [5.8e-3, 4.3e-3, 3.2e-3, 5.3e-3, 5.0e-3, 5.0e-3, 5.0e-3]  # m
LAY_LENGTHS = [0.15, 0.21, 0.32, 0.42, 0.52, 0.62]  # m, layers 1–6
E, YIELD, TENSILE = 188e9, 1540e6, 2000e6  # Pa
# Bridon's (2007) measured force–strain points and Judge et al.'s 3D FE model's first point
MEASURED = [(0.00208, 0.36e6), (0.006, 0.964e6), (0.00852, 1.522e6), (0.01216, 2.216e6)]
MEASURED_BREAK = 3.606e6  # N, the largest force of the measured curve
FE_FIRST = (0.00864, 2.5e6)
LAYER_2_USED = 3.1e-3  # m, the data file's assumption (see its header)


def _area(diameters) -> float:
    return sum(n * math.pi * d**2 / 4 for n, d in zip(WIRES, diameters, strict=True))


def test_the_strand_is_the_sources_construction():
    """Per layer the source's number of wires (120 in all: "the 120-wire spiral strand") and wire
    diameter, layer 2's excepted (3.1 mm assumed for 3.2 mm); E, the yield stress and the tensile
    strength of every wire; alternating lay hands with the outer layer right hand (assumed)."""
    c = judge120()
    assert [lay.wires for lay in c.layers] == WIRES and c.n_wires == 120
    used = [*DIAMETERS[:2], LAYER_2_USED, *DIAMETERS[3:]]
    assert [lay.wire.diameter for lay in c.layers] == pytest.approx(used, rel=1e-12)
    assert {lay.wire.E for lay in c.layers} == {E}
    assert {lay.wire.yield_stress for lay in c.layers} == {YIELD}
    assert {lay.wire.tensile_strength for lay in c.layers} == {TENSILE}
    assert [lay.lay for lay in c.layers[1:]] == ["S", "Z", "S", "Z", "S", "Z"]


def test_its_lay_angles_give_the_sources_lay_lengths():
    """Each layer's lay angle, with the helix radius of touching layers, gives back the source's
    lay length within 0.01 % (the angles are written to 1e-4°); every layer fits (fill < 1)."""
    c = judge120()
    pitches = [lay.pitch for lay in c.layers[1:]]
    np.testing.assert_allclose(pitches, LAY_LENGTHS, rtol=1e-4)
    assert all(0.9 < lay.fill < 1.0 for lay in c.layers[1:])


def test_the_sources_layer_2_would_overlap_and_what_the_assumption_changes():
    """With the source's 3.2 mm wires in layer 2 at its lay length the cable is refused (fill
    1.017 ≥ 1); the assumed 3.1 mm takes the outer diameter from the source's 5.8 + 2 (4.3 + 3.2
    + 5.3 + 3 × 5.0) = 61.4 mm to 61.2 mm and the metallic area down by 0.4 %."""
    angles = [lay.lay_angle for lay in judge120().layers[1:]]
    layers = zip(WIRES[1:], DIAMETERS[1:], angles, strict=True)
    data = {
        "name": "source",
        "core": {"diameter": DIAMETERS[0], "E": E, "nu": 0.3, "friction": 0.3},
        "layer": [
            {
                "wires": n,
                "diameter": d,
                "E": E,
                "nu": 0.3,
                "lay": "SZ"[i % 2],
                "friction": 0.3,
                "lay_angle": a,
            }
            for i, (n, d, a) in enumerate(layers)
        ],
    }
    with pytest.raises(CableError, match=r"layer\[2\].*fill 1\.01[67]"):
        cable_from_dict(data)
    c = judge120()
    source_diameter = DIAMETERS[0] + 2 * sum(DIAMETERS[1:])
    assert source_diameter == pytest.approx(61.4e-3)
    assert c.outer_diameter == pytest.approx(source_diameter - 2 * (3.2e-3 - LAYER_2_USED))
    area = sum(lay.wires * lay.wire.area for lay in c.layers)
    assert area / _area(DIAMETERS) - 1 == pytest.approx(-0.0039, abs=2e-4)


def test_the_measured_breaking_force_is_below_the_wires_aggregate_strength():
    """Bridon's strand broke at 3.606 MN, 84 % of its wires' aggregate strength Σ A σ_u
    (σ_u = 2000 MPa); the mooring case takes that force as its MBS."""
    aggregate = _area(DIAMETERS) * TENSILE
    assert MEASURED_BREAK / aggregate == pytest.approx(0.833, abs=0.005)
    case = load_case(CASE)
    assert case.fatigue.breaking_strength == MEASURED_BREAK
    used = sum(lay.wires * lay.wire.area for lay in case.cable.layers) * TENSILE
    assert MEASURED_BREAK < used


def test_the_fibre_model_bounds_the_measured_and_the_3d_stiffness():
    """The fibre model's EA (ends held, wires touching rigidly; 365 MN) is Costello's ∂F/∂ε
    within 0.1 %, and above the secant stiffness of Bridon's measured curve to 2.2 MN (0.44–0.50
    of it: a new strand beds in) and of Judge et al.'s 3D FE model at 2.5 MN (0.79): contact
    compliance, bedding-in and end slip only soften a strand."""
    c = judge120()
    ea = fibre_model(c, 1.0)["EA"]
    assert costello_stiffness(c)[0, 0] == pytest.approx(ea, rel=1e-3)
    measured = [force / strain / ea for strain, force in MEASURED]
    np.testing.assert_allclose(measured, 0.47, atol=0.035)
    assert FE_FIRST[1] / FE_FIRST[0] / ea == pytest.approx(0.79, abs=0.01)


def test_the_mooring_case_reads_as_its_comments_say():
    """Mean tension 25 % MBS, swing ±5 % MBS (range 10 %), a saddle load of 2 % of the mean
    tension held (the axis turns by 2 atan(0.01) = 1.15°), 1.86 m = three lay lengths of the
    outer layer, leaving a free span of z = 0.31–1.55 m between the default end zones (half the
    outer lay length); every layer is steel and assessed with EN 1992-1-1's prestressing-steel
    curve."""
    case = load_case(CASE)
    assert case.cable.name == judge120().name
    load = case.load
    assert load.kind == "tension_cycle" and list(load.cycle) == [1.0, -1.0, 0.0]
    assert load.tension == pytest.approx(0.25 * MEASURED_BREAK)
    assert 2 * load.tension_swing == pytest.approx(0.10 * MEASURED_BREAK)
    assert load.fixed_lateral == pytest.approx(0.02 * load.tension, rel=2e-3)
    assert math.degrees(2 * math.atan(load.fixed_lateral / 2 / load.tension)) == pytest.approx(
        1.15, abs=0.01
    )
    assert case.mesh.length == pytest.approx(3 * LAY_LENGTHS[-1])
    assert case.fatigue.end_zone == 0  # the default: the lock's reach
    reach = lock_reach(case.cable)
    assert reach == pytest.approx(LAY_LENGTHS[-1] / 2, rel=1e-4)  # the pitch back from α
    assert free_span(case.mesh.length, reach) == pytest.approx((0.31, 1.55), rel=1e-4)
    curves = case.fatigue.curves(case.cable)
    assert all(c is not None and "prestressing steel" in c.name for c in curves)


@pytest.mark.slow
def test_a_cheap_run_of_the_case_writes_the_wire_level_versus_t_n_comparison(tmp_path):
    """The case at 0.05 m (h_max 10 mm, a 50 kN first tension step, ~30 s): every layer's mean
    stress change over the cycle is the fibre model's E cos²α ΔT/EA within 3 %; fatigue.txt
    assesses every layer, and gives the strand's T–N damages per cycle beside the wire-level one,
    API RP 2SK's being its closed form R^5.05 / K, R = ΔT/MBS, log₁₀K = 3.25 − 3.43 T_mean/MBS,
    for the printed mean and largest range of the rebuilt midspan tension (one steady cycle of
    the whole range), within 5 %."""
    out = tmp_path / "cheap"
    sets = ["mesh.length=0.05", "mesh.h_max=1e-2", "steps.tension=50e3"]
    sets += ["output.fields=false", "output.plots=false"]
    args = ["run", str(CASE), "--out", str(out)]
    assert main([*args, *[a for s in sets for a in ("--set", s)]]) == 0
    summary = (out / "summary.txt").read_text()
    changes = re.findall(r"^\s+(core|layer \d)\s+\+([\d.]+) /\s+\+([\d.]+)$", summary, re.M)
    assert len(changes) == 7
    for _, model, fibre in changes:
        assert float(model) == pytest.approx(float(fibre), rel=0.03)
    text = (out / "fatigue.txt").read_text()
    assert "not assessed" not in text
    tn = re.search(r"mean ([\d.]+) kN, largest range ([\d.]+) kN", text)
    mean, rng = float(tn[1]) * 1e3, float(tn[2]) * 1e3
    api = re.search(r"API RP 2SK spiral strand .*: damage ([\d.e+-]+) per cycle", text)
    k = 10 ** (3.25 - 3.43 * mean / MEASURED_BREAK)
    closed = (rng / MEASURED_BREAK) ** 5.05 / k
    assert float(api[1]) == pytest.approx(closed, rel=0.05)
    assert re.search(r"DNV-OS-E301 spiral rope .*: damage [\d.]+e-\d+ per cycle", text)
    wire = re.search(r"wire-level model on the same history: largest damage ([\d.e+-]+)", text)
    assert 0 < float(wire[1]) < 1


def test_the_shipped_tension_history_gives_the_mooring_pages_spectrum(capsys):
    """docs/mooring.md walks from cases/mooring_judge120_history.csv to a year of damage: its
    rainflow count, in three classes scaled from the record's own duration to a year, is the
    spectrum the page runs: ±2.5, ±5 and ±7.5 % MBS, 4e6, 1e6 and 1e5 cycles, each amplitude read
    in N from the kN column."""
    history = CASE.parent / "mooring_judge120_history.csv"
    args = ["spectrum", str(history), "--column", "tension_kN", "--time-column", "time_s"]
    assert main([*args, "--period", "1y", "--bins", "3"]) == 0
    out = capsys.readouterr().out
    block = out.split("[fatigue.spectrum]")[1]
    classes = [[float(a), float(n)] for a, n in re.findall(r"\[([\d.]+), ([\d.]+)\]", block)]
    mbs = MEASURED_BREAK
    expected = [[0.025 * mbs, 4e6], [0.05 * mbs, 1e6], [0.075 * mbs, 1e5]]
    np.testing.assert_allclose(classes, expected, rtol=1e-9)
    page = (CASE.parents[1] / "docs" / "mooring.md").read_text()
    assert "classes = [" + ", ".join(f"[{a:.0f}, {n:.0f}]" for a, n in classes) + "]" in page
