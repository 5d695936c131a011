"""Fatigue a mooring or conductor engineer can act on: steel wires assessed with their published
S–N curve, layers without one reported "not assessed", the strand-level T–N check of the mooring
standards, stuck versus slid on a physical threshold, Poffenberger–Swart only where its long span
holds, and the free span reported apart from the clamp zones."""

from __future__ import annotations

import csv
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from strand.app.case import load_case
from strand.app.cli import main
from strand.app.fatigue.report import fatigue_report
from strand.app.fatigue.tension_check import strand_tension
from strand.app.history import read_history
from strand.app.settings import FatigueSettings
from strand.cable.description import cardinal
from strand.fatigue import (
    SN_CURVES,
    api_spiral_strand_life,
    dnv_spiral_rope_life,
    free_span,
    in_clamp_zone,
    miner_damage,
    span_check,
    span_error,
    stuck_throughout,
)
from strand_cases import SEVEN_WIRE, seven_wire

ROOT = Path(__file__).resolve().parents[1]


# -- S–N curves of steel wire (EN 1992-1-1:2004, Table 6.4N) -----------------------------------
@pytest.mark.parametrize(
    "key, at_knee, k2",
    [("en1992-prestressing-steel", 185.0, 9.0), ("en1992-steel-duct", 120.0, 7.0)],
)
def test_steel_wire_curves_are_eurocode_2s_prestressing_steel(key, at_knee, k2):
    """Δσ_Rsk at N* = 1e6 cycles, slope k1 = 5 above, k2 below (the table's values): the curve
    gives N* at Δσ_Rsk, 1e5 at Δσ_Rsk 10^(1/5) and 1e8 at Δσ_Rsk 100^(−1/k2); σ_a is half Δσ."""
    curve = SN_CURVES[key]
    assert curve.material == "steel"
    for cycles, stress_range in (
        (1e6, at_knee),
        (1e5, at_knee * 10 ** (1 / 5)),
        (1e8, at_knee * 100 ** (-1 / k2)),
    ):
        assert curve.life(0.5e6 * stress_range) == pytest.approx(cycles, rel=1e-9)


def test_a_steel_wire_at_a_known_stress_range_gets_the_damage_the_curve_gives_by_hand():
    """200 cycles of 250 MPa: N = 1e6 (185/250)^5 by Table 6.4N's k1 = 5, D = 200/N."""
    n = 1e6 * (185.0 / 250.0) ** 5
    damage = miner_damage([250e6] * 200, [1.0] * 200, SN_CURVES["en1992-prestressing-steel"])
    assert damage == pytest.approx(200 / n, rel=1e-9)


def test_each_layer_gets_its_materials_curve_or_none():
    """Cardinal: steel core and layer 1 with the steel curve, aluminium layers with CIGRE's;
    ``steel_sn_curve = "none"`` leaves the steel layers without one (not assessed)."""
    curves = FatigueSettings().curves(cardinal())
    assert [c.material for c in curves] == ["steel"] * 2 + ["aluminium"] * 3
    none = FatigueSettings(steel_sn_curve="none").curves(cardinal())
    assert none[:2] == [None, None] and none[2] is curves[2]


# -- strand-level T–N (DNV-OS-E301, API RP 2SK) -------------------------------------------------
def test_spiral_strand_t_n_lives_at_known_tension_ranges():
    """DNV-OS-E301 spiral rope n = 1.7e17 s^−4.8 (s in MPa over the metallic area) and API RP 2SK
    spiral strand N = 10^(3.25 − 3.43 L_m) R^−5.05 (R = ΔT/MBS), from the constants by hand."""
    area = 500e-6  # m²
    assert dnv_spiral_rope_life(100e6 * area, area) == pytest.approx(1.7e17 * 100**-4.8, rel=1e-12)
    mbs = 1e6
    life = api_spiral_strand_life(0.1 * mbs, mbs, 0.3 * mbs)
    assert life == pytest.approx(10 ** (3.25 - 3.43 * 0.3) * 0.1**-5.05, rel=1e-12)
    assert np.isinf(dnv_spiral_rope_life(0.0, area))


# -- stuck versus slid ---------------------------------------------------------------------------
def test_a_pair_with_round_off_slip_is_stuck_and_one_that_slides_a_micrometre_is_not():
    """The 1 nm threshold: a pair whose Coulomb slide is round-off (1e-17 m) stayed stuck; one
    that slid by 1e-6 m did not, even if it comes back to where it started."""
    sliding = np.zeros((4, 3, 3))
    sliding[1:, 0, 0] = 1e-17
    sliding[2, 1, 1] = 1e-6  # out and back
    sliding[1:, 2, 2] = 1e-6
    np.testing.assert_array_equal(stuck_throughout(sliding, 1e-9), [True, False, False])


# -- Poffenberger–Swart's long span ----------------------------------------------------------------
def test_poffenberger_swart_is_skipped_on_a_short_span_and_holds_on_a_long_one():
    """Cardinal at 40 kN, read at 89 mm: on 0.25 m the finite span changes the clamp curvature
    by more than 10 % with EI_max (skipped, with the reason); on 1 m it holds. The error tends
    to 0 for a long span (semi-infinite beam) and is large when kx is not small against ka."""
    short, long = (span_check(cardinal(), 40e3, span, 0.089) for span in (0.25, 1.0))
    assert not short.holds and "too short" in short.reason and abs(short.error) > 0.1
    assert long.holds and abs(long.error) < 0.1
    assert abs(span_error(50.0, 2.0, 0.089)) < 1e-12
    assert not span_check(cardinal(), 40e3, 0.1, 0.089).holds  # the point beyond the load


# -- the run's report ------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def seven_wire_run(tmp_path_factory):
    """A 1+6 run (0.1 m, 10 kN, lateral ±300 N), its folder."""
    folder = tmp_path_factory.mktemp("zones")
    case = folder / "seven.toml"
    case.write_text(SEVEN_WIRE.replace("cycle = [1.0, 0.0]", "cycle = [1.0, -1.0, 0.0]"))
    assert main(["run", str(case), "--out", str(folder / "out")]) == 0
    return folder / "out"


def _rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def test_steel_wires_are_assessed_and_a_layer_without_a_curve_reads_not_assessed(seven_wire_run):
    """The all-steel 1+6: every wire has a finite, positive damage under the steel curve; with
    ``steel_sn_curve = "none"`` every wire and pair reads "not assessed" (NaN damage, never 0 or
    inf) and fatigue.txt says so in one line."""
    cable = seven_wire().cable
    wires = _rows(seven_wire_run / "wires.csv")
    assert {w["sn_curve"] for w in wires} == {"en1992-prestressing-steel"}
    assert all(0 < float(w["damage"]) < math.inf for w in wires)
    r = fatigue_report(seven_wire_run, cable, 10e3, FatigueSettings(steel_sn_curve="none"))
    wires = _rows(seven_wire_run / "wires.csv")
    assert {w["sn_curve"] for w in wires} == {"not assessed"}
    assert all(
        math.isnan(float(w[k]))
        for w in wires
        for k in ("damage", "repetitions_to_failure", "damage_free_span")
    )
    pairs = _rows(seven_wire_run / "crossings.csv")
    assert {p["damage_assessed"] for p in pairs} == {"not assessed"}
    assert all(math.isnan(float(p["damage"])) for p in pairs)
    assert sum("not assessed" in line for line in r.text.splitlines()) == 1
    assert "layers [0, 1]: not assessed" in r.text


def test_pairs_that_never_slipped_are_stuck_throughout(seven_wire_run):
    """crossings.csv's stuck_throughout: every pair whose state never read "slip" is stuck,
    some pairs slid; the count per interface is in fatigue.txt."""
    pairs = read_history(seven_wire_run / "contact_pairs.h5")
    never = np.all(pairs["state"] != 2, axis=0)
    stuck = np.array([int(p["stuck_throughout"]) for p in _rows(seven_wire_run / "crossings.csv")])
    assert np.all(stuck[never] == 1) and np.any(stuck == 0)
    assert (
        f"{stuck.sum()} of {len(stuck)} pairs at 0|1"
        in (seven_wire_run / "fatigue.txt").read_text()
    )


def test_hot_spots_and_damage_are_split_by_zone(seven_wire_run):
    """With a 20 mm end zone: each element's zone follows its z; a wire's damage is the larger
    of its free-span and clamp-zone damage; the free span's hot spots lie in [20, 80] mm; the
    strand tension rebuilt at midspan is the applied 10 kN, and the report says the run has no
    tension cycle; Poffenberger–Swart is skipped on this 0.1 m span."""
    cable = seven_wire().cable
    r = fatigue_report(seven_wire_run, cable, 10e3, FatigueSettings(end_zone=0.02))
    sections = read_history(seven_wire_run / "wire_sections.h5")
    z = sections.static["z"]
    np.testing.assert_array_equal(r.elements.clamp, in_clamp_zone(z, 0.1, 0.02))
    assert r.elements.clamp.any() and (~r.elements.clamp).any()
    wires = r.wires
    np.testing.assert_allclose(
        wires.whole.damage, np.maximum(wires.free_span.damage, wires.clamp_zone.damage)
    )
    free = r.text.split("free span (")[1].split("clamp zone (")[0]
    hot = [
        row
        for row in free.split("hot spots")[1].split("first wires")[0].splitlines()[2:]
        if row.strip()
    ]
    assert len(hot) == 5 and all(0.02 <= float(line.split()[3]) <= 0.08 for line in hot)
    tension = strand_tension(sections)
    np.testing.assert_allclose(tension, 10e3, rtol=1e-2)
    assert "no tension cycle" in r.text
    check, worst = r.tension_check, int(np.nanargmax(wires.whole.damage))
    assert check.wire == worst
    assert check.wire_in_clamp == (wires.clamp_zone.damage[worst] >= wires.free_span.damage[worst])
    assert check.free_wire == int(np.nanargmax(wires.free_span.damage))
    assert check.free_damage == wires.free_span.damage[check.free_wire] <= check.wire_damage
    where = "clamp zone" if check.wire_in_clamp else "free span"
    assert f"per cycle (wire {worst}, {where})" in r.text
    assert ("; in the free span" in r.text) == check.wire_in_clamp
    assert "Poffenberger–Swart skipped" in r.text and r.poffenberger_swart.holds is False
    default = replace(FatigueSettings(), end_zone=0.0).end_zone_length(cable)
    assert default == pytest.approx(cable.layers[-1].pitch / 2)  # how far the ends' lock reaches


def _intervals(text: str) -> list[tuple[float, float]]:
    return [(float(a), float(b)) for a, b in re.findall(r"z in \[([-\d.e]+), ([-\d.e]+)\]", text)]


def test_a_span_without_a_free_span_says_so_in_one_line(seven_wire_run):
    """0.1 m of the 1+6 at the default end zone, half its 0.198 m lay length: no free span, one
    line saying what span or end zone would leave one (no interval, let alone an inverted one),
    and every element in the clamp zone."""
    cable = seven_wire().cable
    r = fatigue_report(seven_wire_run, cable, 10e3, FatigueSettings(), write=False)
    lines = [line for line in r.text.splitlines() if line.startswith("free span")]
    half = cable.layers[1].pitch / 2
    assert lines == [
        f"free span: none: the span 0.1 m is not longer than two end zones (2 × {half:.4g} m, "
        f"[fatigue] end_zone); a span longer than {2 * half:.4g} m, or an end_zone shorter than "
        "0.05 m, leaves one"
    ]
    assert f"{2 * half:.4g}" == "0.1977" and _intervals(r.text) == []
    assert r.tension_check.free_wire is None and r.tension_check.wire_in_clamp
    assert f"(wire {r.tension_check.wire}, clamp zone: no free span)" in r.text
    assert r.elements.clamp.all() and f"clamp zone (within {half:.4g} m of an end):" in r.text


def test_the_quick_case_reports_its_free_span(quick_run):
    """cases/quick_1x6.toml as shipped: a free span 0.099–0.201 m of its 0.3 m, with its own hot
    spots and first wires to fail; the clamp zones reported beside it."""
    text = (quick_run["folder"] / "fatigue.txt").read_text()
    case = quick_run["case"]
    half = case.cable.layers[1].pitch / 2
    assert _intervals(text) == [(round(half, 5), round(0.3 - half, 4))]
    free = text.split(f"free span (z in [{half:.4g}, {0.3 - half:.4g}] m):\n")[1]
    free = free.split("clamp zone (")[0]
    hot = [
        row
        for row in free.split("hot spots")[1].split("first wires")[0].splitlines()[2:]
        if row.strip()
    ]
    assert len(hot) == 5 and all(half <= float(row.split()[3]) <= 0.3 - half for row in hot)
    assert "none" not in free and f"clamp zone (within {half:.4g} m of an end):" in text


@pytest.mark.parametrize("name", sorted(p.name for p in (ROOT / "cases").glob("*.toml")))
def test_every_example_case_has_a_free_span_or_says_why_not(name):
    """Each case in cases/ leaves a free span of more than one element at its end zone, or its
    comments say that it has none."""
    path = ROOT / "cases" / name
    case = load_case(path)
    span = free_span(case.mesh.length, case.fatigue.end_zone_length(case.cable))
    if span is None:
        assert "No free span" in path.read_text(), name
    else:
        assert span[1] - span[0] > case.mesh.h_max, (name, span)
