"""Geometrically exact (Simo-Reissner) 3D beam on a 1D manifold mesh in 3D, in UFL.

Units are whatever the user's are, consistently; strand itself uses SI (m, N, Pa, rad).

Unknowns. One blocked P1 field ``w`` of shape (6,) per node: displacement u = w[0:3] and rotation
vector θ = w[3:6] of the cross-section (total, from the initial configuration).

Frames. Every cell carries an initial orthonormal frame Λ0 = [t, e2, e3] whose first column is the
unit tangent of the (straight) cell; curved wires are polylines whose kinks are stress-free. The
current frame is Λ(θ) Λ0.

Strains, in the material (section) frame, at the cell midpoint (the one Gauss point):

* Γ = Λ0ᵀ (Λmᵀ (t + u') − t)     axial (Γ1) and shear (Γ2, Γ3) strains,
* K = Λ0ᵀ log(Λaᵀ Λb) / h         torsion (K1) and bending (K2, K3) curvatures,

with ' = d/ds along the cell, h the cell length, Λa, Λb the nodal rotations and Λm their geodesic
midpoint (quaternion SLERP at ½). This is the two-node, one-point form of the strain-invariant
element of Jelenić & Crisfield (CMAME 171, 1999): strains depend on relative rotations only, so they
are objective (a rigid rotation of a loaded beam leaves them unchanged to round-off) and
path-independent. Interpolating the total rotation vector instead (K = Tᵀ(θ)θ') is not objective:
its midpoint rotation errs by O(φ²), φ the relative rotation of the two nodes, which shows up as
spurious shear forces κGA·O(φ²). Nodal values are recovered exactly at the midpoint from the P1
field as θ ∓ (h/2) θ'. Adjacent nodal rotation vectors must differ by less than π.

Linear elastic circular section: N = diag(EA, κGA, κGA) Γ and M = diag(GJ, EI, EI) K. One Gauss
point per cell (uniform reduced integration) is the classical cure for shear locking of two-node
Reissner elements; it leaves no spurious zero-energy mode.

The residual is the derivative of the strain energy, so the tangent from ``ufl.derivative`` is
consistent and symmetric (for conservative loads).
"""

from __future__ import annotations

import copy
import math
import numbers
from typing import TYPE_CHECKING

import ufl

from .rotations import (
    curvature_matrix,
    quaternion,
    quaternion_conjugate,
    quaternion_log,
    quaternion_matrix,
    quaternion_product,
)

if TYPE_CHECKING:
    from dolfinx import fem
    from dolfinx.mesh import Mesh

#: a section's property: a number, or UFL data (a ``Constant``, a cell-wise ``Function``)
SectionValue = float | ufl.core.expr.Expr

__all__ = [
    "CircularSection",
    "ReissnerBeam",
    "has_elastic_stresses",
    "unit_tangent",
    "tangent_frame",
    "moment_virtual_work",
    "REDUCED_QUADRATURE",
]

#: Form metadata for the one-point (midpoint) rule used for every beam term.
REDUCED_QUADRATURE = {"quadrature_degree": 1}


def check_beam_unknown(w: fem.Function) -> None:
    """Raise ``ValueError`` in one line unless ``w`` is (6,)-valued on a 1D mesh in 3D, the only
    setting the beam forms are written for (UFL would fail later with an index error)."""
    domain = ufl.domain.extract_unique_domain(w)
    if domain is None:
        raise ValueError("the beam's unknown must be a Function on a mesh (found no domain)")
    tdim, gdim = domain.topological_dimension, domain.geometric_dimension  # ufl ≥ 2025: ints
    if (tdim, gdim) != (1, 3):
        raise ValueError(
            f"Reissner beam forms need a 1D mesh in 3D (cells are lines, points have x, y, z); "
            f"got a {tdim}D mesh in {gdim}D: build it with three coordinates per point "
            "(e.g. dolfinx.mesh.create_mesh with a line element of shape (3,))"
        )
    if w.ufl_shape != (6,):
        raise ValueError(
            f"Reissner beam forms need a (6,)-valued unknown (u, θ) per node; got shape "
            f"{w.ufl_shape}: use functionspace(mesh, ('Lagrange', 1, (6,)))"
        )


def unit_tangent(mesh: Mesh) -> ufl.core.expr.Expr:
    """Unit tangent of each cell of a 1D mesh embedded in 3D, oriented along the cell's node order."""
    J = ufl.Jacobian(mesh)
    t = ufl.as_vector([J[0, 0], J[1, 0], J[2, 0]])
    return t / ufl.sqrt(ufl.dot(t, t))


def tangent_frame(t: ufl.core.expr.Expr, hint: ufl.core.expr.Expr | None = None):
    """Orthonormal frame Λ0 = [t, e2, e3] (columns) built from the tangent t.

    e2 is the part of ``hint`` orthogonal to t. Without a hint, e_x is used unless t is within
    ~25° of e_x, then e_y: this works for straight wires along any axis and for helices.
    """
    if hint is None:
        ex, ey = ufl.as_vector([1.0, 0.0, 0.0]), ufl.as_vector([0.0, 1.0, 0.0])
        hint = ufl.conditional(ufl.lt(abs(t[0]), 0.9), ex, ey)
    e2 = hint - ufl.dot(hint, t) * t
    e2 = e2 / ufl.sqrt(ufl.dot(e2, e2))
    e3 = ufl.cross(t, e2)
    return ufl.as_matrix([[t[i], e2[i], e3[i]] for i in range(3)])


class CircularSection:
    """Elastic solid circular section of diameter d (m), Young's modulus E (Pa), Poisson ratio ν.

    Arguments may be numbers, ``Constant`` or cell-wise (DG0) ``Function`` objects, so one mesh can
    mix steel and aluminium wires. The shear coefficient defaults to Cowper's 6(1+ν)/(7+6ν).
    ``torsional_stiffness`` (N m²) replaces GJ = G πd⁴/32 when given: for a benchmark that sets
    it apart, or a section whose torsion is not that of a solid circle.

    Given numbers, the stiffnesses below are numbers. ``ReissnerBeam`` puts them in its forms as
    cell-wise data (``on_mesh``), not as literals: a literal is part of the compiled kernel, so
    every new diameter or modulus would cost a new FFCx compilation.

    A section law of one's own subclasses it and overrides ``force_stiffness`` and
    ``moment_stiffness`` (a linear law), or the beam's ``N``, ``M`` and
    ``strain_energy_density`` (a nonlinear one: ``ReissnerBeam``).
    """

    def __init__(
        self,
        d: SectionValue,
        E: SectionValue,
        nu: SectionValue,
        shear_coefficient: SectionValue | None = None,
        torsional_stiffness: SectionValue | None = None,
    ):
        self._arguments = (d, E, nu, shear_coefficient, torsional_stiffness)
        self.d, self.E, self.nu = d, E, nu
        self.torsional_stiffness = torsional_stiffness
        self.G = E / (2 * (1 + nu))
        self.shear_coefficient = (
            6 * (1 + nu) / (7 + 6 * nu) if shear_coefficient is None else shear_coefficient
        )
        self.area = math.pi * d**2 / 4
        self.second_moment = math.pi * d**4 / 64
        self.polar_moment = math.pi * d**4 / 32

    def on_mesh(self, mesh: Mesh) -> CircularSection:
        """This section with each number among its arguments held by a cell-wise (DG0) function
        of ``mesh``; ``Constant`` and ``Function`` arguments are kept. Its forms are those of a
        strand's layer sections (cell-wise d, E, ν), so one compiled kernel serves both."""
        if not any(isinstance(a, numbers.Real) for a in self._arguments):
            return self  # every argument is already data of the forms (or None)
        from dolfinx import fem  # here, not at the top: the forms import without dolfinx

        space = fem.functionspace(mesh, ("DG", 0))

        def cell_wise(value, name):
            if not isinstance(value, numbers.Real):
                return value
            f = fem.Function(space, name=name)
            f.x.array[:] = value
            return f

        names = ("d", "E", "nu", "shear_coefficient", "torsional_stiffness")
        # a copy keeps a subclass and its own attributes (its overridden stiffnesses); only the
        # five arguments are replaced
        section = copy.copy(self)
        CircularSection.__init__(section, *map(cell_wise, self._arguments, names))
        return section

    @property
    def EA(self):
        """Axial stiffness (N)."""
        return self.E * self.area

    @property
    def GA(self):
        """Shear stiffness κGA (N)."""
        return self.shear_coefficient * self.G * self.area

    @property
    def GJ(self):
        """Torsional stiffness (N m²): ``torsional_stiffness`` if given, else G πd⁴/32."""
        if self.torsional_stiffness is not None:
            return self.torsional_stiffness
        return self.G * self.polar_moment

    @property
    def EI(self):
        """Bending stiffness (N m²), the same about both axes."""
        return self.E * self.second_moment

    def force_stiffness(self) -> ufl.core.expr.Expr:
        """3×3 matrix C_N of the section forces N = C_N Γ: diag(EA, κGA, κGA) in N, for the
        axial and the two shear strains of the section frame [t, e2, e3]. Override it (with
        ``moment_stiffness``) for another linear section, e.g. anisotropic or coupled terms;
        ``ReissnerBeam.N`` and the energy ½ Γ·N use it."""
        return ufl.as_matrix([[self.EA, 0, 0], [0, self.GA, 0], [0, 0, self.GA]])

    def moment_stiffness(self) -> ufl.core.expr.Expr:
        """3×3 matrix C_M of the section moments M = C_M K: diag(GJ, EI, EI) in N m², for the
        torsion and the two bending curvatures of the section frame. Override it for another
        linear section (e.g. EI2 ≠ EI3); ``ReissnerBeam.M`` and the energy ½ K·M use it."""
        return ufl.as_matrix([[self.GJ, 0, 0], [0, self.EI, 0], [0, 0, self.EI]])


class ReissnerBeam:
    """Strain measures, section forces, energy and residual of a Reissner beam.

    What a law of one's own overrides (the strains ``Gamma`` and ``K`` stay):

    * a hyperelastic law: ``strain_energy_density`` ψ(Γ, K); the residual and its tangent
      follow by ``ufl.derivative``;
    * the resultants ``N`` and ``M`` (and so ``section_forces``, ``spatial_force``,
      ``spatial_moment``), which outputs, section cuts and pictures read: override them
      with the energy, as ∂ψ/∂Γ and ∂ψ/∂K;
    * a law without an energy: ``residual``, e.g. ∫ (N·δΓ + M·δK) dx written out
      (``ufl.derivative`` of ``Gamma`` and ``K`` gives δΓ, δK), whose tangent is then not
      symmetric in general.

    A linear section of one's own subclasses ``CircularSection`` instead. A strand takes either
    through ``strand``'s beam factory: ``StrandModel(geometry, beam=MyBeam)`` calls
    ``MyBeam(w, section)`` with the strand's unknown and its layers' section.

    A history-dependent law (plasticity) reads a state of the last converged step from
    functions of its own and lists, as ``history``, the objects that update them once per
    converged step (``strand.solver.InternalVariables``); ``StrandProblem`` hands them to its
    Newton problem. A law whose surface stresses are not Navier's from ``N`` and ``M`` leaves
    ``elastic_stresses`` (``has_elastic_stresses``): strand's fatigue outputs refuse it.

    Args:
        w: the (6,)-valued P1 unknown (u, θ) on a 1D mesh in 3D.
        section: the section law (``CircularSection``); the forms hold its numbers as
            cell-wise data (``CircularSection.on_mesh``).
        frame: initial frame Λ0 = [t, e2, e3] per cell; default ``tangent_frame(unit_tangent(mesh))``.
        dx: integration measure; default one-point rule (reduced integration).
    """

    #: the state of a history-dependent law: objects with ``commit()`` and ``rollback()``
    #: (``strand.solver.HistoryState``), committed once per converged step; none here
    history: tuple = ()
    #: whether Navier's formula, σ = N/A + M r/I at the surface of a linear elastic round wire,
    #: gives this law's stresses from ``N`` and ``M`` (strand's fatigue outputs compute them so).
    #: A subclass that overrides the law (``N``, ``M``, ``strain_energy_density``, ``residual``)
    #: does not inherit it: it sets it again if true (``has_elastic_stresses``)
    elastic_stresses: bool = True

    def __init__(
        self,
        w: fem.Function,
        section: CircularSection,
        frame: ufl.core.expr.Expr | None = None,
        dx: ufl.Measure | None = None,
    ):
        check_beam_unknown(w)
        mesh = w.function_space.mesh
        self.w = w
        self.section = section.on_mesh(mesh)
        self.t = unit_tangent(mesh)
        self.frame = tangent_frame(self.t) if frame is None else frame
        self.dx = dx if dx is not None else ufl.Measure("dx", mesh, metadata=REDUCED_QUADRATURE)
        self.u = ufl.as_vector([w[i] for i in range(3)])
        self.theta = ufl.as_vector([w[i] for i in range(3, 6)])
        J = ufl.Jacobian(mesh)
        self.h = ufl.sqrt(sum(J[i, 0] ** 2 for i in range(3)))  # cell length
        dtheta = self.d_ds(self.theta)
        q_a = quaternion(self.theta - self.h / 2 * dtheta)
        q_b = quaternion(self.theta + self.h / 2 * dtheta)
        #: midpoint rotation Λm (SLERP at ½ of the nodal rotations)
        self.Lambda = quaternion_matrix((q_a[0] + q_b[0], q_a[1] + q_b[1]))
        #: relative rotation vector of the two nodes, in the frame of node a (= of the midpoint)
        self.phi = quaternion_log(quaternion_product(quaternion_conjugate(q_a), q_b))

    def d_ds(self, f: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
        """Derivative along the cell, d/ds."""
        return ufl.dot(ufl.grad(f), self.t)

    @property
    def Gamma(self):
        """Material translational strains Γ (axial, shear 2, shear 3), dimensionless, in the
        section frame [t, e2, e3]."""
        L0, Lam, t = self.frame, self.Lambda, self.t
        return L0.T * (Lam.T * (t + self.d_ds(self.u)) - t)

    @property
    def K(self):
        """Material curvatures K (torsion, bending 2, bending 3) in rad/m, section frame."""
        return self.frame.T * self.phi / self.h

    @property
    def N(self):
        """Material section forces (axial N, shears V2, V3) in N: ``force_stiffness`` Γ here.
        A law of one's own overrides it (with ``strain_energy_density``) as ∂ψ/∂Γ."""
        return self.section.force_stiffness() * self.Gamma

    @property
    def M(self):
        """Material section moments (torque, bending M2, M3) in N m: ``moment_stiffness`` K
        here. A law of one's own overrides it (with ``strain_energy_density``) as ∂ψ/∂K."""
        return self.section.moment_stiffness() * self.K

    def section_forces(self):
        """(N, V2, V3, Mt, M2, M3) as one 6-vector, material frame."""
        N, M = self.N, self.M
        return ufl.as_vector([N[0], N[1], N[2], M[0], M[1], M[2]])

    def spatial_force(self):
        """Section force n = Λ Λ0 N in the global frame (N)."""
        return self.Lambda * (self.frame * self.N)

    def spatial_moment(self):
        """Section moment m = Λ Λ0 M in the global frame (N m)."""
        return self.Lambda * (self.frame * self.M)

    def strain_energy_density(self) -> ufl.core.expr.Expr:
        """Strain energy per unit length ψ (J/m = N) at the cell's Gauss point: here the linear
        ½ (Γ·N + K·M). Override it for a hyperelastic law ψ(Γ, K) of one's own (a UFL
        expression of ``self.Gamma`` and ``self.K``): ``energy`` and ``residual`` use it, so the
        residual is δψ and the tangent its consistent, symmetric second derivative. Override
        ``N`` and ``M`` as well (∂ψ/∂Γ, ∂ψ/∂K) so that outputs read the law's resultants."""
        return 0.5 * (ufl.dot(self.Gamma, self.N) + ufl.dot(self.K, self.M))

    def energy(self) -> ufl.Form:
        """Strain energy (J): ∫ ψ dx with ``strain_energy_density`` ψ."""
        return self.strain_energy_density() * self.dx

    def residual(self, v: ufl.Argument | None = None) -> ufl.Form:
        """Internal virtual work δΠ(w; v) (J per unit of ``v``), the derivative of ``energy``;
        add external work with a minus sign. Override it for a law without an energy: the
        virtual work ∫ (N·δΓ + M·δK) dx of one's own resultants, with δΓ, δK from
        ``ufl.derivative(self.Gamma, self.w, v)`` and likewise for ``self.K``."""
        if v is None:
            v = ufl.TestFunction(self.w.function_space)
        return ufl.derivative(self.energy(), self.w, v)


#: the members that make a beam's law: a subclass overriding any of them has a law of its own
LAW_MEMBERS = ("N", "M", "strain_energy_density", "residual")


def has_elastic_stresses(beam: object) -> bool:
    """Whether the beam law ``beam`` (an instance or a class) declares Navier's stresses:
    ``elastic_stresses`` true, set by the class that last defines the law (``LAW_MEMBERS``) or
    by one derived from it, or on the instance. A subclass of ``ReissnerBeam`` with a law of
    its own (softening, plasticity) is thus not taken at its parent's word; an object without
    the attribute does not declare it."""
    if not isinstance(beam, type) and "elastic_stresses" in getattr(beam, "__dict__", {}):
        return bool(vars(beam)["elastic_stresses"])
    cls = beam if isinstance(beam, type) else type(beam)
    declared = next((k for k in cls.__mro__ if "elastic_stresses" in vars(k)), None)
    if declared is None or not declared.elastic_stresses:
        return False
    for name in LAW_MEMBERS:
        defined = next((k for k in cls.__mro__ if name in vars(k)), None)
        if defined is not None and not issubclass(declared, defined):
            return False
    return True


def moment_virtual_work(
    moment: ufl.core.expr.Expr, theta: ufl.core.expr.Expr, v_theta: ufl.core.expr.Expr
) -> ufl.core.expr.Expr:
    """Virtual work m·δω = m·T(θ)δθ of a fixed-direction (spatial) moment m on the rotation dofs.

    Integrate it on the points where the moment acts (e.g. ``ds(tag)`` at a wire end).
    For a planar rotation about the moment axis this reduces to m·δθ.
    """
    return ufl.dot(moment, curvature_matrix(theta) * v_theta)
