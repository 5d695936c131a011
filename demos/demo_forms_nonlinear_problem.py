# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # The beam forms with dolfinx's own `NonlinearProblem`
#
# `forms` is plain UFL: its Reissner beam needs nothing of strand's solver. This demo bends a
# cantilever far into the nonlinear range with `dolfinx.fem.petsc.NonlinearProblem` and shows the
# PETSc options it needs, and why; then the same with strand's `NonlinearProblem`, which extends
# dolfinx's. The reference is the elastica: a cantilever under a dead tip load $P$ with
# $PL^2/EI = 10$ has its tip at $v/L = 0.81061$ (Mattiasson, IJNME 17, 1981). Units: SI.
#
# The script runs on any number of processes (`mpirun -n 2 python
# demo_forms_nonlinear_problem.py`) with the same result: process 0 prints and draws.

# +
import strand  # noqa: F401  (the wheel's MPI library must be loaded before dolfinx; see README)

# isort: split

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import ufl
from dolfinx import fem, mesh
from dolfinx.fem.petsc import NonlinearProblem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand import (
    NewtonOptions,
    NodalLoad,
    beam_space,
    dof_values,
    locate_nodes,
    straight_beam_mesh,
)
from strand import NonlinearProblem as StrandNonlinearProblem

comm = MPI.COMM_WORLD


def say(*text):
    """``print`` on process 0 only."""
    if comm.rank == 0:
        print(*text)


# -

# ## The cantilever
#
# 40 cells along $x$, clamped at $x = 0$, a fixed-direction force $P e_y$ at the tip. The force
# does not depend on $w$, so the Jacobian is the beam's alone and we give it as `J`: the same form
# as every strand beam's tangent, so FFCx's cache serves both with one compiled kernel (the
# default, the derivative of `F`, carries the force's zero derivative and compiles its own).
# The nodes are read by their position: `dof_values(w, points)` gives the unknowns of the nodes
# at `points` on every process, each read where it is owned.

L, n, d, E, nu = 1.0, 40, 0.01, 210e9, 0.3
domain = straight_beam_mesh(comm, L, n)
V = beam_space(domain)
w = fem.Function(V)
section = CircularSection(d, E, nu)
beam = ReissnerBeam(w, section)
tip = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], L))
root = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], 0.0))
ds = ufl.Measure("ds", domain, subdomain_data=mesh.meshtags(domain, 0, tip, np.ones_like(tip)))
force = fem.Constant(domain, np.zeros(3))
v = ufl.TestFunction(V)
F = beam.residual(v) - ufl.dot(force, ufl.as_vector([v[0], v[1], v[2]])) * ds(1)
J = ufl.derivative(beam.residual(v), w)
bc = fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, root), V)
P = 10 * E * np.pi * d**4 / 64 / L**2
x0 = np.c_[np.linspace(0.0, L, n + 1), np.zeros((n + 1, 2))]  # the nodes, root to tip
lu = {"ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"}

# ## PETSc's defaults: no convergence, and no error
#
# By default SNES globalises Newton with a backtracking line search (`bt`): it accepts a step
# only if it lowers $\|F\|$. A beam's residual rises by orders of magnitude in Newton's first
# iterations: the first correction is the linear solution, whose large tip deflection stretches the
# beam (axial strain $\sim (v/L)^2/2$, times $EA$). So `bt` shrinks every step to a sliver, and
# after `snes_max_it` iterations the solve stops where it is, without raising.

default = NonlinearProblem(F, w, bcs=[bc], J=J, petsc_options_prefix="default_", petsc_options=lu)
force.value = [0.0, P, 0.0]
default.solve()
reason, its = default.solver.getConvergedReason(), default.solver.getIterationNumber()
v_default = dof_values(w, x0[-1])[0, 1] / L
say(f"default options: reason {reason}, {its} iterations, tip at v/L = {v_default:.4f}")
assert reason < 0  # what every script must check (or ask PETSc to raise, below)

# ## The options that work
#
# * `snes_linesearch_type: basic`: full Newton steps, which converge quadratically once close;
# * load increments, so that each solve starts close (here ten equal ones);
# * `snes_divergence_tolerance`: PETSc stops Newton when $\|F\|$ exceeds $10^4$ times its initial
#   value, which a beam's first iterations do on their way to converge; we raise it;
# * `snes_error_if_not_converged`: a solve that fails raises instead of returning quietly.

w.x.array[:] = 0.0
options = {
    **lu,
    "snes_linesearch_type": "basic",
    "snes_divergence_tolerance": 1e300,
    "snes_atol": 1e-8,
    "snes_rtol": 1e-10,
    "snes_error_if_not_converged": True,
}
problem = NonlinearProblem(F, w, bcs=[bc], J=J, petsc_options_prefix="beam_", petsc_options=options)
shapes = []
for k in range(1, 11):
    force.value = [0.0, k / 10 * P, 0.0]
    problem.solve()
    u = dof_values(w, x0)
    shapes.append(x0[:, :2] + u[:, :2])
    say(f"P = {k / 10:.1f} × 10 EI/L²: {problem.solver.getIterationNumber()} Newton iterations")
v_tip, u_tip = u[-1, 1] / L, u[-1, 0] / L
say(f"tip: v/L = {v_tip:.5f} (elastica 0.81061), (L − x)/L = {-u_tip:.5f} (elastica 0.55500)")
assert abs(v_tip - 0.81061) < 1e-3 and abs(-u_tip - 0.55500) < 1e-3

# ## The same with strand's `NonlinearProblem`
#
# `strand.solver.NonlinearProblem` is this class, extended: the same arguments
# (`petsc_options_prefix`, `petsc_options`), the same `problem.solver` SNES, plus terms assembled
# outside UFL (contact pairs, nodal loads: here the tip force as a `NodalLoad`, which loads its
# node once, on the process owning it, whatever ghosts it is given), strand's
# convergence tests (`NewtonOptions`) and the options above as its defaults. Its `solve` returns
# the outcome (converged in physical terms, iterations, residual norms) rather than raising. Its
# stall test, which stops an attempt whose residual has not halved in two iterations, is off by
# default (`NewtonOptions.stall_after = None`); strand's own runs switch it on from the 4th
# iteration (`StrandProblem`, `[steps] stall`). Here it would stop the first two steps, whose
# residual rises for several iterations before Newton's quadratic phase, so it stays off.

w_s = fem.Function(V)
tip_node = locate_nodes(V, x0[-1])  # on the processes holding it, none elsewhere
tip_load = NodalLoad(tip_node, [[0.0, P, 0.0, 0.0, 0.0, 0.0]] * len(tip_node))
newton = NewtonOptions(atol=1e-8, rtol=1e-10)
strand_problem = StrandNonlinearProblem(
    ReissnerBeam(w_s, section).residual(),
    w_s,
    [bc],
    terms=[tip_load],
    options=newton,
    petsc_options_prefix="strand_beam_",
)
snes = strand_problem.solver
say(f"strand's SNES: {snes.getType()}, options prefix {snes.getOptionsPrefix()}")
for k in range(1, 11):
    tip_load.factor = k / 10
    result = strand_problem.solve()
    assert result.converged, result.reason
v_strand = dof_values(w_s, x0[-1])[0, 1] / L
say(f"strand's NonlinearProblem: last step {result.iterations} iterations, v/L = {v_strand:.5f}")
say(f"|v_strand - v_dolfinx| / L = {abs(v_strand - v_tip):.1e}")
assert abs(v_strand - v_tip) < 1e-12
strand_problem.destroy()

# ## Picture
#
# The ten deformed shapes, drawn by process 0 (every process holds them: `dof_values`).

if comm.rank == 0:
    out = Path("results/demo_forms_nonlinear_problem")
    out.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(5, 4.5))
    for k, xy in enumerate(shapes, start=1):
        ax.plot(xy[:, 0], xy[:, 1], "-", color=plt.cm.viridis(k / 10), lw=1)
    ax.plot([1 - 0.555], [0.81061], "kx", ms=8, label="elastica, PL²/EI = 10")
    ax.plot(x0[:, 0], x0[:, 1], "k:", lw=1)
    ax.set(xlabel="x (m)", ylabel="y (m)", aspect="equal", title="ten load steps")
    ax.legend(loc="lower right")
    fig.savefig(out / "cantilever.png", dpi=120, bbox_inches="tight")
    print("picture:", out / "cantilever.png")

# ## Exercises
#
# 1. **A smaller load.** Set $PL^2/EI = 1$ (`P = 1 * E * ...`, and drop the two checks against
#    the values at 10). How far below linear theory's $v/L = PL^2/3EI$ is the tip?
#    *Answer:* $v/L$ = **0.3017** (Mattiasson's 0.30172), **9.5** % below $1/3$: even at
#    $PL^2/EI = 1$ the shortening of the lever arm counts.
# 2. **Coarser.** Use 20 cells instead of 40 (`n`), back at $PL^2/EI = 10$. How much does the tip
#    move?
#    *Answer:* $v/L$ = **0.81056**, 5e-5 below the 40 cells' 0.81061: two-node cells with one
#    Gauss point are slightly stiff in bending, by $O(1/n^2)$.
