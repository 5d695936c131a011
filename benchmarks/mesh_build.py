"""Time to build the Cardinal strand (geometry, pairs, dolfinx mesh, dof blocks of the pairs).

Run: .venv/bin/python benchmarks/mesh_build.py [case.toml] [--repeats N] [--quick]
(default: the built-in Cardinal case, 1 m, 4 mm elements, best of 5; --quick: 0.1 m, once).
Target: under 5 s for Cardinal, 1 m, 4 mm.
"""

import strand  # noqa: F401

# isort: split

import time

from harness import parser, stamp
from mpi4py import MPI

from strand.app.case import load_case
from strand.app.cli import mesh_table
from strand.cable.geometry import build_geometry
from strand.cable.mesh import beam_space, cable_mesh


def main(case_file: str | None = None, repeats: int = 5, settings: list[str] | None = None) -> None:
    print(f"stamp: {stamp()}\n")
    case = load_case(case_file, settings or [])
    rows = []
    for _ in range(repeats):
        t = [time.perf_counter()]
        g = build_geometry(case.cable, case.mesh.length, case.mesh.h_max)
        t.append(time.perf_counter())
        cm = cable_mesh(g, MPI.COMM_WORLD)
        t.append(time.perf_counter())
        cm.pair_blocks(beam_space(cm.mesh))
        t.append(time.perf_counter())
        rows.append([t[i + 1] - t[i] for i in range(3)])
    best = [min(c) for c in zip(*rows, strict=True)]
    print(mesh_table(g))
    print()
    print(f"best of {repeats}           time (s)")
    print(f"geometry + pairs (numpy)  {best[0]:.4f}")
    print(f"dolfinx mesh + tags       {best[1]:.4f}")
    print(f"space + pair dof blocks   {best[2]:.4f}")
    print(f"total                     {sum(best):.4f}   (target < 5 s)")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "0.1 m, built once")
    cli.add_argument("case", nargs="?", help="a case file (default: the built-in Cardinal case)")
    cli.add_argument("--repeats", type=int, default=5, help="builds, the best kept (default 5)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    if args.quick:
        main(args.case, 1, ["mesh.length=0.1"])
    else:
        main(args.case, args.repeats)
