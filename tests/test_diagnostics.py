"""The wires' spin and torque (``strand.model.cell_results.section_spin``, ``section_torque``,
``cell_results``) against closed forms, the per-layer fits against φ (``layer_fields``), and the
uniform bending summary's table of them beside the rolling estimate."""

from __future__ import annotations

import numpy as np
import pytest
from dolfinx import fem

from beam_cases import cantilever, section_stiffness
from strand.app.case import load_case
from strand.app.history import read_history
from strand.app.run import run_case
from strand.model.cell_results import cell_results, section_spin, section_torque
from strand.model.layer_fields import harmonic_fit, layer_fields
from strand.model.model import StrandModel
from strand_cases import SEVEN_WIRE, seven_wire


def test_a_cantilever_under_end_torque_spins_linearly_and_carries_the_torque():
    """An oblique straight cantilever, clamped at the root, torque T about its axis at the tip:
    every section spins by θ·t = T s/GJ (s from the root; the cell's value is its nodes' mean,
    so at its midpoint) and carries m·t = T."""
    L, T, direction = 0.7, 15.0, np.array([1.0, 2.0, -0.5])
    d = direction / np.linalg.norm(direction)
    case = cantilever(10, L, direction)
    case.moment.value = T * d
    assert case.solver.solve().converged
    V = case.V
    cells = V.dofmap.list
    w = case.w.x.array.reshape(-1, 6)
    x = V.tabulate_dof_coordinates() + w[:, :3]
    tangent = x[cells[:, 1]] - x[cells[:, 0]]
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    D = fem.functionspace(case.mesh, ("DG", 0, (3,)))
    moment = fem.Function(D)
    moment.interpolate(fem.Expression(case.beam.spatial_moment(), D.element.interpolation_points))
    m = moment.x.array.reshape(-1, 3)[D.dofmap.list[:, 0]]
    GJ = section_stiffness()["GJ"]
    s = V.tabulate_dof_coordinates()[cells].mean(axis=1) @ d
    spin = section_spin(w[:, 3:], cells, tangent)
    np.testing.assert_allclose(spin, T * s / GJ, rtol=1e-8)
    assert spin.max() == pytest.approx(T * (L - L / 20) / GJ, rel=1e-8)  # the tip cell
    np.testing.assert_allclose(section_torque(m, tangent), T, rtol=1e-8)


def test_a_strand_turned_rigidly_about_its_axis_spins_by_the_turn_along_each_tangent():
    """A 1+6 turned rigidly by ω about e_z: its sections spin by ω t_z (t_z = 1 on the core,
    cos α of the helices' chords) and carry no torque (``cell_results``)."""
    geometry = seven_wire(lay_angle=12.0, length=0.05)
    model = StrandModel(geometry)
    omega = 0.3
    c, s = np.cos(omega), np.sin(omega)
    Q = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    X = geometry.points
    w = np.zeros((len(X), 6))
    w[:, :3] = X @ Q.T - X
    w[:, 5] = omega
    blocks = model.i2b >= 0
    model.nodal[model.i2b[blocks]] = w[blocks]
    cells = cell_results(model)
    chord = X[geometry.cells[:, 1]] - X[geometry.cells[:, 0]]
    t_z = chord[:, 2] / np.linalg.norm(chord, axis=1)
    np.testing.assert_allclose(cells.spin, omega * t_z, rtol=1e-12)
    assert cells.spin[cells.layer == 0] == pytest.approx(omega, rel=1e-12)
    assert np.median(t_z[cells.layer == 1]) == pytest.approx(np.cos(np.radians(12.0)), 1e-3)
    assert np.abs(cells.torque).max() < 1e-9


def test_layer_fields_recover_the_harmonics_they_fit():
    """Fields a sin φ (axial force), b cos φ (spin), c sin φ (torque) plus offsets and the other
    harmonic, on unevenly sampled angles: the fits return a, b, c per layer, the axial one over
    K r κ, the others over κ."""
    rng = np.random.default_rng(3)
    layer = np.repeat([0, 1, 2], 40)
    phi = rng.uniform(-180.0, 120.0, layer.size)
    p = np.radians(phi)
    a, b, c = np.array([0.0, 8.0, 3.0]), np.array([0.0, -2e-4, 5e-5]), np.array([0.0, 6e-3, -1e-3])
    axial = a[layer] * np.sin(p) + 0.7 * np.cos(p) + 0.1
    spin = b[layer] * np.cos(p) + 1e-5 * np.sin(p) - 3e-6
    torque = c[layer] * np.sin(p) + 2e-4 * np.cos(p)
    kappa, plane = 0.002, np.array([4e3, 5e3])
    f = layer_fields(layer, phi, axial, spin, torque, kappa, plane)
    np.testing.assert_allclose(f.axial_share, a[1:] / (plane * kappa), rtol=1e-10)
    np.testing.assert_allclose(f.spin, b[1:] / kappa, rtol=1e-10)
    np.testing.assert_allclose(f.torque, c[1:] / kappa, rtol=1e-10)
    assert list(f.cells) == [40, 40]
    assert np.all(np.isnan(harmonic_fit(phi[:2], axial[:2])))


def test_the_bending_summary_tables_the_wire_fields_per_layer(tmp_path):
    """A quick 1+6 bending run (``run_case``): the summary prints the per-layer table beside the
    rolling estimate (1+6: share 1.00, no spin), the report holds it, and ``wire_sections.h5``
    carries the spin and torque of the cell results."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    case = load_case(
        path,
        [
            "output.plots=false",
            "output.fields=false",
            'load.kind="bending"',
            "load.zone=0.04",
            "load.curvature=0.5",
            "steps.curvature=0.1",
            "steps.curvature_max=0.2",
        ],
    )
    out = tmp_path / "out"
    result = run_case(case, out, stream=open(tmp_path / "log.txt", "w"))  # noqa: SIM115
    assert not result.failure
    rolling = result.reference.rolling
    assert rolling.first.curvature == pytest.approx(result.bending[0].measures.curvature)
    assert rolling.largest.curvature > rolling.first.curvature
    assert rolling.first.cells[0] > 0 and np.isfinite(rolling.first.axial_share[0])
    assert rolling.estimate.axial_share[0] == pytest.approx(1.0)
    text = (out / "summary.txt").read_text()
    lines = text.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("wire fields per layer"))
    assert "spin (rad m)" in lines[head + 3] and "torque (N m²)" in lines[head + 3]
    row = lines[head + 5].split()
    assert len(row) == 10 and row[0] == "1" and row[3] == "1.00"
    assert float(row[1]) == pytest.approx(rolling.first.axial_share[0], abs=0.006)
    sections = read_history(out / "wire_sections.h5")
    peak = list(sections.numbers).index(result.peak_step.number)
    np.testing.assert_allclose(sections["spin"][peak], result.peak.spin, rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose(sections["torque"][peak], result.peak.torque, rtol=1e-5, atol=1e-6)
    assert np.abs(result.peak.spin).max() > 1e-4
