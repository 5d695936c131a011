# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # A section law of your own: a beam that softens in bending
#
# `forms.ReissnerBeam` writes the strains of a geometrically exact beam in UFL and takes its
# residual as the derivative of a strain energy density. Any section law that has an energy can
# be plugged in by overriding that density: the residual and its consistent tangent follow from
# `ufl.derivative`, with no other change. This tutorial does it for a nonlinear bending law, then
# checks the finite-element result against the closed form.
#
# **The law.** A strand bends stiffly while its wires stick to each other and softly once they
# slip: its moment–curvature runs from a stick slope $EI_{max}$ to a slip slope $EI_{min}$ over a
# curvature scale $\kappa_b$. A smooth law with that shape, per bending axis, is
#
# $$\psi(\kappa) = \tfrac12 EI_{min}\,\kappa^2 + (EI_{max} - EI_{min})\,\kappa_b^2
#   \ln\cosh(\kappa/\kappa_b), \qquad
#   M(\kappa) = \psi'(\kappa) = EI_{min}\,\kappa + (EI_{max} - EI_{min})\,\kappa_b
#   \tanh(\kappa/\kappa_b),$$
#
# with tangent $EI_{max}$ at $\kappa = 0$ and $EI_{min}$ for $\kappa \gg \kappa_b$. Axial force,
# shear and torsion stay linear elastic.
#
# **The closed form.** A cantilever of length $L$ with a fixed-direction end moment $M$ is in pure
# bending: the moment is $M$ in every section, so the curvature is the same everywhere, the root
# $\kappa$ of $M(\kappa) = M$, and the beam is an arc of a circle. Its tip turns by $\kappa L$ and
# sits at $x = \sin(\kappa L)/\kappa$, $y = (1 - \cos\kappa L)/\kappa$. Units: SI.
#
# The script runs on any number of processes (`mpirun -n 2 python demo_section_law.py`) with
# the same result: process 0 prints and draws.

# +
import strand  # noqa: F401  (loads the dolfinx wheel's MPI library first)

# isort: split

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam, moment_virtual_work
from strand import LoadStepper, NonlinearProblem, beam_space, dof_values, straight_beam_mesh

comm = MPI.COMM_WORLD

# -

# ## The beam with its own section law
#
# `ReissnerBeam` gives the material strains $\Gamma$ (axial, two shears) and $K$ (torsion, two
# bending curvatures) as UFL expressions. The subclass below keeps the linear section for
# $\Gamma$ and torsion, and replaces the bending part of the energy by $\psi(K_2) + \psi(K_3)$.
# It also overrides `M`, the section moments, so that outputs and pictures read the law's
# moments. (A law isotropic in bending would take $\psi$ of $\sqrt{K_2^2 + K_3^2}$; one law per
# axis is enough for a beam bent in one plane.)


class SofteningBeam(ReissnerBeam):
    """A Reissner beam whose bending moments follow ψ(κ) above, per bending axis; EI_min and
    EI_max in N m², kappa_b in 1/m."""

    def __init__(self, w, section, EI_min, EI_max, kappa_b):
        super().__init__(w, section)
        self.EI_min, self.EI_max, self.kappa_b = EI_min, EI_max, kappa_b

    def bending_energy(self, k):
        d_EI, kb = self.EI_max - self.EI_min, self.kappa_b
        return 0.5 * self.EI_min * k**2 + d_EI * kb**2 * ufl.ln(ufl.cosh(k / kb))

    def bending_moment(self, k):
        d_EI, kb = self.EI_max - self.EI_min, self.kappa_b
        return self.EI_min * k + d_EI * kb * ufl.tanh(k / kb)

    @property
    def M(self):
        K, GJ = self.K, self.section.GJ
        return ufl.as_vector([GJ * K[0], self.bending_moment(K[1]), self.bending_moment(K[2])])

    def strain_energy_density(self):
        K = self.K
        linear = 0.5 * ufl.dot(self.Gamma, self.N) + 0.5 * self.section.GJ * K[0] ** 2
        return linear + self.bending_energy(K[1]) + self.bending_energy(K[2])


# A steel rod of 10 mm whose stick slope is its own $EI$, softening to a tenth of it past
# $\kappa_b = 1$ 1/m:

L, n_cells, d, E = 1.0, 40, 0.01, 210e9
EI_max = E * np.pi * d**4 / 64
EI_min, kappa_b = 0.1 * EI_max, 1.0


def moment_law(kappa):
    """M(κ) of the law, N m (numpy)."""
    return EI_min * kappa + (EI_max - EI_min) * kappa_b * np.tanh(kappa / kappa_b)


def curvature_under(moment):
    """The root κ of M(κ) = moment (1/m), by bisection: M is increasing."""
    low, high = 0.0, moment / EI_min
    for _ in range(200):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if moment_law(mid) < moment else (low, mid)
    return 0.5 * (low + high)


# ## Mesh, load and supports
#
# As in the cantilever roll-up tutorial: a straight beam along $x$, clamped at the root, with a
# fixed-direction end moment about $e_z$ whose virtual work `moment_virtual_work` provides.

domain = straight_beam_mesh(comm, L, n_cells, direction=(1.0, 0.0, 0.0))
V = beam_space(domain)
w = fem.Function(V, name="w")
beam = SofteningBeam(w, CircularSection(d, E, 0.3), EI_min, EI_max, kappa_b)

tip = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], L))
root = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], 0.0))
ds = ufl.Measure("ds", domain, subdomain_data=mesh.meshtags(domain, 0, tip, np.ones_like(tip)))
moment = fem.Constant(domain, np.zeros(3))
v = ufl.TestFunction(V)
v_theta = ufl.as_vector([v[3], v[4], v[5]])
F = beam.residual(v) - moment_virtual_work(moment, beam.theta, v_theta) * ds(1)
clamp = fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, root), V)

# ## Load stepping to half a circle
#
# The largest moment is the one that bends the rod into half a circle, $\kappa L = \pi$. At every
# converged step we keep the applied moment and the tip's rotation and position: `dof_values`
# reads the tip node's unknowns where it is owned and gives them to every process.

M_max = moment_law(np.pi / L)
problem = NonlinearProblem(F, w, [clamp])
steps = []


def record(step):
    tip_w = dof_values(w, [L, 0.0, 0.0])[0]
    steps.append((step.load * M_max, tip_w[5], L + tip_w[0], tip_w[1]))


stepper = LoadStepper(problem, first_step=0.05, min_step=1e-3, max_step=0.1, on_step=record)
stepper.ramp(lambda lam: setattr(moment, "value", [0.0, 0.0, lam * M_max]), 0.0, 1.0)

# ## Against the closed form
#
# At every step the tip rotation is $\kappa L$ with $\kappa$ the law's root: each cell's curvature
# is its relative rotation over its length, and equilibrium makes each cell's moment $M$, so the
# element reproduces the law exactly. The tip lies on the circle of radius $1/\kappa$ up to the
# chords' sagitta, a relative $(\kappa h)^2/24$ with $h = L/40$.

M, rotation, x_tip, y_tip = np.array(steps).T
kappa = np.array([curvature_under(m) for m in M])
x_exact, y_exact = np.sin(kappa * L) / kappa, (1 - np.cos(kappa * L)) / kappa
rotation_error = np.max(np.abs(rotation - kappa * L) / (kappa * L))
position_error = np.max(np.hypot(x_tip - x_exact, y_tip - y_exact)) / L
if comm.rank == 0:
    print(
        f"{len(steps)} steps; largest relative error of the tip rotation {rotation_error:.1e}, "
        f"of the tip position {position_error:.1e} (sagitta bound {(np.pi / n_cells) ** 2 / 24:.1e})"
    )
assert rotation_error < 1e-6
assert position_error < (np.pi / n_cells) ** 2 / 24 * 1.1

# ## Picture
#
# The finite-element moment–curvature (applied moment against tip rotation over length) on the
# law, between its stick and slip slopes; and the rod's tip path against the circle's, drawn by
# process 0.

if comm.rank == 0:
    out = Path("results/demo_section_law")
    out.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    k = np.linspace(0.0, np.pi / L, 200)
    ax1.plot(k, moment_law(k), "k-", label="law M(κ)")
    ax1.plot(k, EI_max * k, "k:", label="stick slope EI_max")
    ax1.plot(k, EI_min * k + (EI_max - EI_min) * kappa_b, "k--", label="slip slope EI_min")
    ax1.plot(rotation / L, M, "o", label="finite elements")
    ax1.set(
        xlabel="curvature κ (1/m)",
        ylabel="moment M (N m)",
        ylim=(0, 1.2 * M_max),
        title="moment–curvature of the section law",
    )
    ax1.legend()
    ax2.plot(x_exact, y_exact, "k-", label="closed form")
    ax2.plot(x_tip, y_tip, "o", label="finite elements")
    ax2.set(xlabel="x (m)", ylabel="y (m)", aspect="equal", title="tip positions during the load")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(out / "section_law.png", dpi=120)
    print("picture:", out / "section_law.png")

# ## Exercises
#
# 1. **A sharper knee.** Set $\kappa_b = 0.5$ 1/m. Which moment bends the rod into half a circle
#    now? (A new $\kappa_b$ is a new number in the UFL forms: the first run compiles a kernel.)
#    *Answer:* $M(\pi/L) = EI_{min}\pi + (EI_{max} - EI_{min})\,\kappa_b\tanh(2\pi)$ = **78.8** N m
#    (124.8 N m with $\kappa_b = 1$), and the tip turns by **1.000** $\pi$ under it.
# 2. **The stiff rod's moment.** Load the softening rod with the moment that bends a linear rod
#    of stiffness $EI_{max}$ into half a circle, $M = \pi EI_{max}/L$ (drop the check against
#    the sagitta bound, which assumes half a circle). How far does it bend?
#    *Answer:* $0.1\,\kappa + 0.9\tanh\kappa = \pi$ (in 1/m, with $\kappa_b$ = 1 1/m), so
#    $\kappa = 10\pi - 9$ = **22.42** 1/m, as the tip rotation over $L$ finds (**22.42** 1/m):
#    the rod winds **3.57** times round.
