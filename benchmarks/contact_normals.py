"""Compare the three contact normals on Cardinal: convergence, cost and gap accuracy.

Run: .venv/bin/python benchmarks/contact_normals.py [length_m] [P_max_N] [frictionless] [--quick]
(default 1 m, 4300 N; --quick: 0.1 m to 500 N)

Contacts use the seed paper's penalty compliance (compliance = "penalty"), as in the stamped table.
For each normal (neighbour, director, frozen), the default case's strand over the length: 40 kN
tension, then the saddle load 0 → P_max in steps of 250 N growing to 400 N, stepped as a run steps
them (``strand.model.programme.run_programme`` with the case's step control). Prints
per normal the Newton iterations per step, step cuts, wall time, time per iteration, midspan
deflection, and the error of the element's gaps against the gaps measured on the deformed
centrelines (rms / max per interface, µm). Add "frictionless" to run without friction.
"""

import strand  # noqa: F401

# isort: split

import os
import time

import numpy as np
from harness import parser, stamp

from strand.app.build import build_problem, step_control
from strand.app.case import load_case
from strand.model.programme import run_programme
from strand.model.strand_contact import centreline_gaps
from strand.solver import LoadStepFailure, StepRecord


def run(length: float, normal: str, friction: bool, p_max: float) -> dict:
    """One normal's run: its Newton iterations per step, cuts, time, deflection and gap errors."""
    case = load_case(
        None,
        [
            f"mesh.length={length}",
            f'contact.normal="{normal}"',
            f"contact.friction={str(friction).lower()}",
            'contact.compliance="penalty"',
            f"load.lateral={p_max}",
            "load.cycle=[1.0]",
            "steps.lateral=250",
            "steps.lateral_max=400",
        ],
    )
    with open(os.devnull, "w") as sink:
        problem, programme = build_problem(case, sink)
    geometry = problem.geometry
    records: dict[str, list[StepRecord]] = {"tension": [], "lateral": []}

    def on_step(stage, record, position) -> None:
        records[stage.parameter].append(record)

    out = {"normal": normal, "failed": ""}
    t0 = time.perf_counter()
    try:
        run_programme(problem, programme, on_step, **step_control(case))
    except LoadStepFailure as failure:
        out["failed"] = (
            str(failure).split(":")[0]
            + f" at {problem.setup.tension:.0f} N / {problem.setup.lateral:.0f} N"
        )
    out["seconds"] = time.perf_counter() - t0
    out["tension"] = [r.iterations for r in records["tension"]]
    out["lateral"] = [r.iterations for r in records["lateral"]]
    out["cuts"] = sum(r.cuts for r in records["tension"] + records["lateral"])
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
    problem.solver.destroy()
    return out


def main(length: float = 1.0, p_max: float = 4300.0, frictionless: bool = False) -> None:
    print(f"stamp: {stamp()}\n")
    results = [run(length, n, not frictionless, p_max) for n in ("neighbour", "director", "frozen")]
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
