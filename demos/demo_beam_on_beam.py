# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # A beam pressed onto a beam: line contact
#
# Two simply supported beams of span $L$ lie one on the other along their whole length; the upper
# one (b) carries a uniform load $q_0$. Where they stay in contact they share one deflection $w$,
# and each carries its part of the load through its own bending stiffness:
#
# $$EI_b\, w'''' = q_0 - q_c, \qquad EI_a\, w'''' = q_c \quad\Rightarrow\quad
# q_c = q_0\,\frac{EI_a}{EI_a + EI_b}, \qquad w(L/2) = \frac{5 q_0 L^4}{384\,(EI_a + EI_b)}:$$
#
# the contact line load $q_c$ is uniform, and the two beams bend as one of stiffness
# $EI_a + EI_b$.
#
# **The contact terms.** Each node of b is paired with the nearest node of a (a *line* pair):
# its normal is the part of $x_b - x_a$ normal to beam a, its gap
# $g = (x_b - x_a)\cdot n - r_a - r_b$, and it stands for a tributary length $\ell$ of the contact
# line, with a penalty $p = k\,\ell \langle -g \rangle$: a bed of springs of stiffness $k$ per unit
# length (a Winkler foundation, `LinePenaltyLaw(k)`), stiff enough here that the beams' gap,
# $q_c/k$, is negligible.
# Units: SI.
#
# The script runs on any number of processes (`mpirun -n 2 python demo_beam_on_beam.py`) with
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

from forms import CircularSection, ReissnerBeam
from strand import (
    LinePenaltyLaw,
    NonlinearProblem,
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

# ## Two beams, one mesh
#
# The lower beam a is 6 mm thick, the upper b 4 mm: a carries five sixths of the load. On
# several processes a pair is evaluated by the process owning its node a, which must also hold
# its node b and their neighbours: `candidate_stencils` finds the pairs on the input arrays
# (`reach` and `line` as `candidate_pairs` below), and `slab_partitioner` cuts the mesh into
# slabs along $x$, both beams together, with each pair's nodes whole on one process.

L, n, E, nu = 0.5, 100, 200e9, 0.3
r_a, r_b = 3e-3, 2e-3
x = np.linspace(0.0, L, n + 1)
x_a = np.c_[x, 0 * x, 0 * x]
x_b = np.c_[x, 0 * x, 0 * x + r_a + r_b]
points = np.vstack([x_a, x_b])
cells = np.vstack([np.c_[0:n, 1 : n + 1], np.c_[0:n, 1 : n + 1] + n + 1])
reach = 1e-6  # the largest initial gap of a pair (m): the beams touch
stencils = candidate_stencils(
    points, cells, range(n + 1), range(n + 1, 2 * n + 2), r_a, r_b, reach, line=True
)
partitioner = slab_partitioner(points[:, 0], cells, [stencils])
domain = polyline_mesh(comm, points, cells, partitioner)
V = beam_space(domain)
a, b = locate_nodes(V, x_a), locate_nodes(V, x_b)
w = fem.Function(V)

# Each beam has its own diameter: a cell-wise (DG0) diameter gives `CircularSection` the
# stiffness of each cell's beam (interpolated at the cells' midpoints). The load acts on b's
# cells only, which a cell tag selects.

DG0 = fem.functionspace(domain, ("DG", 0))
d = fem.Function(DG0)
d.interpolate(lambda p: np.where(p[2] > r_a, 2 * r_b, 2 * r_a))
upper = mesh.locate_entities(domain, 1, lambda p: p[2] > r_a)
beam = ReissnerBeam(w, CircularSection(d, E, nu))
q0 = 20.0  # N/m
dx = ufl.Measure("dx", domain, subdomain_data=mesh.meshtags(domain, 1, upper, 1))
v = ufl.TestFunction(V)
F = beam.residual(v) + q0 * v[2] * dx(1)

# ## Line pairs and supports
#
# `candidate_pairs(..., line=True)` pairs every node of b within reach of a's surface, and
# `LinePenaltyLaw(k)` gives each pair the stiffness $k\,\ell$ of its tributary length. Both beams
# are pinned at $x = 0$ and on rollers at $x = L$, and held against twisting: dolfinx's
# `locate_dofs_topological` on a component `V.sub(c)` gives that component's dofs at the end
# vertices. The load does not depend on $w$, so the tangent is the beams' alone: given as `J`, it
# is the same form as a strand's tangent, and FFCx's cache serves both with one compiled kernel
# (the default, `ufl.derivative(F, w)`, carries the load's zero derivative and compiles a kernel
# of its own).

pairs = candidate_pairs(V, a, b, r_a, r_b, reach, line=True)
k_line = 1e10  # N/m²
contact = contact_terms(pairs, LinePenaltyLaw(k_line))
pins = mesh.locate_entities_boundary(domain, 0, lambda p: np.isclose(p[0], 0.0))
ends = mesh.locate_entities_boundary(
    domain, 0, lambda p: np.isclose(p[0], 0.0) | np.isclose(p[0], L)
)
bcs = [
    fem.dirichletbc(0.0, fem.locate_dofs_topological(V.sub(c), 0, ends), V.sub(c))
    for c in (1, 2, 3)
]
bcs.append(fem.dirichletbc(0.0, fem.locate_dofs_topological(V.sub(0), 0, pins), V.sub(0)))
problem = NonlinearProblem(F, w, bcs, terms=[contact], J=ufl.derivative(beam.residual(v), w))
result = problem.solve()
if comm.rank == 0:
    print(f"Newton: {result.iterations} iterations, residual {result.residual:.1e} N")
assert result.converged

# ## Against the closed form
#
# The closed form holds away from the supports. Near them the contact departs from it (by 1.3 %
# at 0.15 L), and the pair at each support, which joins two supported nodes, is pressed by the
# rotation of the beams' ends (its normal turns with beam a, its nodes cannot move apart), so the
# line load is compared over the middle 60 % of the span.
#
# On several processes each holds part of the beams and of the pairs. `dof_values` gives the
# unknowns of the nodes at given points on every process (each read where it is owned); the
# pairs' results are put in their global order (`pairs.index`) and summed over the processes.

I_a, I_b = np.pi * (2 * r_a) ** 4 / 64, np.pi * (2 * r_b) ** 4 / 64
share = I_a / (I_a + I_b)
w_mid = 5 * q0 * L**4 / (384 * E * (I_a + I_b))
w_a, w_b = -dof_values(w, x_a)[:, 2], -dof_values(w, x_b)[:, 2]
n_pairs = comm.allreduce(len(pairs.index))


def in_order(values) -> np.ndarray:
    """Per-pair ``values`` of every process's pairs, in the pairs' global order, everywhere."""
    out = np.zeros(n_pairs)
    out[pairs.index] = values
    return comm.allreduce(out)


x_pairs = in_order(pairs.positions[:, 1, 0])  # the x of each pair's node b
q_c = in_order(contact.state.force / pairs.tributary)
middle = (x_pairs > 0.2 * L) & (x_pairs < 0.8 * L)
w_error = abs(w_b[n // 2] / w_mid - 1)
q_error = np.max(np.abs(q_c[middle] / (share * q0) - 1))
if comm.rank == 0:
    print(
        f"midspan deflection {w_b[n // 2] * 1e3:.4f} mm (closed form {w_mid * 1e3:.4f} mm, "
        f"relative difference {w_error:.1e}); contact line load {q_c[middle].mean():.4f} N/m "
        f"against q0 EI_a/(EI_a + EI_b) = {share * q0:.4f} N/m (largest difference {q_error:.1e})"
    )
assert w_error < 1e-3 and q_error < 1e-2
assert np.max(np.abs(w_a - w_b)) < 1e-6 * w_mid * 1e3  # together: the gap is q_c/k ~ 2 nm

# ## Picture
#
# Drawn by process 0: every process holds the deflections and line loads above.

if comm.rank == 0:
    out = Path("results/demo_beam_on_beam")
    out.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6))
    xi = x / L
    ax1.plot(x * 1e3, w_b * 1e3, "o", ms=2, label="strand, upper beam b")
    ax1.plot(x * 1e3, w_a * 1e3, "-", lw=1, label="strand, lower beam a")
    exact = q0 * L**4 / (24 * E * (I_a + I_b)) * (xi - 2 * xi**3 + xi**4)
    ax1.plot(x * 1e3, exact * 1e3, "k:", label="closed form")
    ax1.set(xlabel="x (mm)", ylabel="deflection (mm)", title="the two beams bend as one")
    ax2.plot(x_pairs * 1e3, q_c, "o", ms=2, label="strand (pair force / ℓ)")
    ax2.axhline(share * q0, color="k", lw=1, label=r"$q_0\,EI_a/(EI_a + EI_b)$")
    ax2.set(
        xlabel="x (mm)",
        ylabel="contact line load (N/m)",
        ylim=(0, 1.6 * share * q0),
        title="what b passes on to a (the support pairs: off scale)",
    )
    for ax in (ax1, ax2):
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "beam_on_beam.png", dpi=120)
    print("picture:", out / "beam_on_beam.png")

# ## Exercises
#
# 1. **Swap the beams.** Put the thin beam below: `r_a, r_b = 2e-3, 3e-3`. Predict the contact
#    line load and the midspan deflection.
#    *Answer:* $q_c = q_0\,EI_a/(EI_a + EI_b) = q_0\cdot 16/97$ = **3.299** N/m, and strand finds
#    **3.299** N/m: the thin beam below takes a sixth of the load. The deflection does not
#    change, **1.068** mm by the closed form and **1.068** mm by strand: the two bend as one.
# 2. **How stiff a bed?** The penalty lets the beams overlap by $q_c/k$. Which $k$ keeps that
#    gap at 1 % of the midspan deflection?
#    *Answer:* $k = q_c / (0.01\,w(L/2))$ = **1.56e6** N/m²; the demo's 1e10 N/m² keeps it
#    below 2e-6 of the deflection.
