"""Fatigue for a design note: the wire-level mean-stress corrections (Goodman, Gerber, SWT)
against hand values, a user's own S–N curve against a hand Miner sum across its knee, the design
fatigue factor scaling every damage (wire-level and T–N) exactly, and bad settings refused in one
line before anything is computed."""

from __future__ import annotations

import csv
import math
import re
from dataclasses import replace

import numpy as np
import pytest

from strand.app.case import case_from_dict
from strand.app.cli import main
from strand.app.errors import CaseError
from strand.app.fatigue.report import fatigue_report
from strand.app.fatigue.wire_stresses import repeating_damage, surface_stress_at
from strand.app.history import read_history
from strand.app.settings import FatigueSettings
from strand.fatigue import (
    SN_CURVES,
    MeanStress,
    equivalent_amplitude,
    miner_damage,
    repeating_cycles,
    repeating_ranges,
)
from strand_cases import SEVEN_WIRE, one_line_error, seven_wire

MPA = 1e6
S_U = 2000 * MPA  # Pa, Judge et al.'s wires


# -- mean-stress corrections ----------------------------------------------------------------------
@pytest.mark.parametrize(
    "law, hand",
    [
        ("goodman", 100 / (1 - 500 / 2000)),  # σ_a / (1 − σ_m/σ_u) = 133.3 MPa
        ("gerber", 100 / (1 - (500 / 2000) ** 2)),  # σ_a / (1 − (σ_m/σ_u)²) = 106.7 MPa
        ("swt", math.sqrt((500 + 100) * 100)),  # √(σ_max σ_a) = 244.9 MPa
    ],
)
def test_each_law_gives_the_hand_value_of_a_cycle_about_a_tensile_mean(law, hand):
    """σ_a = 100 MPa about σ_m = 500 MPa, σ_u = 2000 MPa (25 % of it, as a strand's wires)."""
    got = equivalent_amplitude(100 * MPA, 500 * MPA, S_U, law)
    assert got == pytest.approx(hand * MPA, rel=1e-12)


@pytest.mark.parametrize("law", ["none", "goodman", "gerber", "swt"])
def test_a_zero_mean_cycle_is_not_corrected(law):
    """At σ_m = 0 every law gives the amplitude back: no correction."""
    amplitude = np.array([0.0, 1.0, 50.0, 300.0]) * MPA
    got = equivalent_amplitude(amplitude, 0.0, S_U, law)
    np.testing.assert_allclose(got, amplitude, rtol=1e-15, atol=0)


def test_compressive_means_earn_no_credit_and_a_mean_at_the_strength_breaks_the_wire():
    """Goodman and Gerber take σ_m < 0 as 0; SWT gives no damage where σ_max ≤ 0; a mean at or
    above σ_u: infinite amplitude (Goodman, Gerber), a zero range stays zero."""
    for law in ("goodman", "gerber"):
        assert equivalent_amplitude(100 * MPA, -500 * MPA, S_U, law) == 100 * MPA
        assert equivalent_amplitude(100 * MPA, S_U, S_U, law) == math.inf
        assert equivalent_amplitude(0.0, 1.5 * S_U, S_U, law) == 0.0
    assert equivalent_amplitude(100 * MPA, -200 * MPA, S_U, "swt") == 0.0
    assert equivalent_amplitude(100 * MPA, -50 * MPA, S_U, "swt") == pytest.approx(
        math.sqrt(50 * 100) * MPA, rel=1e-12
    )


@pytest.mark.parametrize("law", ["goodman", "gerber", "swt"])
def test_a_cycle_at_the_curves_own_mean_is_left_as_it_is(law):
    """A curve measured at σ_m0 = 400 MPa: a cycle about σ_m0 keeps its amplitude; Goodman by
    hand, a cycle about 500 MPa: 100 (1 − 0.2)/(1 − 0.25) = 106.7 MPa."""
    assert equivalent_amplitude(
        100 * MPA, 400 * MPA, S_U, law, reference_mean=400 * MPA
    ) == pytest.approx(100 * MPA, rel=1e-12)
    if law == "goodman":
        got = equivalent_amplitude(100 * MPA, 500 * MPA, S_U, law, reference_mean=400 * MPA)
        assert got == pytest.approx(100 * 0.8 / 0.75 * MPA, rel=1e-12)


def test_the_corrected_damage_of_a_repeating_history_is_the_hand_sum():
    """A point's stress 900 → 100 → 600 → 400 MPa, repeating: cycles of 800 and 200 MPa, both
    about 500 MPa; Goodman at σ_u = 2000 MPa makes them 800/0.75 and 200/0.75 on EN 1992-1-1's
    prestressing-steel curve; the design fatigue factor 3 triples the sum."""
    series = np.array([[900.0], [100.0], [600.0], [400.0]]) * MPA
    ranges, means = repeating_ranges(series, means=True)
    assert sorted(ranges[0]) == [200 * MPA, 800 * MPA] and list(means[0]) == [500 * MPA] * 2
    cycles = repeating_cycles(series[:, 0])
    np.testing.assert_array_equal(np.sort(cycles.mean), np.sort(means[0]))
    curve = SN_CURVES["en1992-prestressing-steel"]
    hand = sum(1 / curve.life(r / 2 / 0.75) for r in (800 * MPA, 200 * MPA))
    got = repeating_damage(series, curve, MeanStress("goodman", S_U), factor=3.0)
    assert got[0] == pytest.approx(3 * hand, rel=1e-12)
    plain = repeating_damage(series, curve)
    assert plain[0] == pytest.approx(sum(1 / curve.life(r / 2) for r in (800e6, 200e6)))


# -- a user's own S–N curve ---------------------------------------------------------------------
#: N = a1 Δσ^-3 (Δσ in MPa) to 1e7 cycles, slope 5 beyond (the form of DNV-RP-C203's curves)
LOG_A, M1, M2, KNEE = 12.164, 3.0, 5.0, 1e7
#: two blocks, one on each side of the knee (its range: (10^12.164 / 1e7)^(1/3) = 52.6 MPa)
BLOCKS = ((200.0, 1e5), (30.0, 1e8))  # (Δσ in MPa, cycles)


def _hand_damage(shift: float = 0.0) -> float:
    """Σ n/N of ``BLOCKS`` by hand: N = a1 Δσ^-m1 above the knee's range, N_k (Δσ_k/Δσ)^m2
    below; every life × 10^shift."""
    a1 = 10.0**LOG_A
    at_knee = (a1 / KNEE) ** (1 / M1)
    total = 0.0
    for stress_range, n in BLOCKS:
        life = (
            a1 * stress_range**-M1
            if stress_range >= at_knee
            else KNEE * (at_knee / stress_range) ** M2
        )
        total += n / (life * 10.0**shift)
    return total


def _user_damage(**settings) -> float:
    """The Miner sum of ``BLOCKS`` on a steel strand's wires with ``steel_sn_curve = "user"``,
    read through the case file's settings."""
    fatigue = {"steel_sn_curve": "user", "user_sn_m1": M1, "user_sn_knee": KNEE, **settings}
    case = case_from_dict(
        {"cable": "judge120", "load": {"tension": 9e5, "lateral": 1e3}, "fatigue": fatigue}
    )
    curves = case.fatigue.curves(case.cable)
    assert all(c is curves[0] or c == curves[0] for c in curves)  # every layer is steel
    ranges, counts = zip(*BLOCKS, strict=True)
    return miner_damage(np.array(ranges) * MPA, counts, curves[0])


def test_a_user_curve_gives_the_hand_damage_of_two_blocks_across_its_knee():
    """The same curve from log10 a1, from its range at 2e6 cycles (above the knee) and from its
    range at 1e9 cycles (below it, on slope m2): the hand sum within 1e-12."""
    a1 = 10.0**LOG_A
    at_2e6 = (a1 / 2e6) ** (1 / M1)
    at_knee = (a1 / KNEE) ** (1 / M1)
    at_1e9 = at_knee * (KNEE / 1e9) ** (1 / M2)
    hand = _hand_damage()
    two = dict(user_sn_m2=M2)
    assert _user_damage(user_sn_log_a=LOG_A, **two) == pytest.approx(hand, rel=1e-12)
    assert _user_damage(user_sn_range=at_2e6 * MPA, user_sn_cycles=2e6, **two) == pytest.approx(
        hand, rel=1e-12
    )
    assert _user_damage(user_sn_range=at_1e9 * MPA, user_sn_cycles=1e9, **two) == pytest.approx(
        hand, rel=1e-12
    )
    # one slope throughout: the block below the knee damages as on slope m1
    one = sum(n / (a1 * s**-M1) for s, n in BLOCKS)
    assert _user_damage(user_sn_log_a=LOG_A) == pytest.approx(one, rel=1e-12)


def test_a_mean_curve_and_its_characteristic_one_are_two_standard_deviations_apart():
    """Given the characteristic curve and s = 0.2 in log10 N, the mean curve's lives are 10^0.4
    times longer at every range (the knee's cycles with them); and back again."""
    base = dict(user_sn_log_a=LOG_A, user_sn_m2=M2, user_sn_sd=0.2)
    mean = _user_damage(user_sn_use="mean", **base)
    assert mean == pytest.approx(_hand_damage(shift=0.4), rel=1e-12)
    assert _user_damage(**base) == pytest.approx(_hand_damage(), rel=1e-12)
    back = _user_damage(user_sn_given="mean", **base)
    assert back == pytest.approx(_hand_damage(shift=-0.4), rel=1e-12)


# -- bad settings: one line, before computing ---------------------------------------------------
@pytest.mark.parametrize(
    "fatigue, message",
    [
        ({"mean_stress": "goodmann"}, r"\[fatigue\] mean_stress = 'goodmann' is unknown"),
        (
            {"mean_stress": "goodman"},
            r"\[fatigue\] mean_stress = 'goodman' needs the wires' tensile strength: the cable "
            r"'1\+6' gives none for layer\(s\) \[0, 1\]",
        ),
        ({"design_fatigue_factor": 0.5}, r"design_fatigue_factor = 0\.5: expected 1 or more"),
        ({"steel_sn_curve": "user"}, r'steel_sn_curve = "user" needs user_sn_m1'),
        (
            {"steel_sn_curve": "user", "user_sn_m1": 3.0},
            r"needs one intercept: user_sn_log_a .* none is given",
        ),
        (
            {
                "steel_sn_curve": "user",
                "user_sn_m1": 3.0,
                "user_sn_log_a": 12.0,
                "user_sn_range": 9e7,
            },
            r"needs one intercept: .* not both",
        ),
        (
            {"steel_sn_curve": "user", "user_sn_m1": 3.0, "user_sn_range": 90.0},
            r"user_sn_range = 90 Pa is below 1 MPa: did you mean 90e6",
        ),
        (
            {"steel_sn_curve": "user", "user_sn_m1": 3.0, "user_sn_log_a": 30.164},  # Δσ in Pa
            r"range of 5\.26e\+07 MPa at its knee .* log10 a1 is for Δσ in MPa",
        ),
        (
            {
                "steel_sn_curve": "user",
                "user_sn_m1": 3.0,
                "user_sn_log_a": 12.0,
                "user_sn_use": "mean",
            },
            r'user_sn_use = "mean" from a characteristic curve needs user_sn_sd',
        ),
        (
            {
                "steel_sn_curve": "user",
                "user_sn_m1": 3.0,
                "user_sn_log_a": 12.0,
                "user_sn_given": "median",
            },
            r"user_sn_given = 'median' is unknown; choose characteristic or mean",
        ),
        ({"user_sn_sd": -0.2}, r"user_sn_sd = -0\.2: expected a positive number, or 0 for off"),
    ],
)
def test_a_bad_fatigue_setting_is_refused_in_one_line_and_nothing_is_written(
    tmp_path, capsys, fatigue, message
):
    """On the 1+6, whose cable table gives no tensile strength: each bad setting by ``--set``."""
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE)
    sets = [
        a
        for key, value in fatigue.items()
        for a in ("--set", f"fatigue.{key}={value!r}".replace("'", '"'))
    ]
    before = sorted(tmp_path.rglob("*"))
    assert main(["run", str(case), "--out", str(tmp_path / "out"), *sets]) == 2
    line = one_line_error(capsys)
    assert re.search(message, line), line
    assert sorted(tmp_path.rglob("*")) == before


def test_the_user_curves_mean_must_lie_below_the_wires_strength():
    with pytest.raises(CaseError, match=r"user_sn_mean = 2\.1e\+09 Pa is not below the tensile"):
        case_from_dict(
            {
                "cable": "judge120",
                "load": {"tension": 9e5, "lateral": 1e3},
                "fatigue": {
                    "steel_sn_curve": "user",
                    "user_sn_m1": 3.0,
                    "user_sn_log_a": 12.0,
                    "mean_stress": "swt",
                    "user_sn_mean": 2.1e9,
                },
            }
        )


# -- the run's report: the factor and the correction --------------------------------------------
TENSION_CYCLE = SEVEN_WIRE.replace(
    "tension = 10e3\nlateral = 300.0\ncycle = [1.0, 0.0]",
    'kind = "tension_cycle"\ntension = 10e3\ntension_swing = 2e3\nfixed_lateral = 300.0\n'
    "cycle = [1.0, -1.0, 0.0]",
).replace("plots = false", "plots = false\nfields = false")
TENSION, BREAKING = 10e3, 60e3  # N


@pytest.fixture(scope="module")
def cycled_run(tmp_path_factory):
    """A 1+6 run (0.1 m): 10 ± 2 kN with 300 N held at midspan; its folder."""
    assert 'kind = "tension_cycle"' in TENSION_CYCLE
    folder = tmp_path_factory.mktemp("design")
    case = folder / "cycle.toml"
    case.write_text(TENSION_CYCLE)
    assert main(["run", str(case), "--out", str(folder / "out")]) == 0
    return folder / "out"


def _strong(cable, strength: float = S_U):
    """``cable`` with every wire's tensile strength ``strength`` (Pa)."""
    layers = tuple(
        replace(lay, wire=replace(lay.wire, tensile_strength=strength)) for lay in cable.layers
    )
    return replace(cable, layers=layers)


def test_the_design_fatigue_factor_multiplies_every_damage_exactly(cycled_run):
    """DFF 3: every element's, pair's and wire's damage and the DNV and API T–N damages are 3
    times those without it (to round-off), lives a third; the ranges are the same."""
    cable = seven_wire(length=0.1).cable
    plain = fatigue_report(
        cycled_run, cable, TENSION, FatigueSettings(breaking_strength=BREAKING), write=False
    )
    design = fatigue_report(
        cycled_run,
        cable,
        TENSION,
        FatigueSettings(breaking_strength=BREAKING, design_fatigue_factor=3.0),
        write=False,
    )
    assert np.all(plain.elements.damage > 0) and np.all(plain.crossings.damage > 0)
    np.testing.assert_allclose(design.elements.damage, 3 * plain.elements.damage, rtol=1e-15)
    np.testing.assert_allclose(design.crossings.damage, 3 * plain.crossings.damage, rtol=1e-15)
    np.testing.assert_allclose(design.wires.whole.damage, 3 * plain.wires.whole.damage, rtol=1e-15)
    np.testing.assert_allclose(
        design.wires.whole.repetitions, plain.wires.whole.repetitions / 3, rtol=1e-15
    )
    np.testing.assert_array_equal(design.elements.range, plain.elements.range)
    t, t3 = plain.tension_check, design.tension_check
    assert t.cycle and t.dnv > 0 and t.api > 0
    assert t3.dnv == pytest.approx(3 * t.dnv, rel=1e-15)
    assert t3.api == pytest.approx(3 * t.api, rel=1e-15)
    assert "design fatigue factor 3" in design.text and "design fatigue factor" not in plain.text
    user = FatigueSettings(steel_sn_curve="user", user_sn_m1=M1, user_sn_log_a=LOG_A)
    mine = fatigue_report(cycled_run, cable, TENSION, user, write=False)
    assert set(mine.wires.curve) == {"user"} and "user curve (characteristic)" in mine.text


def test_goodman_damages_each_element_at_its_equivalent_ranges(cycled_run):
    """With Goodman (σ_u = 2000 MPa) the worst element's damage is, at its worst surface point,
    the Miner sum over its repeating cycles of N(Δσ/(1 − σ_m/σ_u)) by hand, and above the
    uncorrected one; wires.csv and fatigue.txt name the law; without it they are as before."""
    cable = _strong(seven_wire(length=0.1).cable)
    plain = fatigue_report(cycled_run, cable, TENSION, FatigueSettings(), write=False)
    report = fatigue_report(cycled_run, cable, TENSION, FatigueSettings(mean_stress="goodman"))
    assert np.all(report.elements.damage > plain.elements.damage)
    sections = read_history(cycled_run / "wire_sections.h5")
    curve = SN_CURVES["en1992-prestressing-steel"]
    e = int(np.argmax(report.elements.damage))
    psi = 2 * np.pi * np.arange(16) / 16
    sigma = surface_stress_at(sections, np.full(16, e), psi)  # (S, 16)
    hand = []
    for point in sigma.T:
        c = repeating_cycles(point)
        hand.append(
            sum(1 / curve.life(r / 2 / (1 - m / S_U)) for r, m in zip(c.range, c.mean, strict=True))
        )
    assert report.elements.damage[e] == pytest.approx(max(hand), rel=1e-12)
    with open(cycled_run / "wires.csv") as f:
        rows = list(csv.DictReader(f))
    assert {r["mean_stress"] for r in rows} == {"goodman"}
    assert "mean stress: Goodman" in (cycled_run / "fatigue.txt").read_text()
    fatigue_report(cycled_run, cable, TENSION, FatigueSettings())  # the defaults again
    with open(cycled_run / "wires.csv") as f:
        header = next(csv.reader(f))
    assert "mean_stress" not in header and "design_fatigue_factor" not in header
    assert "mean stress" not in (cycled_run / "fatigue.txt").read_text()


def test_a_spectrum_sums_the_design_damages_and_says_so(tmp_path):
    """A two-amplitude spectrum of the 1+6's tension cycle with DFF 3 and Goodman: per wire and
    zone, spectrum.csv's D is 3 times Σ nᵢ dᵢ of the members reported again without the factor
    (to its six digits), and spectrum.txt and spectrum.csv name the factor and the law."""
    counts = {1e3: 1e5, 2e3: 1e4}
    spectrum = ", ".join(f"[{a!r}, {n!r}]" for a, n in counts.items())
    text = TENSION_CYCLE.replace("[cable.core]", f"[cable.core]\ntensile_strength = {S_U!r}")
    text = text.replace("[[cable.layer]]", f"[[cable.layer]]\ntensile_strength = {S_U!r}")
    text += (
        f"[fatigue]\nspectrum = [{spectrum}]\ndesign_fatigue_factor = 3.0\n"
        f'mean_stress = "goodman"\nbreaking_strength = {BREAKING!r}\n'
    )
    case = tmp_path / "spectrum.toml"
    case.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(case), "--out", str(out)]) == 0
    cable = _strong(seven_wire(length=0.1).cable)
    settings = FatigueSettings(mean_stress="goodman", breaking_strength=BREAKING)
    members = {
        a: fatigue_report(out / f"tension_swing_{a:g}", cable, TENSION, settings, write=False)
        for a in counts
    }
    total = sum(n * members[a].elements.damage for a, n in counts.items())
    clamp = members[1e3].elements.clamp
    with open(out / "spectrum.csv") as f:
        rows = list(csv.DictReader(f))
    assert {r["design_fatigue_factor"] for r in rows} == {"3"}
    assert {r["mean_stress"] for r in rows} == {"goodman"}
    for r in rows:
        mine = (members[1e3].elements.wire == int(r["wire"])) & (
            clamp == (r["zone"] != "free span")
        )
        assert float(r["damage"]) == pytest.approx(3 * total[mine].max(), rel=1e-5)
    summary = (out / "spectrum.txt").read_text()
    assert "design fatigue factor 3" in summary and "mean stress: Goodman" in summary
