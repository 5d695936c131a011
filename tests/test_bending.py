"""Uniform bending under tension: the set-up's equilibrium, the stick limit, and the
analytical stick–slip references it is compared with."""

from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np
import pytest

from forms import CircularSection
from strand.analytical import (
    StickSlipLaw,
    TensionedBeam,
    clamped_deflection,
    ei_min,
    loop_area,
    masing,
    stick_bending_estimate,
)
from strand.analytical.fibre import bending_stiffness_bounds
from strand.app.case import CaseError, case_from_dict
from strand.app.kinds.saddle_report import saddle_beam_reference
from strand.cable.description import cardinal
from strand.cable.geometry import build_geometry
from strand.model.cell_results import cell_results
from strand.model.contact_settings import ContactSettings
from strand.model.layer_fields import zone_layer_fields
from strand.model.model import layer_section
from strand.model.problem import StrandProblem
from strand.setups.bending import UniformBendingTest
from strand.solver import LoadStepper, NewtonOptions


def nineteen_wire(friction: float | None = None):
    cable = cardinal()
    layers = cable.layers[:3]
    if friction is not None:
        layers = [replace(lay, friction=friction) for lay in layers]
    return type(cable)("1+6+12", layers)


def bent(cable, contact: ContactSettings, curvatures, length=0.3, tension=10e3, tensioned=None):
    """The uniform bending test on ``cable``: tension, then the curvatures in turn; yields the
    zone's bending record at each. ``tensioned``: a list that receives the cell results after
    tension."""
    geometry = build_geometry(cable, length, 4e-3)
    problem = StrandProblem(
        geometry,
        contact,
        NewtonOptions(atol=1e-3, max_it=15),
        setup=partial(UniformBendingTest, zone=length / 3),
    )
    setup = problem.setup
    LoadStepper(problem.solver, tension, tension / 64).ramp(
        partial(setup.set, "tension"), 0.0, tension
    )
    if tensioned is not None:
        tensioned.append(cell_results(problem.model, setup.direction))
    stepper = LoadStepper(problem.solver, curvatures[0], curvatures[0] / 64, extrapolate=True)
    for kappa in curvatures:
        stepper.ramp(partial(setup.set, "curvature"), setup.get("curvature"), kappa)
        cells = cell_results(problem.model, setup.direction)
        yield setup.moment_curvature(cells, problem.solver.unconstrained_residual()), problem


@pytest.mark.parametrize(
    "same_layer",
    ["off", pytest.param("packed", marks=pytest.mark.slow)],  # packed: 22 s
)
def test_the_moment_is_uniform_and_equals_the_end_couples(same_layer):
    """Strand plus core strut are loaded by the end couples alone: every section of the zone
    carries the same moment, equal to the reaction couple at either end, and the section's axial
    force equals the tension (friction on, layers partly slipping at the larger curvature).
    Section cuts take each cut element's midpoint forces (one-point elements), so they carry an
    error of the wires' shear force × (distance to the midpoint ≤ h/2): measured 0.35 % here.
    With packed layers the end reactions match within 0.20 / 0.13 % at κ = 0.01 / 0.13 1/m; with
    the same-layer pairs' frozen normal (not objective: a rigid rotation closes them by
    d ω²/2) they were 0.5 / 1.7 % off, and 14 % at κ = 0.66 1/m."""
    for zb, problem in bent(nineteen_wire(), ContactSettings(same_layer=same_layer), [0.01, 0.1]):
        slipping = problem.pair_results().slipping.mean()
        M = zb.moment_zone_middle
        print(zb)
        assert M > 0 and zb.curvature > 0
        assert np.ptp(zb.section_moments) < 5e-3 * M, zb
        assert zb.moment_end_reaction_0 == pytest.approx(M, rel=3e-3)
        assert zb.moment_end_reaction_L == pytest.approx(M, rel=3e-3)
        # same-layer pairs straddling a cut carry part of the tension across it, which the
        # wires' section forces leave out: 3.2e-4 of it here (packed)
        assert zb.axial_force == pytest.approx(10e3, rel=1e-6 if same_layer == "off" else 5e-4)
    assert slipping > 0.1  # the last state really slips


def seven_wire(friction: float):
    cable = cardinal()
    return type(cable)("1+6", [replace(lay, friction=friction) for lay in cable.layers[:2]])


@pytest.mark.slow
def test_frictionless_slope_is_the_wires_own_bending():
    """Frictionless 1+6+12 (objective ``director`` normal), 0.9 m so that the 0.3 m zone holds 1.5
    lay lengths, T = 1 kN: M/κ within 5 % of EI_min, taken as the Costello-type Σ nEI cosα
    2/(2 + ν sin²α) since the beams bend and twist along their helices (the three variants differ
    by 1.5 % here; measured 0.97). Shorter pieces read low (0.3 m: 0.79, its zone is half a lay
    length), and so does a higher tension (10 kN: 0.90; the wires slip sideways towards shorter
    paths, which intra-layer contacts, not modelled, would stop)."""
    cable = nineteen_wire()
    zb, _ = next(
        bent(
            cable,
            ContactSettings(same_layer="off", normal="director", friction=False),
            [0.05],
            0.9,
            1e3,
        )
    )
    slope = zb.moment_zone_middle / zb.curvature
    assert slope == pytest.approx(ei_min(cable, "COSTELLO"), rel=0.05)
    assert np.ptp(zb.section_moments) < 5e-3 * zb.moment_zone_middle


def test_full_stick_reaches_the_plane_section_stiffness_on_a_line_contact():
    """Core + layer 1 (line contact), μ = 5, elastic slip 0.05 µm: nothing slips and M/κ is within
    10 % of EI_max (plane sections); with the seed paper's elastic slip (g_lim = 5 µm) the
    tangential compliance makes the same strand markedly softer."""
    cable = seven_wire(friction=5.0)
    _, ei_max = bending_stiffness_bounds(cable)
    stiff = [
        zb.moment_zone_middle / zb.curvature
        for zb, _ in bent(
            cable,
            ContactSettings(same_layer="off", compliance="penalty", g_lim=5e-8),
            [0.002, 0.005],
        )
    ]
    assert stiff[0] == pytest.approx(ei_max, rel=0.1), (stiff, ei_max)
    assert stiff[1] == pytest.approx(stiff[0], rel=1e-3)  # linear: no slip
    soft = next(bent(cable, ContactSettings(same_layer="off", compliance="penalty"), [0.002]))[0]
    assert soft.moment_zone_middle / soft.curvature < 0.8 * stiff[0]


def test_full_stick_with_crossings_is_limited_by_the_beams_not_the_contacts():
    """Core + layers 1 and 2 (crossings 1|2), μ = 5: the stick slope does not move when the
    contacts are made 100× stiffer or the elastic slip 10× smaller, and it stays well below
    EI_max (measured 0.55 EI_max; Cardinal 0.25): what the beam model with contacts at discrete
    crossings reaches. Recorded so that a change of the element that lifts it is seen. Also
    measured: the same with elements of 2 mm (0.545), wires' shear stiffness ×100 (0.550), 10×
    stiffer wire bending (layer 2's stick share 0.40 → 0.52 of its plane-section share): the
    wires bend between crossings under the friction forces, which act at their surfaces."""
    cable = nineteen_wire(friction=5.0)
    _, ei_max = bending_stiffness_bounds(cable)
    slopes = []
    for contact in (
        ContactSettings(same_layer="off", compliance="penalty", g_lim=5e-8),
        ContactSettings(same_layer="off", compliance="penalty", g_lim=5e-9),
        ContactSettings(
            same_layer="off", compliance="penalty", g_lim=5e-8, k_point=5e9, k_line=5e11
        ),
    ):
        zb = next(bent(cable, contact, [0.002]))[0]
        slopes.append(zb.moment_zone_middle / zb.curvature)
    print(slopes, ei_max)
    assert np.ptp(slopes) < 0.02 * slopes[0]
    assert 0.4 * ei_max < slopes[0] < 0.7 * ei_max


def full_stick_fields(cable):
    """The first step (κ = 0.002 1/m) of ``cable`` in full stick, crossings only (penalty,
    g_lim = 0.05 µm): its zone record, its stick–slip law and the zone's wire fields per layer
    (``layer_fields.zone_layer_fields``); asserts that no pair slips."""
    base = []
    contact = ContactSettings(same_layer="off", compliance="penalty", g_lim=5e-8)
    zb, problem = next(bent(cable, contact, [0.002], tensioned=base))
    assert problem.pair_results().slipping.sum() == 0
    law = StickSlipLaw(cable, 10e3)
    plane = np.array([lay.K * lay.r for lay in law.layers])
    cells = cell_results(problem.model, problem.setup.direction)
    return (
        zb,
        law,
        zone_layer_fields(cells, base[0], problem.setup.measuring_zone, zb.curvature, plane),
    )


def test_in_full_stick_the_wires_roll_on_their_ties_as_the_estimate_says():
    """The 1+6+12 of the test above in full stick (M/κ 0.547 EI_max at κ = 0.002 1/m): the zone's
    wire fields fitted per layer against φ (``layer_fields.zone_layer_fields``) beside the smeared
    estimate of wires rolling on stuck ties (``stick_bending_estimate``: M/κ 0.60 EI_max).
    Measured, layers 1 / 2: axial force share of plane sections 0.90 / 0.37 (estimate 1.00 /
    0.42), spin −0.104 / −0.022 rad m (estimate, magnitudes, 0.115 / 0.0008), torque 2.80 /
    −0.19 N m² (3.08 / 0.007): layer 1 sits on the core and stretches nearly as plane sections
    say, while spinning as the estimate does; layer 2 stretches far less. Its spin, which the
    estimate leaves at nearly zero, is not."""
    cable = nineteen_wire(friction=5.0)
    zb, law, f = full_stick_fields(cable)
    estimate = stick_bending_estimate(cable)
    assert zb.moment_zone_middle / zb.curvature / law.ei_max == pytest.approx(0.547, abs=0.005)
    assert f.axial_share[0] == pytest.approx(0.90, abs=0.03)
    assert f.axial_share[1] == pytest.approx(0.37, abs=0.03)
    assert estimate.axial_share == pytest.approx([1.0, 0.42], abs=0.005)
    assert abs(f.spin[0]) == pytest.approx(estimate.spin[0], rel=0.15)
    assert abs(f.torque[0]) == pytest.approx(estimate.torque[0], rel=0.15)
    assert 0.01 < abs(f.spin[1]) < 0.04 and abs(f.torque[1]) < 0.1 * abs(f.torque[0])


def test_with_the_spin_held_full_stick_nears_plane_sections(monkeypatch):
    """The same 1+6+12 with every wire's GJ × 100, so that no wire can spin on its ties: the
    smeared estimate then gives plane sections (EI_max), and the strand follows, far above the
    0.547 EI_max of free spin (measured 0.891; layer 1 / 2 axial shares 1.00 / 0.83). What the
    estimate leaves out (wires bending between their ties, the tilt of a wire moving its contact
    point) keeps it some 11 % below EI_max."""
    import strand.model.model

    def stiff_torsion(cmesh):
        section = layer_section(cmesh)
        return CircularSection(
            section.d,
            section.E,
            section.nu,
            torsional_stiffness=100 * section.G * section.polar_moment,
        )

    monkeypatch.setattr(strand.model.model, "layer_section", stiff_torsion)
    cable = nineteen_wire(friction=5.0)
    zb, law, f = full_stick_fields(cable)
    estimate = stick_bending_estimate(cable, spin=False)
    assert estimate.ratio == pytest.approx(1.0, abs=1e-9)
    slope = zb.moment_zone_middle / zb.curvature / law.ei_max
    assert slope == pytest.approx(estimate.ratio, rel=0.15)
    assert f.axial_share[0] == pytest.approx(1.0, abs=0.05)
    assert np.all(np.abs(f.spin) < 0.1 * np.abs(stick_bending_estimate(cable).spin[0]))


def test_stick_slip_law_reproduces_the_reference_numbers():
    """Cardinal at 40 kN (docs/theory.md §5.3, §5.4, worked out for Cardinal): EI_min variants, stick stiffness per layer,
    slip onset and slip moments with both friction rules."""
    c = cardinal()
    assert ei_min(c, "EPRI") == pytest.approx(28.81, abs=0.01)
    assert ei_min(c, "PAPAILIOU") == pytest.approx(28.29, abs=0.01)
    assert ei_min(c, "COSTELLO") == pytest.approx(28.12, abs=0.01)
    own = StickSlipLaw(c, 40e3, "own_tension")
    cum = StickSlipLaw(c, 40e3, "cumulative")
    assert np.allclose(own.stick_stiffness, [51.9, 140.6, 474.1, 1105.3], atol=0.1)
    assert own.ei_max == pytest.approx(1800, rel=1e-3)
    assert np.allclose(own.slip_onset, [0.0096, 0.0158, 0.0104, 0.0086], atol=1e-4)
    assert np.allclose(own.full_slip, [0.0155, 0.0269, 0.0177, 0.0148], atol=1e-4)
    assert np.allclose(cum.slip_onset, [0.120, 0.084, 0.036, 0.0086], atol=1e-3)
    assert np.allclose(own.slip_moment, [0.64, 2.8, 6.3, 12.2], rtol=0.02)
    assert np.allclose(cum.slip_moment, [7.9, 15.0, 21.6, 12.2], rtol=0.01)
    # smooth law: stick slope below κ_b, tends to EI_min κ + Σ M_slip, and lies under piecewise
    k = np.array([1e-4, 0.05, 0.5, 50.0])
    assert cum.moment(k[0]) / k[0] == pytest.approx(cum.ei_max, rel=1e-9)
    assert cum.moment(k[-1]) - cum.ei_min * k[-1] == pytest.approx(cum.slip_moment.sum(), 1e-3)
    assert np.all(cum.moment(k) <= cum.piecewise(k) + 1e-9)
    # exponential capstan: slightly more friction than its linearisation
    cap = StickSlipLaw(c, 40e3, "own_tension", capstan=True)
    assert np.all(cap.slip_moment > own.slip_moment)
    assert cap.moment(1e-4) / 1e-4 == pytest.approx(cap.ei_max, rel=1e-9)


def test_tensioned_beam_matches_its_closed_form_and_the_reference_deflections():
    """Linear law: the shooting solution equals P/(2T)[a − (2/k) tanh(ka/2)]; with the stick–slip
    law, the virgin deflections of the seed test (docs/theory.md §5.5) within 0.1 mm."""
    for EI in (28.81, 1800.0):
        beam = TensionedBeam(1.0, 40e3, lambda M, EI=EI: M / EI)
        assert beam.deflection(4300.0) == pytest.approx(
            clamped_deflection(4300.0, 40e3, 1.0, EI), rel=1e-6
        )
    for rule, expected in (
        ("own_tension", [4.52, 10.09, 22.93]),
        ("cumulative", [3.09, 8.48, 21.25]),
    ):
        beam = TensionedBeam(1.0, 40e3, StickSlipLaw(cardinal(), 40e3, rule).curvature)
        got = [1e3 * beam.deflection(P) for P in (1000.0, 2000.0, 4300.0)]
        assert np.allclose(got, expected, atol=0.1), (rule, got)


def test_saddle_beam_reference_starts_from_the_unloaded_beam():
    """The saddle run's analytical companion: a load history that does not start at 0 is taken
    from the unloaded beam (first value on the virgin curve), one deflection per load."""
    loads = [1000.0, 2000.0, 0.0]
    ref = saddle_beam_reference(cardinal(), 1.0, 40e3, loads)
    beam = TensionedBeam(1.0, 40e3, StickSlipLaw(cardinal(), 40e3, "own_tension").curvature)
    assert len(ref["own_tension"]) == 3
    assert ref["own_tension"][:2] == pytest.approx([beam.deflection(P) for P in loads[:2]], 1e-3)
    assert ref["own_tension"][2] > 0  # Masing: a residual deflection when unloaded


def test_masing_cycles_close_and_remember():
    """Unloading follows y_r − 2 v((x_r − x)/2); a symmetric cycle closes on itself, its area is
    that of the two branches, and an inner loop is forgotten once the outer path resumes."""
    v = np.tanh
    up = np.linspace(0, 2, 201)
    path = np.r_[up, up[::-1][1:] * 1, -up[1:], -up[::-1][1:]]
    y = masing(v, path)
    assert y[200] == pytest.approx(np.tanh(2))
    assert y[400] == pytest.approx(np.tanh(2) - 2 * np.tanh(1), abs=1e-12)  # x back at 0
    assert y[600] == pytest.approx(-np.tanh(2))
    loop = np.r_[path[200:], path[1:201]]  # +2 → −2 → +2
    expected = 8 * (np.log(np.cosh(2)) - np.tanh(2))  # ∫ (y_up − y_down) dx, closed form
    assert loop_area(loop, masing(v, np.r_[path, path[1:201]])[200:]) == pytest.approx(
        expected, rel=1e-3
    )
    inner = np.r_[np.linspace(0, 1, 101), np.linspace(1, 0.5, 51)[1:], np.linspace(0.5, 2, 151)[1:]]
    assert masing(v, inner)[-1] == pytest.approx(np.tanh(2), abs=1e-12)


def test_bending_case_settings_are_checked():
    case = case_from_dict({"load": {"kind": "bending", "zone": 0.3}, "mesh": {"length": 0.6}})
    assert case.load.kind == "bending" and case.load.curvature == 0.5
    with pytest.raises(CaseError, match="kind = 'twist' is unknown"):
        case_from_dict({"load": {"kind": "twist"}})
    with pytest.raises(CaseError, match=r"zone = 0.8 m must be shorter"):
        case_from_dict({"load": {"kind": "bending", "zone": 0.8}, "mesh": {"length": 0.5}})
    with pytest.raises(CaseError, match="curvature = 0.1 1/m exceeds curvature_max = 0.05 1/m"):
        case_from_dict({"steps": {"curvature": 0.1}})
