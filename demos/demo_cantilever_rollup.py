# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # Rolling a cantilever into a circle
#
# This demo shows how to build a geometrically exact (Simo-Reissner) beam with the reusable UFL
# forms of `forms/` and solve it with strand's Newton load stepping. A straight cantilever of
# length $L$ carries an end moment $M$ about $e_z$. Pure bending gives a constant curvature
# $\kappa = M/EI$, so at $M = 2\pi EI/L$ the beam closes into a full circle and its tip comes back to
# the clamped root: a classical test of finite rotations that no small-rotation model can pass.
#
# Units are SI (m, N, Pa, rad). The script runs on any number of processes, as dolfinx's demos
# do (`mpirun -n 2 python demo_cantilever_rollup.py`), with the same result: process 0 prints
# and draws.

# +
import strand  # noqa: F401  (loads the dolfinx wheel's libraries before mpi4py/petsc4py)

# isort: split

from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam, moment_virtual_work
from strand import (
    FieldWriter,
    LoadStepper,
    NonlinearProblem,
    beam_space,
    dof_values,
    offscreen_plotter,
    straight_beam_mesh,
    tubes,
)
from strand.cable.pictures import save

comm = MPI.COMM_WORLD

# -

# ## Mesh and unknowns
#
# The beam is a 1D mesh embedded in 3D. Each node carries six unknowns in one blocked P1 space: the
# displacement $u$ and the rotation vector $\theta$ of the cross-section.

L, n_cells = 1.0, 40
domain = straight_beam_mesh(comm, L, n_cells, direction=(1.0, 0.0, 0.0))
V = beam_space(domain)
w = fem.Function(V, name="w")

# ## The beam forms
#
# `CircularSection` turns a diameter, Young's modulus and Poisson ratio into $EA$, $\kappa GA$,
# $GJ$ and $EI$ (any of them may be a cell-wise `Function`). `ReissnerBeam` builds, at the one Gauss
# point of each cell, the strains in the section frame $\Lambda_0 = [t, e_2, e_3]$:
#
# $$\Gamma = \Lambda_0^T(\Lambda_m^T(t + u') - t), \qquad K = \Lambda_0^T \log(\Lambda_a^T\Lambda_b)/h,$$
#
# with $\Lambda_a, \Lambda_b$ the nodal rotations and $\Lambda_m$ their midpoint. Using relative
# rotations makes the strains objective. The residual is the derivative of the strain energy.

section = CircularSection(d=0.01, E=210e9, nu=0.3)
beam = ReissnerBeam(w, section)
EI = 210e9 * np.pi * 0.01**4 / 64

# The end moment is a fixed-direction (spatial) moment $m$; its virtual work on the rotation vector
# is $m \cdot T(\theta)\,\delta\theta$, which `moment_virtual_work` provides. It acts on the tip
# vertex, which is a boundary "facet" of the 1D mesh, so `ds` integrates there.

tip = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], L))
root = mesh.locate_entities_boundary(domain, 0, lambda x: np.isclose(x[0], 0.0))
ds = ufl.Measure("ds", domain, subdomain_data=mesh.meshtags(domain, 0, tip, np.ones_like(tip)))
moment = fem.Constant(domain, np.zeros(3))
v = ufl.TestFunction(V)
v_theta = ufl.as_vector([v[3], v[4], v[5]])
F = beam.residual(v) - moment_virtual_work(moment, beam.theta, v_theta) * ds(1)
clamp = fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, root), V)

# ## Newton load stepping
#
# strand's `NonlinearProblem` (dolfinx's, extended) is solved by PETSc SNES (Newton, MUMPS LU)
# with the consistent tangent from `ufl.derivative`. `LoadStepper` raises the load factor, growing
# the step after easy solves and halving it after failures; results are written after every
# converged step (`FieldWriter` writes collectively, as dolfinx's `XDMFFile` does).

out = Path("results/demo_cantilever_rollup")
problem = NonlinearProblem(F, w, [clamp])
M_full = 2 * np.pi * EI / L
with FieldWriter(out / "rollup.xdmf", beam) as writer:

    def report(step):
        writer.write(step.load)
        if comm.rank == 0:
            print(f"M/M_full = {step.load:.3f}: {step.iterations} Newton iterations")

    stepper = LoadStepper(problem, first_step=0.1, min_step=1e-3, max_step=0.1, on_step=report)
    stepper.ramp(lambda lam: setattr(moment, "value", [0.0, 0.0, lam * M_full]), 0.0, 1.0)

# The tip is back at the root, and the tip section has turned by $2\pi$. On several processes
# the tip node lives on one of them (and as a ghost on its neighbour): `dof_values` reads the
# unknowns of the nodes at given points where each is owned and gives them to every process.

u_tip = dof_values(w, [L, 0.0, 0.0])[0]
error = np.linalg.norm(u_tip[:3] + [L, 0.0, 0.0]) / L
if comm.rank == 0:
    print(f"|u_tip + L e_x| / L = {error:.2e}, tip rotation = {u_tip[5] / np.pi:.6f} π")
assert error < 1e-3

# ## Picture
#
# The deformed beam as a tube, coloured by the bending moment (constant, as pure bending requires).
# `tubes` is collective: every process gives its part of the beam, process 0 gets the whole tube
# and draws it.

U = fem.functionspace(domain, ("Lagrange", 1, (3,)))
u = fem.Function(U)
u.interpolate(fem.Expression(beam.u, U.element.interpolation_points))
M3 = fem.Function(fem.functionspace(domain, ("DG", 0)))
M3.interpolate(fem.Expression(beam.M[2], M3.function_space.element.interpolation_points))
tube = tubes(U, u.x.array.reshape(-1, 3), M3.x.array, "M3 (N m)", radius=0.01)
if comm.rank == 0:
    plotter = offscreen_plotter(window_size=(800, 600))
    plotter.add_mesh(tube, cmap="viridis", clim=[0.0, 1.2 * M_full])
    plotter.view_xy()
    print("picture:", save(plotter, out / "rollup.png"))

# ## Exercises
#
# 1. **Half a circle.** Stop the ramp at half the moment (`stepper.ramp(..., 0.0, 0.5)`, and drop
#    the check that the tip is back at the root). Predict where the tip is before running.
#    *Answer:* $\kappa L = \pi$: the beam is a half circle of diameter $2L/\pi$, its tip right
#    above the root ($x$ = **0.000 m**) at $y = 2L/\pi$ = **0.637 m**, pointing back along
#    $-e_x$.
# 2. **One and a half turns.** Ramp to $1.5\,M_{full}$. Where is the tip, and by how much has its
#    section turned? (The rotation vector is total, not wrapped to $(-\pi, \pi]$: neighbouring
#    nodes only need to differ by less than $\pi$.)
#    *Answer:* $\kappa L = 3\pi$, so $y = (1 - \cos 3\pi)/\kappa = 2L/3\pi$ = **0.212 m** above
#    the root, and $\theta_z$ = **3.000** $\pi$.
