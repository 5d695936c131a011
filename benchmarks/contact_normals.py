"""Compare the three contact normals on Cardinal: convergence, cost and gap accuracy.

Run: .venv/bin/python benchmarks/contact_normals.py [length_m] [P_max_N] [frictionless] [--quick]
(default 1 m, 4300 N; --quick: 0.1 m to 500 N)

Contacts use the seed paper's penalty compliance (compliance = "penalty"), as in the README table.
For each normal (neighbour, director, frozen): 40 kN tension, then the saddle load 0 → P_max. Prints
per normal the Newton iterations per step, step cuts, wall time, time per iteration, midspan
deflection, and the error of the element's gaps against the gaps measured on the deformed
centrelines (rms / max per interface, µm). Add "frictionless" to run without friction.
"""

import strand  # noqa: F401

# isort: split

import time

import numpy as np
from harness import parser, stamp

from strand.cable.description import cardinal
from strand.cable.geometry import build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.model.strand_contact import centreline_gaps
from strand.setups import SaddleTest
from strand.solver import LoadStepFailure, LoadStepper, NewtonOptions


def run(geometry, normal: str, friction: bool, p_max: float) -> dict:
    problem = StrandProblem(
        geometry,
        ContactSettings(normal=normal, friction=friction, compliance="penalty"),
        NewtonOptions(atol=1e-3, max_it=12),
        setup=SaddleTest,
    )
    out = {"normal": normal, "failed": ""}
    t0 = time.perf_counter()
    tension = LoadStepper(problem.solver, 10e3, 500.0)
    lateral = LoadStepper(problem.solver, 250.0, 15.0, max_step=400.0)
    try:
        tension.ramp(problem.setup.set_tension, 0.0, 40e3, "tension")
        lateral.ramp(problem.setup.set_lateral, 0.0, p_max, "lateral")
    except LoadStepFailure as failure:
        out["failed"] = (
            str(failure).split(":")[0]
            + f" at {problem.setup.tension:.0f} N / {problem.setup.lateral:.0f} N"
        )
    out["seconds"] = time.perf_counter() - t0
    out["tension"] = [r.iterations for r in tension.history]
    out["lateral"] = [r.iterations for r in lateral.history]
    out["cuts"] = sum(r.cuts for r in tension.history + lateral.history)
    out["its"] = sum(out["tension"]) + sum(out["lateral"])
    out["deflection"] = problem.setup.midspan_deflection()
    out["P"] = problem.setup.lateral
    x = problem.positions()
    measured = centreline_gaps(geometry, x) - centreline_gaps(geometry, geometry.points)
    error = problem.pair_results().gap - measured
    out["gap_error"] = [
        (np.sqrt(np.mean(error[m] ** 2)), np.abs(error[m]).max())
        for m in (geometry.pairs.interface == i for i in range(4))
    ]
    out["penetration"] = -problem.pair_results().gap.min()
    return out


def main(length: float = 1.0, p_max: float = 4300.0, frictionless: bool = False) -> None:
    print(f"stamp: {stamp()}\n")
    geometry = build_geometry(cardinal(), length, 4e-3)
    results = [
        run(geometry, n, not frictionless, p_max) for n in ("neighbour", "director", "frozen")
    ]
    print(
        f"Cardinal L = {length} m, T = 40 kN, saddle 0 → {p_max:.0f} N, "
        f"{'frictionless' if frictionless else 'friction on'}"
    )
    head = f"{'normal':10s} {'tension its':14s} {'lateral its':34s} {'cuts':>4s} {'time s':>7s}"
    head += f" {'s/it':>5s} {'δ mm':>6s} {'pen µm':>6s}  gap error rms/max µm (0|1 1|2 2|3 3|4)"
    print(head)
    for r in results:
        errors = " ".join(f"{1e6 * a:.2f}/{1e6 * b:.1f}" for a, b in r["gap_error"])
        its = max(r["its"], 1)
        print(
            f"{r['normal']:10s} {str(r['tension']):14s} {str(r['lateral']):34s} {r['cuts']:4d} "
            f"{r['seconds']:7.1f} {r['seconds'] / its:5.2f} {1e3 * r['deflection']:6.2f} "
            f"{1e6 * r['penetration']:6.2f}  {errors}"
        )
        if r["failed"]:
            print(f"{'':10s} FAILED: {r['failed']} (δ above is at the last converged load)")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "0.1 m to 500 N")
    cli.add_argument("length", nargs="?", type=float, default=1.0, help="m (default 1)")
    cli.add_argument("p_max", nargs="?", type=float, default=4300.0, help="N (default 4300)")
    cli.add_argument("frictionless", nargs="?", choices=["frictionless"], help="friction off")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    length, p_max = (0.1, 500.0) if args.quick else (args.length, args.p_max)
    main(length, p_max, args.frictionless is not None)
