# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # A history-dependent law: a wire bent past yield by another
#
# A copper wire b, clamped at one end, rests with its free end on a crossing wire a. Wire a is
# pushed up by $\delta$, bends b past its yield moment through the contact, then goes back
# down: b keeps a permanent bend. This tutorial writes an elastic–plastic bending law in UFL,
# keeps its state (the plastic curvature) with strand's `InternalVariables`, which commit it
# after converged load steps only, and checks the residual curvature against the closed form.
#
# **The law.** Per bending axis (enough for a wire bent in one plane), the moment follows the
# elastic part of the curvature, and a yield function with linear kinematic hardening bounds
# it:
#
# $$M = EI\,(\kappa - \kappa_p), \qquad f = |M - H\kappa_p| - M_y \le 0,$$
#
# with $M_y$ the yield moment and $H$ the hardening modulus (N m²). Given the curvature $\kappa$
# of a step and the plastic curvature $\kappa_p^n$ of the last converged one, the return map is
# exact for this linear law: with the trial moment $M^{tr} = EI(\kappa - \kappa_p^n)$ and
# $\xi = M^{tr} - H\kappa_p^n$,
#
# $$\Delta\kappa_p = \frac{\langle |\xi| - M_y\rangle}{EI + H}\,\operatorname{sign}\xi, \qquad
# M = M^{tr} - EI\,\Delta\kappa_p, \qquad \kappa_p^{n+1} = \kappa_p^n + \Delta\kappa_p .$$
#
# Above yield the section's stiffness is $EI\,H/(EI + H)$. Axial force, shear and torsion stay
# linear elastic.
#
# **The closed form.** The contact is frictionless and its normal held vertical, so a pushes on
# b's tip with a vertical force $P$: b is a cantilever under a tip force, statically
# determinate, with the moment $M(x) = P\,(L - x)$ at a distance $x$ from the clamp (in the
# undeformed geometry: the lever arm shortens by $u_x(L) - u_x(x)$, a relative $\theta^2/2$
# at most, 4e-4 here). Loaded to $P_{max}$, the sections where $M$ exceeded $M_y$ hold
# $\kappa_p = (M - M_y)/H$. Unloaded, $P = 0$ and $M = 0$ everywhere, so, provided the
# unloading stays elastic ($P_{max}L < 2M_y$ for kinematic hardening), the wire keeps the
# residual curvature
#
# $$\kappa_{res}(x) = \frac{\langle P_{max}(L - x) - M_y\rangle}{H}$$
#
# over the plastic zone $x < L - M_y/P_{max}$, and none beyond. The tip force itself follows
# from the contact's penalty $K_N$ and the cantilever's deflection under it, elastic
# ($PL^3/3EI + PL/\kappa GA$) plus the plastic curvature's share, with $s_y = M_y/P$:
#
# $$\delta(P) = \frac{P}{K_N} + \frac{PL^3}{3EI} + \frac{PL}{\kappa GA}
#   + \frac{1}{H}\Big[\frac{P}{3}\,(L^3 - s_y^3) - \frac{M_y}{2}\,(L^2 - s_y^2)\Big]
#   \quad (P > M_y/L).$$
#
# Units: SI. The script runs on any number of processes (`mpirun -n 2 python
# demo_plastic_bending.py`) with the same result: process 0 prints and draws.

# +
import strand  # noqa: F401  (loads the dolfinx wheel's MPI library first)

# isort: split

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand import (
    InternalVariables,
    LoadStepper,
    NonlinearProblem,
    PenaltyLaw,
    beam_space,
    candidate_pairs,
    candidate_stencils,
    contact_terms,
    dof_values,
    locate_nodes,
    polyline_mesh,
    slab_partitioner,
)

comm = MPI.COMM_WORLD

# -

# ## The law in UFL
#
# `ReissnerBeam` gives the curvatures $K$ (torsion, two bending) at the single Gauss point of
# each cell. The subclass below takes the committed plastic curvatures of the two bending axes
# as a cell-wise (DG0) function `kappa_p`, and writes the return map with `ufl.conditional`:
# `M` is the returned moment, and `plastic_curvature` is $\kappa_p^{n+1}$, the state to commit
# after a converged step. The law has no energy, so it overrides `residual` with the virtual
# work $\int (N\cdot\delta\Gamma + M\cdot\delta K)\,dx$; `ufl.derivative` of it is the
# consistent tangent.


class PlasticBeam(ReissnerBeam):
    """A Reissner beam whose bending moments are elastic–plastic with linear kinematic
    hardening, per bending axis: yield moment M_y (N m), hardening modulus H (N m²), committed
    plastic curvatures ``kappa_p`` (1/m, a DG0 function of shape (2,))."""

    def __init__(self, w, section, kappa_p, M_y, H):
        super().__init__(w, section)
        self.kappa_p, self.M_y, self.H = kappa_p, M_y, H

    def plastic_increment(self):
        """Δκ_p of the return map, per bending axis (1/m)."""
        EI, H, K = self.section.EI, self.H, self.K
        out = []
        for i in range(2):
            xi = EI * (K[i + 1] - self.kappa_p[i]) - H * self.kappa_p[i]
            f = abs(xi) - self.M_y
            size = ufl.conditional(ufl.gt(f, 0.0), f / (EI + H), 0.0)
            out.append(ufl.conditional(ufl.ge(xi, 0.0), size, -size))
        return ufl.as_vector(out)

    def plastic_curvature(self):
        """κ_p after the return map (1/m): the state a converged step commits."""
        return self.kappa_p + self.plastic_increment()

    @property
    def M(self):
        K, EI = self.K, self.section.EI
        bending = EI * (ufl.as_vector([K[1], K[2]]) - self.plastic_curvature())
        return ufl.as_vector([self.section.GJ * K[0], bending[0], bending[1]])

    def residual(self, v=None):
        v = ufl.TestFunction(self.w.function_space) if v is None else v
        d_gamma = ufl.derivative(self.Gamma, self.w, v)
        d_kappa = ufl.derivative(self.K, self.w, v)
        return (ufl.dot(self.N, d_gamma) + ufl.dot(self.M, d_kappa)) * self.dx


# ## Two wires in one mesh
#
# Wire b runs along $x$ from its clamp to its tip at $x = L$, where it rests on wire a, which
# runs along $y$ below it. As in the crossed-beams tutorial, `candidate_stencils` finds the
# pair on the input arrays and `slab_partitioner` keeps its two nodes on one process. The
# copper wire: $d$ = 3 mm, $E$ = 120 GPa, first yield at $\sigma_y$ = 70 MPa, so
# $M_y = \sigma_y \pi d^3/32$, and a hardening modulus $H = EI/4$.

r, L, n = 1.5e-3, 0.06, 60  # wire radius (m), length of b (m), cells of b
E, nu, sigma_y = 120e9, 0.33, 70e6
x_b = np.linspace(0.0, L, n + 1)[:, None] * [1.0, 0.0, 0.0] + [0.0, 0.0, 2 * r]
x_a = np.linspace(-0.01, 0.01, 11)[:, None] * [0.0, 1.0, 0.0] + [L, 0.0, 0.0]
points = np.vstack([x_b, x_a])
cells = np.vstack([np.c_[0:n, 1 : n + 1], np.c_[0:10, 1:11] + n + 1])
reach = 1e-4  # largest initial gap of a pair (m)
stencils = candidate_stencils(points, cells, range(n + 1, n + 12), range(n + 1), r, r, reach)
partitioner = slab_partitioner(points[:, 0], cells, [stencils])
V = beam_space(polyline_mesh(comm, points, cells, partitioner))
a, b = locate_nodes(V, x_a), locate_nodes(V, x_b)
clamp = locate_nodes(V, x_b[0])

section = CircularSection(2 * r, E, nu)
EI, GA = section.EI, section.GA
M_y, H = sigma_y * np.pi * (2 * r) ** 3 / 32, section.EI / 4
kappa_p = fem.Function(fem.functionspace(V.mesh, ("DG", 0, (2,))), name="kappa_p")
w = fem.Function(V, name="w")
beam = PlasticBeam(w, section, kappa_p, M_y, H)

# ## Contact, supports and the state
#
# The pair gets a penalty law, no friction, and its initial normal for good (`"frozen"`): with
# the default `"director"` normal, from the wires' rotated tangents, the contact point would
# move along b as its tip turns (by about $2r\theta$, 70 µm here), shortening the lever arm
# by a relative 1e-3. Wire a is prescribed in full: it moves up by $\delta$ and nothing else.
# Wire b is clamped at $x = 0$. `InternalVariables` maps `kappa_p` to its update:
# `NonlinearProblem(history=[...])` commits it once per converged step, after the unknowns,
# and restores it whenever a failed attempt is rolled back, so Newton's iterations and
# `LoadStepper`'s discarded attempts never touch it. (In a strand, a law built by the `beam`
# factory lists such objects as its `history`, and `StrandProblem` passes them on; its fatigue
# outputs refuse it, as its stresses are not Navier's elastic ones.)

K_N = 1e8
pairs = candidate_pairs(V, a, b, r, r, reach)
contact = contact_terms(pairs, PenaltyLaw(K_N), normal="frozen")
lift = fem.Constant(V.mesh, 0.0)
bcs = [fem.dirichletbc(lift, 6 * a + 2, V.sub(2))]
bcs += [fem.dirichletbc(0.0, 6 * a + c, V.sub(c)) for c in (0, 1, 3, 4, 5)]
bcs += [fem.dirichletbc(np.zeros(6), clamp, V)]
plastic = InternalVariables({kappa_p: beam.plastic_curvature()})
problem = NonlinearProblem(beam.residual(), w, bcs, terms=[contact], history=[plastic])

# ## Up and down
#
# At $\delta_{max}$ = 1.25 mm the tip force bends b's clamped end to about $1.6\,M_y$: past
# yield, short of the $2M_y$ at which unloading would yield back. After every converged step
# we keep $\delta$ and the pair's force, summed over the processes.


def on_all(values) -> float:
    """The sum of ``values`` over this process's pairs and every other process's."""
    return comm.allreduce(float(np.sum(values)))


path = [(0.0, 0.0)]  # (δ, P)
stepper = LoadStepper(
    problem,
    0.05e-3,
    1e-7,
    max_step=0.05e-3,
    on_step=lambda s: path.append((float(lift.value), on_all(contact.state.force))),
)
delta_max = 1.25e-3
stepper.ramp(lambda d: setattr(lift, "value", d), 0.0, delta_max)
P_max = path[-1][1]
shortening = -dof_values(w, x_b[-1])[0, 0] / L  # of the lever arm at the peak: −u_x(L)/L
stepper.ramp(lambda d: setattr(lift, "value", d), delta_max, 0.0)
delta, P = np.array(path).T

# ## Against the closed form
#
# Unloaded, b carries no moment, so each cell's curvature (its relative rotation over its
# length) is its plastic curvature; `dof_values` reads both at the cells' midpoints $x_m$ (the
# DG0 dofs) on every process. They differ from the closed form by the lever arm's shortening
# at the peak, $|u_x(L)|/L$ at the clamp, which the plastic zone raises by
# $P_{max}L/(P_{max}L - M_y)$ in $\kappa_p$. The force path is compared with $P(\delta)$ up and
# down, within the same order $\theta^2$: the beam is geometrically exact, the closed form is
# not. Refining the cells or the steps changes neither error: the element reproduces the
# statically determinate moment in each cell, and the return map is exact for any step.


def cell_values(f, x):
    """The values of the DG0 function ``f`` at the cell midpoints ``x`` of b, on every process."""
    return dof_values(f, np.c_[x, np.zeros_like(x), np.full_like(x, 2 * r)])


def lift_of(P, P_peak):
    """δ(P) of the closed form (m) on the branch that has reached P_peak ≥ P (N)."""
    plastic = 0.0
    if P_peak * L > M_y:
        s = M_y / P_peak
        plastic = (P_peak * (L**3 - s**3) / 3 - M_y * (L**2 - s**2) / 2) / H
    return P / K_N + P * L**3 / (3 * EI) + P * L / GA + plastic


def force_at(d, P_peak=None):
    """The root P of δ(P) = d (N) by bisection, loading (P_peak None: the peak is P itself)
    or unloading from P_peak: 0 once the contact has opened."""
    low, high = 0.0, 2 * P_max
    for _ in range(100):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if lift_of(mid, P_peak or mid) < d else (low, mid)
    return 0.5 * (low + high)


x_mid = 0.5 * (x_b[1:, 0] + x_b[:-1, 0])
kappa_res = np.abs(cell_values(kappa_p, x_mid)[:, 0])  # about e_y
kappa_exact = np.maximum(P_max * (L - x_mid) - M_y, 0.0) / H
k_space = fem.functionspace(V.mesh, ("DG", 0))
curvature = fem.Function(k_space)
curvature.interpolate(fem.Expression(beam.K[1], k_space.element.interpolation_points))
kappa_total = np.abs(cell_values(curvature, x_mid)[:, 0])
peak = int(np.argmax(delta))
P_exact = np.array([force_at(d, P_max if i > peak else None) for i, d in enumerate(delta)])
curvature_error = np.max(np.abs(kappa_res - kappa_exact)) / np.max(kappa_exact)
spring_back = np.max(np.abs(kappa_total - kappa_res)) / np.max(kappa_exact)
force_error = np.max(np.abs(P - P_exact)) / P_max
zone = L - M_y / P_max
estimate = shortening * P_max * L / (P_max * L - M_y)
if comm.rank == 0:
    print(f"M_y = {M_y:.4f} N m, H = {H:.4f} N m², P_max L / M_y = {P_max * L / M_y:.4f}")
    print(f"{len(path) - 1} steps, {plastic.commits} commits of the plastic curvature")
    print(f"plastic zone L − M_y/P_max = {zone * 1e3:.2f} mm")
    print(f"κ_res at the clamp's cell {kappa_res[0]:.5f} 1/m, closed form {kappa_exact[0]:.5f}")
    print(f"largest |κ_res − closed form| / max κ_res = {curvature_error:.1e}")
    print(f"  expected from the lever arm's shortening {shortening:.1e}: {estimate:.1e}")
    print(f"unloaded: largest |κ − κ_p| / max κ_res = {spring_back:.1e}")
    print(f"largest |P − P(δ)| / P_max = {force_error:.1e}")
assert plastic.commits == len(path) - 1
assert 1 < P_max * L / M_y < 2
assert curvature_error < 1e-3
assert spring_back < 1e-6
assert force_error < 3e-3

# ## Picture
#
# The tip force against the lift of wire a, up and down, on its closed form; and the residual
# curvature along b after unloading, on the closed form's triangle over the plastic zone.

if comm.rank == 0:
    out = Path("results/demo_plastic_bending")
    out.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.plot(1e3 * delta, P_exact, "k-", lw=1, label="closed form")
    ax1.plot(1e3 * delta, P, "o", ms=3, label="strand")
    ax1.axhline(M_y / L, color="k", ls=":", lw=1, label="first yield, $P = M_y/L$")
    ax1.set(xlabel="lift of wire a, δ (mm)", ylabel="tip force P (N)", title="up and down")
    ax1.legend()
    ax2.plot(1e3 * x_mid, kappa_exact, "k-", lw=1, label="closed form")
    ax2.plot(1e3 * x_mid, kappa_res, "o", ms=3, label="strand")
    ax2.set(xlabel="distance from the clamp, x (mm)", ylabel="residual curvature (1/m)")
    ax2.set_title("after unloading")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(out / "plastic_bending.png", dpi=120)
    print("picture:", out / "plastic_bending.png")

# ## Exercises
#
# 1. **Deeper.** Lift wire a to $\delta_{max}$ = 1.5 mm. Does the unloading stay elastic, and
#    what residual curvature is left at the clamp?
#    *Answer:* $P_{max}L/M_y$ = **1.71**, still below 2: elastic unloading. At the clamp's cell,
#    $\kappa_{res} = (P_{max}(L - x_m) - M_y)/H$ = **1.075** 1/m, and strand finds
#    **1.075** 1/m.
# 2. **Softer hardening.** Back at 1.25 mm, halve the hardening: $H = EI/8$. Predict which way
#    the peak force and the residual curvature go.
#    *Answer:* the wire yields more easily, so the peak force falls, $P_{max}L/M_y$ = **1.41**
#    (1.57 with $H = EI/4$), yet the residual curvature rises: at the clamp's cell
#    $\kappa_{res}$ = **1.23** 1/m by the closed form and **1.23** 1/m by strand (0.873 before).
