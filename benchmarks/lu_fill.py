"""What same-layer contact does to the LU: Cardinal's tangent pattern factorised by MUMPS.

Run: .venv/bin/python benchmarks/lu_fill.py [length_m] [--quick]   (default 1.0; --quick: 0.05)

For the strand of the default case (Cardinal, h_max 4 mm) the Jacobian's sparsity pattern (the
beam forms' extended by the pair stencils, ``strand.solver.terms.create_extended_matrix``) with:
no same-layer pairs; the same-layer pairs as built (node a against the segment b₀b₁ of the
neighbour that faces it); as a variant not taken, node a against the neighbour's node nearest to
the facing point; and the mesh with facing stations and its two-node pairs
(``same_layer_stencil = "facing"``: more nodes, its own pattern). Each pattern is factorised with MUMPS's PORD, AMF and METIS
orderings on diagonally dominant values (``strand.solver.ordering``: the count is the pattern's
alone). Prints the matrix's entries, MUMPS's operations per LU (RINFOG(3)) and factor entries
(INFOG(29)), and, per same-layer pair, how far its facing point lies from the nearest node of the
neighbour (what the node-to-node variant would move it by).
"""

import strand  # noqa: F401

# isort: split

import time

import numpy as np
from harness import parser, stamp, table

from strand.app.case import load_case
from strand.cable.geometry import build_geometry
from strand.model.problem import StrandProblem
from strand.model.same_layer import same_layer_pairs
from strand.setups import SaddleTest
from strand.solver.ordering import ORDERINGS, pattern_lu
from strand.solver.terms import create_extended_matrix


def main(length: float = 1.0) -> None:
    case = load_case(None, [f"mesh.length={length}", 'contact.same_layer="packed"'])
    geometry = build_geometry(case.cable, length, case.mesh.h_max)
    problem = StrandProblem(geometry, case.contact, setup=SaddleTest)
    J = problem.solver._J  # the compiled Jacobian form
    crossings = [t.stencils for t in problem.model.contact]
    segments = [np.asarray(t.stencils) for t in problem.model.same_layer]
    nearest = []
    for t, st in zip(problem.model.same_layer, segments, strict=True):
        xi = t.c[:, 2]  # the facing point's weight on b₁
        nearest.append(np.column_stack([st[:, 0], np.where(xi < 0.5, st[:, 1], st[:, 2])]))
    print(
        f"# LU fill of Cardinal's tangent pattern, L = {length:g} m, "
        f"{6 * len(geometry.points)} unknowns\n\nstamp: {stamp()}\n"
    )
    columns = [
        "same-layer pairs",
        "matrix entries",
        "ordering",
        "LU operations",
        "factor entries",
        "s",
    ]
    print(table([], columns))
    facing_case = load_case(
        None,
        [
            f"mesh.length={length}",
            'contact.same_layer="packed"',
            'contact.same_layer_stencil="facing"',
        ],
    )
    facing_geometry = build_geometry(case.cable, length, case.mesh.h_max, facing=True)
    facing = StrandProblem(facing_geometry, facing_case.contact, setup=SaddleTest)
    facing_stencils = [t.stencils for t in facing.model.contact]
    facing_stencils += [np.asarray(t.stencils) for t in facing.model.same_layer]
    variants = {
        "off": (J, crossings),
        "node to segment (built)": (J, crossings + segments),
        "node to nearest node (not built)": (J, crossings + nearest),
        f"facing stations ({6 * len(facing_geometry.points)} unknowns)": (
            facing.solver._J,
            facing_stencils,
        ),
    }
    for name, (form, stencils) in variants.items():
        A = create_extended_matrix(form, stencils)
        entries = A.getInfo()["nz_used"]
        for ordering in ("pord", "amf", "scotch", "metis", "qamd"):
            t0 = time.perf_counter()
            flops, factor = pattern_lu(A, ORDERINGS[ordering])
            seconds = time.perf_counter() - t0
            cells = [
                name,
                f"{entries:.3g}",
                ordering.upper(),
                f"{flops:.3g}",
                f"{factor:.3g}",
                f"{seconds:.1f}",
            ]
            print(table([cells], columns, head=False), flush=True)
        A.destroy()
    pairs = same_layer_pairs(geometry, "packed")
    h = np.linalg.norm(geometry.points[pairs.b1] - geometry.points[pairs.b0], axis=1)
    offset = np.minimum(pairs.weight, 1 - pairs.weight) * h
    cells = []
    for layer in np.unique(pairs.layer):
        m = pairs.layer == layer
        cells.append(
            [
                layer,
                m.sum(),
                f"{h[m].mean() * 1e3:.2f}",
                f"{np.median(offset[m]) * 1e3:.2f}, {offset[m].max() * 1e3:.2f}",
            ]
        )
    print(
        "\n"
        + table(
            cells,
            [
                "layer",
                "same-layer pairs",
                "element (mm)",
                "facing point to nearest node: median, max (mm)",
            ],
        )
    )
    problem.solver.destroy()
    facing.solver.destroy()


if __name__ == "__main__":
    cli = parser(__doc__, "0.05 m")
    cli.add_argument("length", nargs="?", type=float, default=1.0, help="m (default 1)")
    args = cli.parse_args()
    main(0.05 if args.quick else args.length)
