"""A first script with strand's library: two steel wires crossing at right angles, both clamped
at their ends, the upper one pushed down at the crossing by a point load P. Each wire carries
about half of it: the contact force is P / (2 + k/K_N), k a wire's midspan stiffness and K_N the
contact's. Runs on any number of processes: ``python first_script.py`` or
``mpirun -n 2 python first_script.py``. docs/user-guide/library.md explains it. Units: SI."""

# 1. A mesh of two wires
import strand  # noqa: F401  (first: loads the dolfinx wheel's MPI library)

# isort: split

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand import (
    ElasticSlip,
    LoadStepper,
    NodalLoad,
    NonlinearProblem,
    PenaltyLaw,
    beam_space,
    candidate_pairs,
    candidate_stencils,
    contact_terms,
    locate_nodes,
    polyline_mesh,
    slab_partitioner,
)

comm = MPI.COMM_WORLD
r, L, n = 1.5e-3, 0.2, 40  # wire radius, span (m), cells per wire
s = np.linspace(-L / 2, L / 2, n + 1)
x_a = np.c_[s, 0 * s, 0 * s]  # wire a along x
x_b = np.c_[0 * s, s, 0 * s + 2 * r]  # wire b along y, resting on a at the origin
points = np.vstack([x_a, x_b])
cells = np.vstack([np.c_[0:n, 1 : n + 1], np.c_[0:n, 1 : n + 1] + n + 1])
stencils = candidate_stencils(points, cells, range(n + 1), range(n + 1, 2 * n + 2), r, r, 1e-4)
domain = polyline_mesh(comm, points, cells, slab_partitioner(points[:, 0], cells, [stencils]))
V = beam_space(domain)  # per node: displacement u and rotation θ, 6 values
w = fem.Function(V)
section = CircularSection(2 * r, 200e9, 0.3)
beam = ReissnerBeam(w, section)

# 2. The nodes
nodes_a, nodes_b = locate_nodes(V, x_a), locate_nodes(V, x_b)
ends = locate_nodes(V, [x_a[0], x_a[-1], x_b[0], x_b[-1]])
top = locate_nodes(V, x_b[n // 2])  # wire b's midpoint, above the crossing

# 3. Supports, load and contact
P = 1.0  # N
bcs = [fem.dirichletbc(np.zeros(6), ends, V)]  # the four ends clamped
load = NodalLoad(top, [[0.0, 0.0, -P, 0.0, 0.0, 0.0]] * len(top))
pairs = candidate_pairs(V, nodes_a, nodes_b, r, r, reach=1e-4)
K_N = 1e8  # N/m
contact = contact_terms(pairs, PenaltyLaw(K_N), ElasticSlip(mu=0.3, g_lim=5e-6))
problem = NonlinearProblem(beam.residual(), w, bcs, terms=[contact, load])

# 4. Load steps
stepper = LoadStepper(problem, first_step=0.25, min_step=1e-3)
steps = stepper.ramp(lambda factor: setattr(load, "factor", factor), 0.0, 1.0)

# 5. Results, on every rank
p = comm.allreduce(float(contact.state.force.sum()))  # the pair is on one rank
owned = top[top < V.dofmap.index_map.size_local]  # the node is owned by one rank
deflection = comm.allreduce(float(-w.x.array.reshape(-1, 6)[owned, 2].sum()))
k = 1 / (L**3 / (192 * section.EI) + L / (4 * section.GA))  # clamped span, central force
if comm.rank == 0:
    print(f"{len(steps)} load steps, {sum(rec.iterations for rec in steps)} Newton iterations")
    print(f"contact force p = {p:.10g} N; closed form P/(2 + k/K_N) = {P / (2 + k / K_N):.10g} N")
    print(
        f"deflection under the load = {deflection:.10g} m; closed form (P - p)/k = "
        f"{(P - p) / k:.10g} m"
    )
assert abs(p / (P / (2 + k / K_N)) - 1) < 1e-6  # the two wires share the load
assert abs(deflection / ((P - p) / k) - 1) < 5e-3  # two-node cells: stiff by O(1/n²)
