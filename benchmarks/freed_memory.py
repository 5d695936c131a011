"""Freed memory kept for the next factorisation (``strand.solver.keep_freed_memory``) against
glibc's defaults, on the main job's window, measured in one run.

Run: .venv/bin/python benchmarks/freed_memory.py [--quick] [--ranks N] [--length L]
(--quick: 0.05 m on 1 rank, a smoke test of the script; default: 0.3 m on 2 ranks)

Each variant runs the default case (Cardinal, packed layers, 40 kN, first leg to +4.3 kN; no
fields, figures, checkpoints or histories) on a shortened piece, in a process of its own, one
after the other: glibc's defaults (``STRAND_KEEP_FREED_MEMORY=0``) and strand's (blocks up to
1 GiB served from the heap, which is not trimmed). Prints per variant: wall time of the run,
steps, Newton iterations, LU factorisations, time per iteration, minor page faults (all ranks)
and peak memory (largest rank); then the largest difference of the runs' midspan deflection.
"""

import strand  # noqa: F401

# isort: split

import argparse
import os
import resource
import time
from pathlib import Path

from harness import parser, peak_mib, print_result, run_variants, stamp, table
from window import WINDOW  # the main job's window (this folder, the script's first path)

ROOT = Path("results/benchmark_freed_memory")
#: name: the environment's STRAND_KEEP_FREED_MEMORY
VARIANTS = {"glibc defaults": "0", "freed memory kept": "1"}


def run_variant(name: str, length: float) -> dict:
    """Run one variant in this process; returns its measurements."""
    from mpi4py import MPI
    from petsc4py import PETSc

    from strand.app.case import load_case
    from strand.app.run import run_case

    PETSc.Log.begin()
    case = load_case(None, [*WINDOW, f"mesh.length={length}"])
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.perf_counter()
    with open(os.devnull, "w") as sink:
        result = run_case(case, ROOT / name.replace(" ", "_"), stream=sink, overwrite=True)
    seconds = time.perf_counter() - t0
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults
    return {
        "seconds": seconds,
        "steps": len(result.steps),
        "iterations": result.iterations,
        "lu": PETSc.Log.Event("MatLUFactorNum").getPerfInfo()["count"],
        "faults": MPI.COMM_WORLD.allreduce(faults),
        "peak_mib": peak_mib(MPI.COMM_WORLD),
        "deflection": [s.state.deflection for s in result.steps],
        "failure": result.failure,
    }


def main(ranks: int, length: float, quick: bool) -> None:
    print(f"stamp: {stamp()}")
    args = ["--length", str(length)] + (["--quick"] if quick else [])
    rows = run_variants(
        __file__,
        list(VARIANTS),
        args,
        ranks,
        lambda n: {**os.environ, "STRAND_KEEP_FREED_MEMORY": VARIANTS[n]},
    )
    print(f"\nthe default case at {length:g} m, tension and the first leg, {ranks} rank(s)")
    columns = ["variant", "time (s)", "steps", "its", "LUs", "s/it", "page faults", "peak MiB"]
    print(
        table(
            [
                [
                    name,
                    f"{r['seconds']:.1f}" + (" FAILED" if r["failure"] else ""),
                    r["steps"],
                    r["iterations"],
                    r["lu"],
                    f"{r['seconds'] / max(r['iterations'], 1):.3f}",
                    r["faults"],
                    f"{r['peak_mib']:.0f}",
                ]
                for name, r in rows.items()
            ],
            columns,
            plain=True,
        )
    )
    a, b = (rows[n]["deflection"] for n in VARIANTS)
    same = len(a) == len(b)
    gap = max((abs(x - y) for x, y in zip(a, b, strict=True)), default=0.0) if same else None
    print(
        "midspan deflections: "
        + ("different step counts" if gap is None else f"largest difference {gap:.3g} m")
    )


if __name__ == "__main__":
    cli = parser(__doc__, "0.05 m on 1 rank")
    cli.add_argument("--ranks", type=int, default=2, help="MPI ranks per variant (default 2)")
    cli.add_argument("--length", type=float, default=0.3, help="m (default 0.3)")
    cli.add_argument("--one", help=argparse.SUPPRESS)  # a variant's own process
    args = cli.parse_args()
    length = 0.05 if args.quick else args.length
    if args.one:
        from mpi4py import MPI

        print_result(run_variant(args.one, length), MPI.COMM_WORLD)
    else:
        main(1 if args.quick else args.ranks, length, args.quick)
