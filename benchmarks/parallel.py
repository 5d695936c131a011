"""Distributed runs: the default Cardinal case on 1 and 2 ranks, and a 4 m span on 2 ranks.

Run: .venv/bin/python benchmarks/parallel.py [--quick]

Each variant is a ``strand run`` in its own process group (``mpirun -n <ranks>`` from the venv:
the dolfinx wheel's mpich), driven by this script as a worker (``--worker``) so that the solver's
own timings come back. The table gives per variant: wall time, steps, Newton iterations, time per
iteration, the LU share of it (MUMPS factorisation and solves: the Newton solves less the
residual and Jacobian callbacks), and the peak memory of every rank; then the largest relative
difference of the 2-rank run's deflections, end displacements and wire axial forces from the
serial run's. ``--quick`` runs 0.05 m (to +0.5 kN, one leg) and 0.1 m instead of 1 m and 4 m:
a smoke test of the script.

The 4 m span runs the tension and the first leg to 1 kN only: its time per iteration and memory
are what a longer span costs, without the whole cycle's time.
"""

import strand  # noqa: F401

# isort: split

import csv
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from harness import parser, peak_mib, stamp, table
from mpi4py import MPI

ROOT = Path("results/benchmark_parallel")
MPIRUN = Path(sys.executable).parent / "mpirun"


#: ``--quick``: the short piece's load, one leg to +0.5 kN
QUICK = ["load.lateral=500", "load.cycle=[1.0]"]


def variants(quick: bool) -> list[tuple[str, int, list[str]]]:
    """(name, MPI ranks, case settings) of each run."""
    short, long = ("0.05", "0.1") if quick else ("1.0", "4.0")
    base = [f"mesh.length={short}", *(QUICK if quick else [])]
    span = [f"mesh.length={long}", "load.lateral=1000.0", "load.cycle=[1.0]"]
    return [
        (f"Cardinal {short} m, 1 rank", 1, base),
        (f"Cardinal {short} m, 2 ranks", 2, base),
        (f"Cardinal {long} m, T + 1 kN, 2 ranks", 2, span),
    ]


def worker(folder: str, settings: list[str]) -> None:
    """One run (under mpirun for several ranks); rank 0 writes ``timings.json``."""
    from strand.app.case import load_case
    from strand.beam.parallel import abort_on_error

    abort_on_error()  # an error on one rank ends both (else the other waits for ever)
    from strand.app.run import run_case

    comm = MPI.COMM_WORLD
    case = load_case(None, [*settings, "output.plots=false"])
    t0 = time.perf_counter()
    with open("/dev/null", "w") as log:
        result = run_case(case, folder, stream=log, overwrite=True)
    total = time.perf_counter() - t0
    peaks = comm.gather(peak_mib(), root=0)
    if comm.rank == 0:
        tm = result.timings
        info = {
            "seconds": total,
            "steps": len(result.steps),
            "iterations": result.iterations,
            "cuts": sum(s.cuts for s in result.steps),
            "solve": tm["solve"],
            "lu": tm["solve"] - tm["residual"] - tm["jacobian"],
            "memory": peaks,
            "failure": result.failure,
        }
        Path(folder, "timings.json").write_text(json.dumps(info))


def _columns(path: Path, names: list[str]) -> np.ndarray:
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return np.array([[float(r[n]) for n in names] for r in rows])


def difference(serial: Path, parallel: Path) -> tuple[float, float]:
    """Largest relative difference of (deflection, end displacement) and of the axial forces."""
    names = ["deflection_m", "end_displacement_m"]
    a, b = _columns(serial / "steps.csv", names), _columns(parallel / "steps.csv", names)
    d = float((np.abs(a - b) / np.abs(a).max(axis=0)).max())
    fa = np.loadtxt(serial / "axial_forces.csv", delimiter=",", skiprows=1, usecols=7)
    fb = np.loadtxt(parallel / "axial_forces.csv", delimiter=",", skiprows=1, usecols=7)
    return d, float(np.abs(fa - fb).max() / np.abs(fa).max())


def main(quick: bool) -> None:
    print(f"stamp: {stamp()}\n")
    rows = []
    for name, ranks, settings in variants(quick):
        folder = ROOT / name.replace(" ", "_").replace(",", "").replace("+", "")
        cmd = [sys.executable, __file__, "--worker", str(folder), *settings]
        if ranks > 1:
            cmd = [str(MPIRUN), "-n", str(ranks), *cmd]
        print(f"running {name} ...", flush=True)
        subprocess.run(cmd, check=True)
        info = json.loads((folder / "timings.json").read_text())
        rows.append((name, ranks, folder, info))
    print()
    cells = []
    for name, _, _, info in rows:
        its = max(info["iterations"], 1)
        memory = " / ".join(f"{m:.0f}" for m in info["memory"])
        cells.append(
            [
                name,
                f"{info['seconds']:.1f}",
                info["steps"],
                info["iterations"],
                info["cuts"],
                f"{info['solve'] / its:.2f}",
                f"{100 * info['lu'] / info['solve']:.0f} %",
                memory,
            ]
        )
    print(
        table(
            cells,
            [
                "variant",
                "time (s)",
                "steps",
                "its",
                "cuts",
                "s/it",
                "LU share",
                "peak memory per rank (MiB)",
            ],
            plain=True,
        )
    )
    for name, _, _, info in rows:
        if info["failure"]:
            print(f"{name}: FAILED: {info['failure']}")
    d, f = difference(rows[0][2], rows[1][2])
    print(
        f"\n2 ranks against 1: deflection and end displacement within {d:.1e} (relative), "
        f"wire axial forces within {f:.1e} (relative to the largest)"
    )
    print(f"2 ranks / 1 rank wall time: {rows[1][3]['seconds'] / rows[0][3]['seconds']:.2f}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--worker"]:  # one run, launched by main
        worker(sys.argv[2], sys.argv[3:])
    else:
        args = parser(__doc__, "0.05 m on 1 and 2 ranks, 0.1 m on 2").parse_args()
        main(args.quick)
