"""Cost of the beam forms: JIT time and one Newton iteration on a 10,000-element beam.

Run: .venv/bin/python benchmarks/beam_newton.py [n_cells] [--quick]   (default 10,000 cells;
--quick: 100; set XDG_CACHE_HOME to a fresh folder to measure a cold JIT). Prints a table: time,
Newton iterations, peak memory.
"""

import strand  # noqa: F401

# isort: split

import time

import numpy as np
import ufl
from dolfinx import fem, mesh
from harness import parser, peak_mib, stamp, table
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand.cable.mesh import beam_space, input_to_block, polyline_mesh
from strand.solver import NodalLoad, NonlinearProblem

QUICK_CELLS = 100


def main(n_cells: int = 10_000) -> None:
    print(f"stamp: {stamp()}\n")
    # a helical wire of layer 2 of Cardinal, 4 mm cells: n_cells cells
    r, alpha, h = 6.67e-3, np.radians(12.0), 4e-3
    s = np.arange(n_cells + 1) * h * np.cos(alpha)
    phi = np.tan(alpha) / r * s
    x = np.column_stack([r * np.cos(phi), r * np.sin(phi), s])
    cells = np.column_stack([np.arange(n_cells), np.arange(1, n_cells + 1)])
    domain = polyline_mesh(MPI.COMM_WORLD, x, cells)
    V = beam_space(domain)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(3.32e-3, 65e9, 0.33))
    F = beam.residual()

    t0 = time.perf_counter()
    fem.form(F)
    t_F = time.perf_counter() - t0
    t0 = time.perf_counter()
    fem.form(ufl.derivative(F, w))
    t_J = time.perf_counter() - t0

    # clamped root; the tip may only move along the strand axis (a wire in a rigid end fitting)
    root = mesh.locate_entities_boundary(domain, 0, lambda p: np.isclose(p[2], 0.0))
    tip = mesh.locate_entities_boundary(domain, 0, lambda p: np.isclose(p[2], x[-1, 2]))
    bcs = [fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, root), V)]
    for i in (0, 1, 3, 4, 5):
        dofs = fem.locate_dofs_topological(V.sub(i), 0, tip)
        bcs.append(fem.dirichletbc(0.0, dofs, V.sub(i)))
    load = NodalLoad([input_to_block(V)[-1]], [[0.0, 0.0, 20.0, 0.0, 0.0, 0.0]], 1.0)
    problem = NonlinearProblem(F, w, bcs, terms=[load])
    t0 = time.perf_counter()
    result = problem.solve()
    total = time.perf_counter() - t0
    its = max(result.iterations, 1)
    tm = problem.timings
    lu = total - tm["residual"] - tm["jacobian"]
    peak = peak_mib()
    cells = [
        ("cells / unknowns", f"{n_cells} / {V.dofmap.index_map.size_global * 6}"),
        ("JIT residual F (s)", f"{t_F:.2f}"),
        ("JIT Jacobian J (s)", f"{t_J:.2f}"),
        ("Newton iterations (20 N pull)", f"{result.iterations} ({result.reason})"),
        ("time per Newton iteration (s)", f"{total / its:.3f}"),
        ("  residual assembly per iteration (s)", f"{tm['residual'] / (its + 1):.3f}"),
        ("  Jacobian assembly per iteration (s)", f"{tm['jacobian'] / its:.3f}"),
        ("  LU factorisation + solve per iteration (s)", f"{lu / its:.3f}"),
        ("peak memory (MiB)", f"{peak:.0f}"),
    ]
    print(table(cells, ["measure", "value"], plain=True))


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, f"{QUICK_CELLS} cells")
    cli.add_argument("n_cells", nargs="?", type=int, default=10_000, help="default 10,000")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    main(QUICK_CELLS if args.quick else args.n_cells)
