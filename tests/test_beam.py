"""Reissner beam forms against exact and published solutions."""

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI
from scipy.spatial.transform import Rotation

from beam_cases import NU, D, E, cantilever, section_stiffness
from forms import CircularSection, ReissnerBeam
from strand.beam.fields import section_force_values
from strand.cable.description import cardinal
from strand.cable.geometry import build_geometry
from strand.cable.mesh import (
    beam_space,
    cable_mesh,
    node_to_block,
    polyline_mesh,
    straight_beam_mesh,
)
from strand.model.model import layer_section
from strand.solver import LoadStepper

S = section_stiffness()


def ramp(case, set_load, end=1.0, first=0.1, max_step=0.1):
    stepper = LoadStepper(case.solver, first_step=first, min_step=1e-3, max_step=max_step)
    stepper.ramp(set_load, 0.0, end)
    return stepper


@pytest.mark.parametrize("n_cells", [40])
def test_end_moment_rolls_cantilever_into_circle(n_cells):
    """M = 2πEI/L bends the beam into a full circle: the tip returns to the root."""
    L = 1.0
    case = cantilever(n_cells, L)
    M_full = 2 * np.pi * S["EI"] / L

    def set_moment(lam):
        case.moment.value = [0.0, 0.0, lam * M_full]

    ramp(case, set_moment, 0.5)
    # half the moment: half circle of radius R = L/π, tip at (0, 2R) (polygon chord error O(h²))
    half_err = np.linalg.norm(case.tip_u - [-L, 2 * L / np.pi, 0.0]) / L
    assert half_err < 1e-3, half_err
    assert case.tip_theta[2] == pytest.approx(np.pi, rel=1e-9)
    ramp(case, lambda lam: set_moment(0.5 + lam), 0.5)
    full_err = np.linalg.norm(case.tip_u + [L, 0.0, 0.0]) / L
    assert full_err < 1e-3, full_err
    assert case.tip_theta[2] == pytest.approx(2 * np.pi, rel=1e-9)


def test_half_circle_converges_at_second_order():
    """The half-circle tip error (chord vs arc) falls by 4 when the mesh is halved."""
    L = 1.0
    errs = []
    for n in (8, 16):
        case = cantilever(n, L)
        M = np.pi * S["EI"] / L
        ramp(case, lambda lam, c=case, m=M: setattr(c.moment, "value", [0, 0, lam * m]), 1.0)
        errs.append(np.linalg.norm(case.tip_u - [-L, 2 * L / np.pi, 0.0]) / L)
    rate = np.log2(errs[0] / errs[1])
    assert rate == pytest.approx(2.0, abs=0.1), errs


def test_large_tip_force_matches_elastica():
    """Cantilever, transverse dead load PL²/EI = 10 (Mattiasson 1981, Int. J. Numer. Meth. Eng.
    17:145-153, Table 1): v/L = 0.81061, (L - x)/L = 0.55500, tip rotation 1.43029 rad."""
    L = 1.0
    case = cantilever(64, L)
    P = 10 * S["EI"] / L**2
    ramp(case, lambda lam: setattr(case.force, "value", [0.0, lam * P, 0.0]), 1.0)
    # the Reissner beam is extensible and shear-deformable: O(P/EA) ~ 1e-4 from the elastica
    assert case.tip_u[1] / L == pytest.approx(0.81061, abs=1e-3)
    assert -case.tip_u[0] / L == pytest.approx(0.55500, abs=1e-3)
    assert case.tip_theta[2] == pytest.approx(1.43029, abs=1e-3)


@pytest.mark.parametrize("direction", [(0, 0, 1), (1, 2, -0.5)])
def test_bar_tension_and_torsion_exact(direction):
    """Axial force F: u_tip = FL/EA; torque T: twist TL/GJ; N = F, Mt = T in every cell."""
    L = 0.7
    case = cantilever(10, L, direction)
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    F, T = 2.0e3, 15.0
    case.force.value = F * d
    case.moment.value = T * d
    result = case.solver.solve()
    assert result.converged
    assert case.tip_u @ d == pytest.approx(F * L / S["EA"], rel=1e-8)
    assert case.tip_theta @ d == pytest.approx(T * L / S["GJ"], rel=1e-8)
    sf = section_force_values(case.beam)
    np.testing.assert_allclose(sf[:, 0], F, rtol=1e-8)
    np.testing.assert_allclose(sf[:, 3], T, rtol=1e-8)
    np.testing.assert_allclose(sf[:, [1, 2, 4, 5]], 0.0, atol=1e-8 * F)


def test_torsional_stiffness_set_apart_from_E_and_nu():
    """A section given its own GJ twists by TL/GJ under a torque and bends as before (EI, κGA
    from E and ν): a tip force P gives PL³/3EI (1 − 1/4n²) + PL/κGA, the exact tip deflection of n
    two-node one-point Timoshenko cells (each load alone: small rotations)."""
    L, T, P = 0.7, 1.0, 2.0
    GJ = 0.37 * S["GJ"]
    section = CircularSection(D, E, NU, torsional_stiffness=GJ)
    assert section.GJ == GJ and section.EI == pytest.approx(S["EI"], rel=1e-15)
    n = 10
    case = cantilever(n, L, section=section)
    case.moment.value = [T, 0.0, 0.0]
    assert case.solver.solve().converged
    assert case.tip_theta[0] == pytest.approx(T * L / GJ, rel=1e-8)
    case.moment.value = [0.0, 0.0, 0.0]
    case.force.value = [0.0, 0.0, P]
    assert case.solver.solve().converged
    kappa_GA = section.shear_coefficient * E / (2 * (1 + NU)) * np.pi * D**2 / 4
    bending = P * L**3 / (3 * S["EI"]) * (1 - 1 / (4 * n**2))
    assert case.tip_u[2] == pytest.approx(bending + P * L / kappa_GA, rel=1e-4)


def test_one_compiled_kernel_serves_every_section():
    """Section numbers are data of the beam forms, not literals: beams of other diameters and
    moduli, and Cardinal's cell-wise steel and aluminium layers, have the same residual and
    tangent forms (the UFL signature keys FFCx's cache), so the JIT compiles them once."""
    mesh = straight_beam_mesh(MPI.COMM_WORLD, 1.0, 4)
    w = fem.Function(beam_space(mesh))
    cmesh = cable_mesh(build_geometry(cardinal(), 0.02, 4e-3))
    w_strand = fem.Function(beam_space(cmesh.mesh))
    beams = [
        ReissnerBeam(w, CircularSection(D, E, NU)),
        ReissnerBeam(w, CircularSection(3.32e-3, 65e9, 0.33)),
        ReissnerBeam(w_strand, layer_section(cmesh)),
    ]
    for form in (lambda b: b.residual(), lambda b: ufl.derivative(b.residual(), b.w)):
        assert len({form(b).signature() for b in beams}) == 1


def helix_points(radius, lay_angle, length, n):
    z = np.linspace(0.0, length, n + 1)
    phi = np.tan(lay_angle) / radius * z
    return np.column_stack([radius * np.cos(phi), radius * np.sin(phi), z])


def test_unloaded_helix_has_no_section_forces():
    x = helix_points(6.67e-3, np.radians(12.0), 0.2, 60)
    cells = np.column_stack([np.arange(60), np.arange(1, 61)])
    mesh = polyline_mesh(MPI.COMM_WORLD, x, cells)
    w = fem.Function(beam_space(mesh))
    beam = ReissnerBeam(w, CircularSection(3.32e-3, 65e9, 0.33))
    sf = section_force_values(beam)
    assert np.abs(sf).max() < 1e-9


def rigidly_rotated(w_nodes, X, Q):
    """Nodal (u, θ) after turning the deformed structure by the rotation matrix Q about 0."""
    x = X + w_nodes[:, :3]
    R = Rotation.from_matrix(Q) * Rotation.from_rotvec(w_nodes[:, 3:])
    out = np.empty_like(w_nodes)
    out[:, :3] = x @ Q.T - X
    out[:, 3:] = R.as_rotvec()
    return out


def test_rigid_rotation_keeps_section_forces():
    """Objectivity: turning a 3D-loaded cantilever rigidly by 70° leaves its section forces.

    With strains from relative nodal rotations the invariance is exact; interpolating total rotation
    vectors (K = Tᵀ(θ)θ') fails this test with shear-force errors of 180 % of the largest section
    force on this mesh (measured while developing), bending errors of 2e-4.
    """
    case = cantilever(32, 1.0)
    P = 2 * S["EI"]

    def load(lam):
        case.force.value = lam * P * np.array([0.0, 0.6, 0.4])
        case.moment.value = lam * P * np.array([0.3, 0.0, 0.2])

    ramp(case, load, 1.0, first=0.25, max_step=0.5)
    before = section_force_values(case.beam)
    n2b = node_to_block(case.V)
    wn = case.w.x.array.reshape(-1, 6)
    Q = Rotation.from_rotvec(np.radians(70.0) * np.array([1.0, -2.0, 0.5]) / np.sqrt(5.25))
    wn[n2b] = rigidly_rotated(wn[n2b], case.mesh.geometry.x, Q.as_matrix())
    after = section_force_values(case.beam)
    scale = np.abs(before).max()
    assert np.abs(before[:, [1, 2, 4, 5]]).max() > 0.1 * scale  # a genuinely 3D state
    assert np.abs(after - before).max() < 1e-8 * scale


def test_jacobian_matches_finite_differences():
    """The UFL tangent equals central differences of the residual at a random finite-rotation state."""
    rng = np.random.default_rng(7)
    x = helix_points(3.34e-3, np.radians(6.0), 0.05, 12)
    cells = np.column_stack([np.arange(12), np.arange(1, 13)])
    mesh = polyline_mesh(MPI.COMM_WORLD, x, cells)
    V = beam_space(mesh)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(3.34e-3, 180e9, 0.3))
    F = fem.form(beam.residual())
    J = fem.form(ufl.derivative(beam.residual(), w))
    wn = w.x.array.reshape(-1, 6)
    wn[:, :3] = 1e-3 * rng.standard_normal((len(wn), 3))
    wn[:, 3:] = 0.8 * rng.standard_normal((len(wn), 3))  # finite rotations, some near zero below
    wn[0, 3:] = 1e-4 * rng.standard_normal(3)  # the small-angle series branch
    from dolfinx.fem import assemble_matrix, assemble_vector

    A = assemble_matrix(J).to_dense()
    w0 = w.x.array.copy()
    d = rng.standard_normal(w0.size) * np.tile([1e-3] * 3 + [1.0] * 3, len(wn))
    eps = 1e-7

    def residual(z):
        w.x.array[:] = z
        return assemble_vector(F).array.copy()

    fd = (residual(w0 + eps * d) - residual(w0 - eps * d)) / (2 * eps)
    Ad = A @ d
    assert np.linalg.norm(Ad - fd) < 1e-6 * np.linalg.norm(Ad)


@pytest.mark.parametrize("case", ["interval", "scalar"])
def test_beam_forms_refuse_what_they_are_not_written_for(case):
    """An interval mesh (1D in 1D) or a scalar unknown: one clear ValueError, not a UFL index
    error deep in the forms."""
    from dolfinx import fem
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from forms import CircularSection, ReissnerBeam

    if case == "interval":
        m = dmesh.create_interval(MPI.COMM_WORLD, 4, [0.0, 1.0])
        w = fem.Function(fem.functionspace(m, ("Lagrange", 1, (6,))))
        message = "need a 1D mesh in 3D .* got a 1D mesh in 1D"
    else:
        from strand.cable.mesh import straight_beam_mesh

        m = straight_beam_mesh(MPI.COMM_WORLD, 1.0, 4)
        w = fem.Function(fem.functionspace(m, ("Lagrange", 1)))
        message = r"need a \(6,\)-valued unknown"
    with pytest.raises(ValueError, match=message):
        ReissnerBeam(w, CircularSection(0.01, 210e9, 0.3))


class DoubledBending(CircularSection):
    """A section of one's own: EI × 2 about both axes (``moment_stiffness`` overridden)."""

    def moment_stiffness(self):
        return ufl.as_matrix([[self.GJ, 0, 0], [0, 2 * self.EI, 0], [0, 0, 2 * self.EI]])


def test_a_section_subclass_keeps_its_override_on_the_mesh():
    """A ``CircularSection`` subclass given numbers is put on the mesh as data (``on_mesh``)
    and stays itself: a tip moment M turns the tip by ML/(2EI), half the plain section's
    ML/EI, exactly (one-point cells reproduce a uniform moment)."""
    L, M = 0.5, 3.0
    case = cantilever(8, L, section=DoubledBending(D, E, NU))
    assert type(case.beam.section) is DoubledBending
    case.moment.value = [0.0, 0.0, M]
    assert case.solver.solve().converged
    assert case.tip_theta[2] == pytest.approx(M * L / (2 * S["EI"]), rel=1e-8)


def test_a_residual_written_as_virtual_work_is_the_energys_derivative():
    """The recipe for a law without an energy (``ReissnerBeam.residual``'s docstring):
    ∫ (N·δΓ + M·δK) dx, with δΓ and δK by ``ufl.derivative``, assembles to the energy's
    residual at a finite-rotation state (the linear law, which has both)."""
    from dolfinx.fem import assemble_vector

    rng = np.random.default_rng(3)
    x = helix_points(3.34e-3, np.radians(6.0), 0.05, 12)
    mesh = polyline_mesh(MPI.COMM_WORLD, x, np.column_stack([np.arange(12), np.arange(1, 13)]))
    w = fem.Function(beam_space(mesh))
    beam = ReissnerBeam(w, CircularSection(3.34e-3, 180e9, 0.3))
    wn = w.x.array.reshape(-1, 6)
    wn[:, :3] = 1e-3 * rng.standard_normal((len(wn), 3))
    wn[:, 3:] = 0.5 * rng.standard_normal((len(wn), 3))
    v = ufl.TestFunction(w.function_space)
    d_gamma = ufl.derivative(beam.Gamma, w, v)
    d_k = ufl.derivative(beam.K, w, v)
    virtual_work = (ufl.dot(beam.N, d_gamma) + ufl.dot(beam.M, d_k)) * beam.dx
    own = assemble_vector(fem.form(virtual_work)).array
    energy = assemble_vector(fem.form(beam.residual(v))).array
    assert np.abs(energy).max() > 1.0  # a loaded state
    np.testing.assert_allclose(own, energy, rtol=0, atol=1e-10 * np.abs(energy).max())


def test_layer_sections_take_the_cables_shear_coefficient_and_torsional_stiffness():
    """A layer's ``shear_coefficient`` and ``torsional_stiffness`` (cable table) reach its cells'
    section; the core, which gives neither, keeps Cowper's κ and G πd⁴/32. A cable that gives
    neither leaves both out of the forms (None). ``layer`` is each cell's layer index."""
    from strand.cable.description import cable_from_dict

    core = {"diameter": 3e-3, "E": 2e11, "nu": 0.3, "friction": 0.3}
    layer = {"wires": 6, "diameter": 3e-3, "E": 2e11, "nu": 0.3, "lay_angle": 8.0, "lay": "Z"}
    layer |= {"friction": 0.5, "shear_coefficient": 0.5, "torsional_stiffness": 1.25}
    cable = cable_from_dict({"core": core, "layer": [layer]})
    section = layer_section(cable_mesh(build_geometry(cable, 0.02, 4e-3)))
    is_core = section.layer.x.array == 0
    assert 0 < is_core.sum() < len(is_core)
    round_core = CircularSection(3e-3, 2e11, 0.3)
    kappa, gj = section.shear_coefficient.x.array, section.torsional_stiffness.x.array
    np.testing.assert_allclose(kappa[is_core], round_core.shear_coefficient, rtol=1e-15)
    np.testing.assert_allclose(gj[is_core], round_core.GJ, rtol=1e-15)
    np.testing.assert_array_equal(kappa[~is_core], 0.5)
    np.testing.assert_array_equal(gj[~is_core], 1.25)
    plain = layer_section(cable_mesh(build_geometry(cardinal(), 0.02, 4e-3)))
    assert plain.torsional_stiffness is None and isinstance(
        plain.shear_coefficient, ufl.core.expr.Expr
    )
