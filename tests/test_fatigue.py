"""Fatigue outputs against closed forms: friction history of a crossing (stick: no slip; slip:
(s − μP/k)-driven, Coulomb's dissipation), Hertz contact sizes, surface stresses of a bent wire,
S–N and Miner, Poffenberger–Swart on the tensioned beam; and the run's histories and report."""

from __future__ import annotations

import csv

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI

from beam_cases import cantilever
from forms import CircularSection, ReissnerBeam
from strand.analytical import ei_min, poffenberger_swart
from strand.app.cli import main
from strand.app.fatigue.wire_stresses import repeating_damage
from strand.app.history import read_history
from strand.cable.description import cardinal
from strand.cable.mesh import beam_space, polyline_mesh
from strand.contact import ElasticSlip, PenaltyLaw, candidate_pairs, contact_terms, locate_nodes
from strand.contact.hertz import compliance, contact_ellipse, crossed_cylinders
from strand.fatigue import (
    SN_CURVES,
    crossing_cycles,
    miner_damage,
    rainflow_cycles,
    section_components,
    section_frames,
    shear_stress,
    surface_stress,
)
from strand.fatigue.cycles import cycle_steps, repeating_cycles, repeating_ranges
from strand.solver import LoadStepper, NodalLoad, NonlinearProblem
from strand_cases import SEVEN_WIRE

# -- a crossing sheared to and fro (demos/demo_crossed_beams.py) ---------------------------------
R, L, N_CELLS = 1.5e-3, 0.04, 40
E, NU = 200e9, 0.3
MU, P, K_N, G_LIM = 0.3, 50.0, 1e8, 5e-6


def sheared_crossing(path):
    """Press beam b onto beam a with P, then move a along x through ``path`` (m); the pair's
    history (force, traction, slip, sliding, work) and the shear after every converged step,
    the pressed state first; and the series stiffness k of contact and beam b (closed form)."""
    s = np.linspace(-L / 2, L / 2, N_CELLS + 1)
    x_a, x_b = s[:, None] * [1.0, 0, 0], s[:, None] * [0, 1.0, 0] + [0, 0, 2 * R]
    cells = (
        np.vstack([np.c_[0:N_CELLS, 1 : N_CELLS + 1]] * 2)
        + np.repeat([0, N_CELLS + 1], N_CELLS)[:, None]
    )
    V = beam_space(polyline_mesh(MPI.COMM_WORLD, np.vstack([x_a, x_b]), cells))
    a, b = locate_nodes(V, x_a), locate_nodes(V, x_b)
    w = fem.Function(V)
    section = CircularSection(2 * R, E, NU)
    contact = contact_terms(
        candidate_pairs(V, a, b, R, R, reach=1e-4), PenaltyLaw(K_N), ElasticSlip(MU, G_LIM)
    )
    shear = fem.Constant(V.mesh, 0.0)
    bcs = [fem.dirichletbc(shear, 6 * a, V.sub(0))]
    bcs += [fem.dirichletbc(0.0, 6 * a + c, V.sub(c)) for c in range(1, 6)]
    bcs += [fem.dirichletbc(0.0, 6 * b[[0, -1]] + c, V.sub(c)) for c in (0, 1, 3, 4, 5)]
    press = NodalLoad(b[[0, -1]], [[0.0, 0.0, -P / 2, 0.0, 0.0, 0.0]] * 2)
    solver = NonlinearProblem(ReissnerBeam(w, section).residual(), w, bcs, terms=[contact, press])
    LoadStepper(solver, 0.25, 1e-3).ramp(lambda f: setattr(press, "factor", f), 0.0, 1.0)
    rows = []

    def record(_=None):
        h, st = contact.history, contact.state
        rows.append(
            (
                float(shear.value),
                st.force.copy(),
                st.traction.copy(),
                h.slip.copy(),
                h.sliding.copy(),
                h.work.copy(),
            )
        )

    record()
    stepper = LoadStepper(solver, 2e-6, 1e-8, max_step=2e-6, on_step=record)
    for start, end in zip(path[:-1], path[1:], strict=True):
        stepper.ramp(lambda v: setattr(shear, "value", v), start, end)
    solver.destroy()
    beam_b = L**3 / (192 * section.EI) + L / (4 * section.GA) + R**2 * L / (4 * section.GJ)
    k = 1 / (G_LIM / (MU * P) + beam_b)
    shears, *arrays = (np.array(v) for v in zip(*rows, strict=True))
    return shears, arrays, k, beam_b


def test_a_sliding_crossing_slips_by_s_less_mu_p_over_k_and_dissipates_coulombs_work():
    """Shear 0 → +S → −S → +S: on the reversal +S → −S the pair slides by 2(S − μP/k) (the
    parallelogram's width), its surface points move by 2(S − μP·C_b) (beam b's compliance C_b
    takes the rest), the friction force swings by 2μP, and friction dissipates μP per metre
    slid: over the whole path μP × 5(S − μP/k). Counted as a repeating history, the reversal is
    one full cycle with the same amplitudes, and dissipates Coulomb's loop 4μP(S − μP/k)."""
    S = 30e-6
    shears, (force, traction, slip, sliding, work), k, beam_b = sheared_crossing([0.0, S, -S, S])
    cycles = rainflow_cycles(shears)
    cc = crossing_cycles(cycles, force, traction, slip, sliding, work)
    reversal = np.flatnonzero(np.isclose(cycles.range, 2 * S))[0]
    assert cycles.count[reversal] == 0.5
    assert cc.slip_amplitude[reversal, 0] == pytest.approx(S - MU * P / k, rel=3e-3)
    assert cc.displacement_amplitude[reversal, 0] == pytest.approx(S - MU * P * beam_b, rel=3e-3)
    assert cc.friction_amplitude[reversal, 0] == pytest.approx(MU * P, rel=1e-9)
    assert cc.energy[reversal, 0] == pytest.approx(2 * MU * P * (S - MU * P / k), rel=3e-3)
    assert work[-1, 0] == pytest.approx(5 * MU * P * (S - MU * P / k), rel=3e-3)
    assert np.all(np.diff(work[:, 0]) >= -1e-18)  # dissipation never negative
    steady = repeating_cycles(shears)
    full = np.flatnonzero(np.isclose(steady.range, 2 * S))
    assert len(full) == 1 and steady.count[full[0]] == 1.0
    cs = crossing_cycles(steady, force, traction, slip, sliding, work)
    for name in ("slip_amplitude", "displacement_amplitude", "friction_amplitude"):
        assert getattr(cs, name)[full[0], 0] == getattr(cc, name)[reversal, 0], name
    assert cs.energy[full[0], 0] == pytest.approx(4 * MU * P * (S - MU * P / k), rel=3e-3)


def test_a_sticking_crossing_does_not_slide_and_dissipates_nothing():
    """Shear ±S below the slip threshold (S = μP/2k): the friction force follows kS, the pair
    never slides, and its surface points move only by the contact's elastic compliance Q/K_T."""
    _, _, k, _ = sheared_crossing([0.0, 1e-6])
    S = 0.5 * MU * P / k
    shears, (force, traction, slip, sliding, work), k, _ = sheared_crossing([0.0, S, -S, 0.0])
    cc = crossing_cycles(rainflow_cycles(shears), force, traction, slip, sliding, work)
    assert np.max(cc.slip_amplitude) < 1e-15 and np.max(np.abs(work)) < 1e-18
    K_T = MU * P / G_LIM
    big = np.argmax(rainflow_cycles(shears).range)
    assert cc.friction_amplitude[big, 0] == pytest.approx(k * S, rel=3e-3)
    assert cc.displacement_amplitude[big, 0] == pytest.approx(k * S / K_T, rel=3e-3)


# -- Hertz contact sizes -----------------------------------------------------------------------
E_AL, NU_AL, R_AL = 69e9, 0.33, 1.66e-3


def test_contact_ellipse_of_a_sphere_on_a_flat_is_hertzs_circle():
    """Crossed equal cylinders at 90°: a = b = (3PR/4E*)^{1/3}, p₀ = 3P/(2πa²), exactly."""
    e_star = 1 / (2 * compliance(E_AL, NU_AL))
    a, b, p0 = contact_ellipse(R_AL, R_AL, np.pi / 2, E_AL, NU_AL, E_AL, NU_AL, force=40.0)
    radius = (3 * 40.0 * R_AL / (4 * e_star)) ** (1 / 3)
    assert a == pytest.approx(radius, rel=1e-12) and b == pytest.approx(radius, rel=1e-12)
    assert p0 == pytest.approx(3 * 40.0 / (2 * np.pi * radius**2), rel=1e-12)


@pytest.mark.parametrize("deg", [18.0, 25.0, 60.0])
def test_contact_ellipse_against_hertzs_elliptic_integrals(deg):
    """At the crossing angles of stranded wires the semi-axes and peak pressure are within 3 % of
    Hertz's elliptical solution (Johnson 1985 §4.2, solved with scipy's elliptic integrals)."""
    special = pytest.importorskip("scipy.special")
    optimize = pytest.importorskip("scipy.optimize")
    K, Ee = special.ellipk, special.ellipe  # of m = e²
    rx, ry = crossed_cylinders(R_AL, R_AL, np.radians(deg))
    A, B = 1 / (2 * rx), 1 / (2 * ry)
    m = optimize.brentq(
        lambda m: (Ee(m) / (1 - m) - K(m)) / (K(m) - Ee(m)) - B / A, 1e-9, 1 - 1e-12
    )
    e_star = 1 / (2 * compliance(E_AL, NU_AL))
    force = 40.0
    # P = 2πab p₀/3 with p₀ = A E* e² a² / (b (K − E)) and b = a √(1 − e²)
    a = (3 * force * (K(m) - Ee(m)) / (2 * np.pi * A * e_star * m)) ** (1 / 3)
    b = a * np.sqrt(1 - m)
    p0 = 3 * force / (2 * np.pi * a * b)
    got = contact_ellipse(R_AL, R_AL, np.radians(deg), E_AL, NU_AL, E_AL, NU_AL, force=force)
    np.testing.assert_allclose(got, (a, b, p0), rtol=0.03)


# -- surface stresses --------------------------------------------------------------------------
@pytest.mark.parametrize("loads", [(2e3, 0.0, 0.0), (0.0, 0.5, 0.5)])
def test_a_straight_wire_in_tension_or_in_bending_and_torsion_has_navier_and_saint_venant_stresses(
    loads,
):
    """A cantilever along x with a tip force F e_x, or a moment M e_y and a torque T e_x (apart:
    together, tension times deflection adds a moment along the span): σ(ψ) = F/A + (Mr/I) cos ψ
    from e₁ = e_z, so ±Mr/I at the top and bottom fibres and τ = Tr/J, from the beam's own section
    forces through the fatigue module."""
    F, M, T = loads
    c = cantilever(8, length=0.5)
    c.force.value[:] = [F, 0.0, 0.0]
    c.moment.value[:] = [T, M, 0.0]
    c.solver.solve()
    D = fem.functionspace(c.mesh, ("DG", 0, (7,)))
    f = fem.Function(D)
    n, m = c.beam.spatial_force(), c.beam.spatial_moment()
    f.interpolate(
        fem.Expression(ufl.as_vector([c.beam.N[0], *n, *m]), D.element.interpolation_points)
    )
    values = f.x.array.reshape(-1, 7)
    x, cells = c.mesh.geometry.x, c.mesh.geometry.dofmaps[0]
    tangent = np.diff(x[cells], axis=1)[:, 0]  # initial: the rotations stay below 5e-3
    assert np.max(np.abs(c.w.x.array.reshape(-1, 6)[:, 3:])) < 5e-3
    e1, e2 = section_frames(tangent, np.tile([0.0, 0.0, 1.0], (len(cells), 1)))
    m1, m2, torque = section_components(values[:, 4:7], tangent, e1, e2).T
    d = 0.01  # beam_cases.D
    A, I = np.pi * d**2 / 4, np.pi * d**4 / 64
    psi = np.array([0.0, np.pi / 2, np.pi, 3 * np.pi / 2])
    sigma = surface_stress(values[:, :1], m1[:, None], m2[:, None], d, psi)
    expected = F / A + M * (d / 2) / I * np.cos(psi)
    scale = F / A + M * (d / 2) / I
    np.testing.assert_allclose(sigma, np.tile(expected, (len(cells), 1)), atol=1e-3 * scale)
    np.testing.assert_allclose(shear_stress(torque, d), T * (d / 2) / (2 * I), atol=1e-3 * scale)


# -- S–N and Miner ----------------------------------------------------------------------------
def test_cigre_safe_border_line_and_miner_on_constant_amplitude():
    """σ_a = 450 N^{-0.2} MPa below 2e7 cycles, 263 N^{-0.17} beyond; n cycles of one amplitude
    give D = n/N; a history counted by rainflow gives the half cycles ASTM's rule counts."""
    sbl = SN_CURVES["cigre-sbl-multilayer"]
    assert sbl.life(450e6 * 1e6**-0.2) == pytest.approx(1e6, rel=1e-9)
    assert sbl.life(263e6 * 1e8**-0.17) == pytest.approx(1e8, rel=1e-9)
    amplitude = 30e6
    n_fail = (30.0 / 450.0) ** (1 / -0.2)
    assert miner_damage([2 * amplitude] * 5, [1.0] * 5, sbl) == pytest.approx(5 / n_fail)
    c = rainflow_cycles([0.0, 4.0, 0.0, -4.0, 0.0])
    assert sorted(zip(c.range, c.count, strict=True)) == [(4.0, 0.5), (4.0, 0.5), (8.0, 0.5)]


# -- cycles of a repeating history --------------------------------------------------------------
def _counted(c) -> list[tuple[float, float, float]]:
    """(range, mean, count) of every cycle, sorted, to 12 digits."""
    rows = zip(np.round(c.range, 12), np.round(c.mean, 12) + 0.0, c.count, strict=True)
    return sorted((float(r), float(m), float(n)) for r, m, n in rows)


@pytest.mark.parametrize("periods", [1, 4])
def test_a_repeating_sine_counts_its_periods_as_full_cycles(periods):
    """A sin 2πt over N whole periods from t = 0, its peaks sampled: repeating, N cycles of 2A
    about 0. Once through, ASTM counts 0 → A as ½ cycle of A, then each of the 2N − 1 ranges
    between the peaks as ½ cycle of 2A (each contains the start of what is left), then −A → 0 as
    ½ cycle of A: N − ½ cycles of 2A and two halves of A about ±A/2."""
    A = 3.0
    s = A * np.sin(2 * np.pi * np.arange(20 * periods + 1) / 20)
    assert _counted(repeating_cycles(s)) == [(2 * A, 0.0, 1.0)] * periods
    once = _counted(rainflow_cycles(s))
    assert once == sorted(
        [(A, -A / 2, 0.5), (A, A / 2, 0.5)] + [(2 * A, 0.0, 0.5)] * (2 * periods - 1)
    )


def test_repeating_cycles_of_the_saddle_cycle_and_of_two_blocks_by_hand():
    """[0, 1, 0, −1, 0] (the cycle [1, 0, −1, 0] from the tensioned state): one cycle of 2 about
    0, between its turning points 1 and 3. Two blocks, (2, −2) × 10 then (5, −5) × 3 (two sine
    blocks from 0 to 0), repeated: rotated to start at 5, the three-point rule closes (5, −5)
    twice, then each (2, −2) of the small block as the next 2 comes (9 of them) and the last
    when the final 5 comes, and (5, −5) round the small block: 3 cycles of 10 and 10 of 4, all
    about 0 (once through: 13.5 cycles, the block changes −2 → 5 and the ends as halves)."""
    c = repeating_cycles([0.0, 1.0, 0.0, -1.0, 0.0])
    assert _counted(c) == [(2.0, 0.0, 1.0)] and (c.start[0], c.end[0]) == (1, 3)
    t = np.arange(20) / 20
    blocks = np.concatenate(
        [np.tile(2 * np.sin(2 * np.pi * t), 10), np.tile(5 * np.sin(2 * np.pi * t), 3), [0.0]]
    )
    assert _counted(repeating_cycles(blocks)) == [(4.0, 0.0, 1.0)] * 10 + [(10.0, 0.0, 1.0)] * 3
    assert rainflow_cycles(blocks).count.sum() == 13.5


def test_repeating_cycles_are_what_each_further_repetition_adds_once_through():
    """On random histories, Σ count × range^k of the repeating count equals what the third
    repetition adds to a once-through count of the history repeated twice (k = 1, 5, 9); a
    constant history has no cycle."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        s = np.round(rng.normal(size=rng.integers(2, 25)), 2)
        c = repeating_cycles(s)
        twice, thrice = rainflow_cycles(np.tile(s, 2)), rainflow_cycles(np.tile(s, 3))
        assert np.all(c.count == 1.0)
        for k in (1, 5, 9):
            added = np.sum(thrice.count * thrice.range**k) - np.sum(twice.count * twice.range**k)
            assert np.sum(c.range**k) == pytest.approx(added, rel=1e-9, abs=1e-12)
    assert len(repeating_cycles([2.0, 2.0, 2.0])) == 0


def test_a_cycle_over_the_end_of_a_repeating_history_takes_its_window_across_it():
    """[0, 1, −1, 0.5] repeated: (1, −1) from index 1 to 2, and (0.5, 0) from index 3 over the
    end to index 0; that cycle's window is steps 3, 0, its work the work of step 3 to the end
    plus that of the start to step 0 (none: the closure dissipates nothing), its peak force the
    larger of the two steps'."""
    c = repeating_cycles([0.0, 1.0, -1.0, 0.5])
    assert _counted(c) == [(0.5, 0.25, 1.0), (2.0, 0.0, 1.0)]
    wrap = int(np.flatnonzero(c.range == 0.5)[0])
    assert (c.start[wrap], c.end[wrap]) == (3, 0) and list(cycle_steps(3, 0, 4)) == [3, 0]
    assert list(cycle_steps(1, 2, 4)) == [1, 2]
    force = np.array([[5.0], [6.0], [7.0], [8.0]])
    work = np.array([[0.0], [1.0], [3.0], [6.0]])
    slip = np.zeros((4, 1, 3))
    slip[:, 0, 0] = [0.0, 2.0, -2.0, 1.0]
    cc = crossing_cycles(c, force, slip, slip, slip, work)
    assert cc.peak_force[wrap, 0] == 8.0 and cc.mean_force[wrap, 0] == 6.5
    assert cc.energy[wrap, 0] == 0.0 and cc.slip_amplitude[wrap, 0] == 0.5
    other = 1 - wrap
    assert cc.energy[other, 0] == 2 * (3.0 - 1.0) and cc.peak_force[other, 0] == 7.0


# -- Poffenberger–Swart -------------------------------------------------------------------------
def test_poffenberger_swart_is_the_clamped_tensioned_beam():
    """The clamped–clamped span L under tension T and a midspan load ±P (EI = EI_min): the
    displacement at x, w = P/(2T)[x − sinh kx/k + tanh(ka/2)(cosh kx − 1)/k], and the clamp's
    curvature w″(0) = Pk tanh(ka/2)/(2T) give the outer wire's amplitude E d/2 · w″(0): K·Y_b with
    Y_b = 2w(x) is the same to e^{−ka} (1e-8 for Cardinal at 40 kN over 1 m)."""
    cable, T, span, P, x = cardinal(), 40e3, 1.0, 4.3e3, 0.089
    k, a = np.sqrt(T / ei_min(cable)), span / 2
    w = P / (2 * T) * (x - np.sinh(k * x) / k + np.tanh(k * a / 2) * (np.cosh(k * x) - 1) / k)
    outer = cable.layers[-1].wire
    sigma_a = outer.E * outer.diameter / 2 * P * k * np.tanh(k * a / 2) / (2 * T)
    assert poffenberger_swart(cable, T, x) * 2 * w == pytest.approx(sigma_a, rel=1e-7)


# -- the run's histories and report ------------------------------------------------------------
def test_run_writes_pair_and_wire_histories_and_the_fatigue_report(tmp_path):
    """A 1+6 strand, tension then a lateral cycle: the histories start at the tensioned state
    (slips and work zero), friction work never decreases, pairs that never slipped did not slide,
    the wire sections carry the axial forces of ``axial_forces.csv``; the ParaView series reads
    back with meshio; the report's tables have a row per pair, element and wire."""
    meshio = pytest.importorskip("meshio")
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE.replace("cycle = [1.0, 0.0]", "cycle = [1.0, -1.0, 0.0]"))
    out = tmp_path / "out"
    assert main(["run", str(case), "--out", str(out)]) == 0
    pairs, sections = read_history(out / "contact_pairs.h5"), read_history(out / "wire_sections.h5")
    assert pairs.values["load"][0] == 0.0 and np.ptp(pairs.values["load"]) == pytest.approx(600)
    for name in ("slip", "sliding", "work"):
        assert np.all(pairs[name][0] == 0.0)
    assert np.all(np.diff(pairs["work"], axis=0) >= -1e-9)
    never = np.all(pairs["state"] != 2, axis=0)
    assert never.any() and np.max(np.abs(pairs["sliding"][:, never])) < 1e-12
    assert np.any(pairs["state"] == 2)  # and some did slip
    forces = np.loadtxt(out / "axial_forces.csv", delimiter=",", skiprows=1)
    last = forces[forces[:, 0] == sections.numbers[-1]]
    np.testing.assert_allclose(sections["axial"][-1], last[:, 7], rtol=1e-5, atol=1e-3)
    with meshio.xdmf.TimeSeriesReader(out / "contact_points.xdmf") as reader:
        points, _ = reader.read_points_cells()
        assert len(points) == len(pairs.static["z"]) and reader.num_steps == len(pairs)
        _, data, _ = reader.read_data(reader.num_steps - 1)
        np.testing.assert_allclose(data["force"], pairs["force"][-1])
        np.testing.assert_array_equal(data["z"], pairs.static["z"])  # float64 static arrays
    with open(out / "crossings.csv") as f:
        assert len(list(csv.DictReader(f))) == len(pairs.static["z"])
    with open(out / "wires.csv") as f:
        assert len(list(csv.DictReader(f))) == 7
    text = (out / "fatigue.txt").read_text()
    assert "worst line contacts" in text and "Poffenberger–Swart" in text  # 1+6: no crossings


def test_the_repeating_count_of_many_histories_at_once_is_each_ones_count():
    """``repeating_ranges`` counts every column of an array as ``repeating_cycles`` counts it
    alone: the same ranges, on random histories with ties, plateaus, constant and short ones;
    and the damage of the wires' report is the Miner sum of those ranges."""
    rng = np.random.default_rng(7)
    for trial in range(600):
        n, m = int(rng.integers(1, 30)), int(rng.integers(1, 5))
        series = [
            rng.normal(size=(n, m)),
            rng.integers(-2, 3, size=(n, m)).astype(float),  # ties and plateaus
            np.cumsum(rng.normal(size=(n, m)), axis=0),
            np.sin(np.linspace(0, 5 * np.pi, n))[:, None] * rng.integers(0, 3, size=m),
        ][trial % 4]
        got = repeating_ranges(series)
        for j in range(m):
            alone = repeating_cycles(series[:, j]).range
            np.testing.assert_allclose(np.sort(got[j][got[j] > 0]), np.sort(alone[alone > 0]))
    sigma = 1e8 * np.cumsum(rng.normal(size=(40, 50)), axis=0)
    curve = SN_CURVES["en1992-prestressing-steel"]
    each = [miner_damage(repeating_cycles(s).range, 1.0, curve) for s in sigma.T]
    np.testing.assert_allclose(repeating_damage(sigma, curve), each, rtol=1e-14)
    assert np.isnan(repeating_damage(sigma, None)).all()
