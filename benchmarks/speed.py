"""The default case with yesterday's solver settings beside today's, measured in one run.

Run: .venv/bin/python benchmarks/speed.py [--quick] [variant …]   (--quick: 0.05 m to +0.5 kN;
no variant named: those of DEFAULT_RUN)

Every variant runs the whole default case (Cardinal, 1 m, 40 kN, saddle cycle to ±4.3 kN, every
output) in a process of its own, one after the other, so that each has the machine and its own
peak memory. Prints per variant: wall time, converged steps, Newton iterations in converged steps
and in failed attempts, LU factorisations, time per LU, time in outputs, peak memory (of the
largest rank), and the outputs' time by recorder; then each variant's results against the
first's at the programme's turning points (end of tension, the two peaks, the two returns to
zero): the largest difference in midspan deflection and in end displacement (µm), and in the
axial force of any element relative to the largest (axial_forces.csv); and, when it is among the
variants, against the run with every load step halved: the load-step error of each variant.
The issue's bar for "same results": 0.1 µm and 1e-4.
"""

import strand  # noqa: F401

# isort: split

import argparse
import os
import time
from pathlib import Path

import numpy as np
from harness import parser, peak_mib, print_result, run_variants, stamp, table

ROOT = Path("results/benchmark_speed")
QUICK = ["mesh.length=0.05", "load.lateral=500", "load.cycle=[1.0]"]  # a smoke test of the script

#: Newton with full steps, the default before the critical-point line search
BASIC = ['steps.line_search="basic"']
#: name: (case settings, MPI ranks)
VARIANTS = {
    "before: no stall test, full steps": (["steps.stall=false", "steps.balance=0", *BASIC], 1),
    "stall test, full steps": (["steps.balance=0", *BASIC], 1),
    "stall + balance, full steps": (BASIC, 1),
    "default: cp line search": ([], 1),
    "default on 2 ranks": ([], 2),
    "first tension step 10 kN": (["steps.tension=10e3"], 1),
    # cheaper iterations (docs/theory.md §6): GMRES on a kept LU, L-BFGS on each solve's first
    "reuse LU": (['steps.iteration="reuse_lu"'], 1),
    "L-BFGS": (['steps.iteration="lbfgs"'], 1),
    # not speed settings: how far the results move with the load path (friction remembers it)
    "default, lateral steps x2": (["steps.lateral=500", "steps.lateral_max=800"], 1),
    "default, steps halved": (
        ["steps.tension=500", "steps.lateral=125", "steps.lateral_max=200"],
        1,
    ),
}
#: what a run without named variants measures: the line search's gain, the second rank's, and
#: the load-step error of both line searches
DEFAULT_RUN = [
    "stall + balance, full steps",
    "default: cp line search",
    "default on 2 ranks",
    "default, steps halved",
]
#: the variant whose results stand in for the load-step converged ones
HALVED = "default, steps halved"


def slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name).strip("_")


def run_variant(name: str, quick: bool) -> dict:
    """Run one variant in this process; returns its measurements."""
    from mpi4py import MPI
    from petsc4py import PETSc

    from strand.app.case import load_case
    from strand.app.run import run_case

    PETSc.Log.begin()
    settings = VARIANTS[name][0]
    case = load_case(None, [*settings, *(QUICK if quick else [])])
    t0 = time.perf_counter()
    with open(os.devnull, "w") as sink:
        result = run_case(case, ROOT / slug(name), stream=sink, overwrite=True)
    seconds = time.perf_counter() - t0
    lu = PETSc.Log.Event("MatLUFactorNum").getPerfInfo()
    return {
        "seconds": seconds,
        "steps": len(result.steps),
        "iterations": result.iterations,
        "failed_iterations": result.failed_iterations,
        "cuts": sum(s.cuts for s in result.steps),
        "lu": lu["count"],
        "lu_seconds": lu["time"],
        "output_seconds": result.timings["output"],
        "output_by": result.output_timings,
        "peak_mib": peak_mib(MPI.COMM_WORLD),
        "failure": result.failure,
    }


def turning_points(folder: Path) -> dict[int, dict]:
    """Deflection, end displacement (m) and element axial forces (N, the geometry's element
    order) at the programme's whole times (ends of stages), from steps.csv and axial_forces.csv
    (which every rank count writes alike)."""
    steps = np.genfromtxt(folder / "steps.csv", delimiter=",", names=True)
    whole = np.isclose(steps["time"], np.round(steps["time"]), rtol=0, atol=1e-9)
    out = {
        int(step): {"time": round(t), "deflection": d, "end": e, "N": {}}
        for step, t, d, e in zip(
            steps["step"][whole],
            steps["time"][whole],
            steps["deflection_m"][whole],
            steps["end_displacement_m"][whole],
            strict=True,
        )
    }
    with open(folder / "axial_forces.csv") as f:
        next(f)
        for line in f:
            step = int(line[: line.index(",")])
            if step in out:
                cols = line.split(",")
                out[step]["N"][int(cols[2])] = float(cols[7])
    return {
        row["time"]: dict(row, N=np.array([row["N"][i] for i in sorted(row["N"])]))
        for row in out.values()
    }


def main(names: list[str], quick: bool) -> None:
    print(f"stamp: {stamp()}")
    rows = run_variants(__file__, names, ["--quick"] if quick else [], lambda n: VARIANTS[n][1])
    columns = [
        "variant",
        "time (s)",
        "steps",
        "its",
        "+failed",
        "LUs",
        "s/LU",
        "s/it",
        "output s",
        "peak MiB",
    ]
    cells = []
    for name, r in rows.items():
        its = r["iterations"] + r["failed_iterations"]
        cells.append(
            [
                name,
                f"{r['seconds']:.0f}",
                r["steps"],
                r["iterations"],
                r["failed_iterations"],
                r["lu"],
                f"{r['lu_seconds'] / max(r['lu'], 1):.2f}",
                f"{r['seconds'] / max(its, 1):.2f}",
                f"{r['output_seconds']:.0f}",
                f"{r['peak_mib']:.0f}",
            ]
        )
    print(table(cells, columns, plain=True))
    for name, r in rows.items():
        if r["failure"]:
            print(f"{name}: FAILED: {r['failure']}")
    for name, r in rows.items():
        by = sorted(r["output_by"].items(), key=lambda kv: -kv[1])
        print(f"outputs of '{name}' (s): " + ", ".join(f"{k} {v:.0f}" for k, v in by))
    compare(names, names[0])
    if HALVED in names[1:]:
        compare(names, HALVED)


def compare(names: list[str], reference: str) -> None:
    """Print every other variant's largest differences from ``reference`` at the turning points."""
    ref = turning_points(ROOT / slug(reference))
    print(
        f"\nresults against '{reference}' at the ends of the programme's stages (t = "
        f"{', '.join(str(t) for t in ref)}):"
    )
    cells = []
    for name in names:
        if name == reference:
            continue
        other = turning_points(ROOT / slug(name))
        d = max(abs(other[t]["deflection"] - ref[t]["deflection"]) for t in ref)
        e = max(abs(other[t]["end"] - ref[t]["end"]) for t in ref)
        n = max(np.abs(other[t]["N"] - ref[t]["N"]).max() / np.abs(ref[t]["N"]).max() for t in ref)
        cells.append([name, f"{1e6 * d:.4f}", f"{1e6 * e:.4f}", f"{n:.1e}"])
    print(table(cells, ["variant", "deflection (µm)", "end (µm)", "axial force"], plain=True))


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "0.05 m to +0.5 kN")
    cli.add_argument(
        "variants", nargs="*", metavar="variant", help="named in VARIANTS (none: DEFAULT_RUN's)"
    )
    cli.add_argument("--one", help=argparse.SUPPRESS)  # a variant's own process
    args = cli.parse_args()
    unknown = [a for a in [*args.variants, *([args.one] if args.one else [])] if a not in VARIANTS]
    if unknown:
        cli.error(f"unknown variant(s) {unknown}; choose from {list(VARIANTS)}")
    if args.one:
        from mpi4py import MPI

        print_result(run_variant(args.one, args.quick), MPI.COMM_WORLD)
    else:
        serial_only("this benchmark (it launches its 2-rank variant itself)")
        main(args.variants or DEFAULT_RUN, args.quick)
