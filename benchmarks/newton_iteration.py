"""Where the time of one Newton iteration goes at Cardinal size (1 m, 61 wires, ~7,400 pairs).

Run: .venv/bin/python benchmarks/newton_iteration.py [normal] [length_m] [--quick]
(normal: director (default), neighbour or frozen; length default 1 m; --quick: 0.1 m)

The default case (Cardinal, packed layers, friction on) with the seed paper's penalty compliance
(``compliance = "penalty"``), as in the stamped table. Pulls the strand to 40 kN as a run does:
the case's tension stage and step control (first step 1 kN, step cuts, retry, predictor, contact
stabilisation; ``strand.model.programme.run_programme``). Then measures the Newton iterations of
two lateral steps of 250 N (friction on, so the contact is in a mixed stick/slip state; failed
attempts included) and prints the time per iteration split into beam assembly, contact kernels,
insertion into PETSc objects and the LU solve. The last line reads ``contact share of a Newton
iteration: X %``.
"""

import strand  # noqa: F401

# isort: split

import os
import time
from dataclasses import replace

from harness import parser, peak_mib, stamp, table

from strand.app.build import build_problem, step_control
from strand.app.case import load_case
from strand.model.programme import run_programme
from strand.solver import StepRecord

LATERAL_STEP = 250.0  # N, each of the two measured steps
QUICK_LENGTH = 0.1  # m


def main(normal: str = "director", length: float = 1.0) -> None:
    print(f"stamp: {stamp()}\n")
    case = load_case(
        None,
        [
            f"mesh.length={length}",
            f'contact.normal="{normal}"',
            'contact.compliance="penalty"',
            f"load.lateral={2 * LATERAL_STEP}",
            "load.cycle=[1.0]",
            f"steps.lateral={LATERAL_STEP}",
            f"steps.lateral_max={LATERAL_STEP}",
        ],
    )
    t0 = time.perf_counter()
    with open(os.devnull, "w") as sink:
        problem, programme = build_problem(case, sink)
    t_setup = time.perf_counter() - t0
    tension, leg = programme.stages
    records: dict[str, list[StepRecord]] = {tension.name: [], leg.name: []}

    def on_step(stage, record, position) -> None:
        records[stage.name].append(record)

    control = step_control(case)
    solver = problem.solver
    run_programme(problem, replace(programme, stages=(tension,)), on_step, **control)
    solver.timings = dict.fromkeys(solver.timings, 0.0)
    run_programme(problem, replace(programme, stages=(leg,)), on_step, **control)
    lateral = records[leg.name]
    its = sum(r.iterations + r.failed_iterations for r in lateral)
    # SNES evaluates the residual once more than the Jacobian: per iteration, count both
    tm = {k: v / its for k, v in solver.timings.items()}
    contact = tm["terms"] + tm["insert"]
    beam = tm["residual"] + tm["jacobian"] - contact
    lu = tm["solve"] - tm["residual"] - tm["jacobian"]
    total = tm["solve"]
    peak = peak_mib()
    n_pairs = len(problem.geometry.pairs)
    nnz = solver.A.getInfo()["nz_used"]
    pulled = records[tension.name]
    print(
        f"Cardinal, L = {length:g} m, {problem.w.x.array.size} unknowns, {n_pairs} pairs, "
        f"normal = {normal}, matrix non-zeros {nnz:.3g}; set-up {t_setup:.1f} s; tension steps "
        f"{[r.iterations for r in pulled]} (+ {sum(r.failed_iterations for r in pulled)} in "
        f"failed attempts, {sum(r.cuts for r in pulled)} cuts, "
        f"{sum(1 for r in pulled if r.stabilisation)} held by the springs); lateral steps "
        f"{[r.iterations for r in lateral]} (+ {sum(r.failed_iterations for r in lateral)})"
    )
    rows = [
        ("beam assembly (F and J)", beam),
        ("contact kernels", tm["terms"]),
        ("insertion into PETSc", tm["insert"]),
        ("LU factorisation + solve", lu),
        ("total", total),
    ]
    cells = [[name, f"{value:.3f}", f"{100 * value / total:.1f} %"] for name, value in rows]
    print(table(cells, ["part", "s / iteration", "share"], plain=True))
    print(f"peak memory {peak:.0f} MiB")
    print(f"contact share of a Newton iteration: {100 * contact / total:.1f} %")
    solver.destroy()


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, f"{QUICK_LENGTH:g} m")
    cli.add_argument(
        "normal", nargs="?", default="director", choices=["director", "neighbour", "frozen"]
    )
    cli.add_argument("length", nargs="?", type=float, default=1.0, help="m (default 1)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    main(args.normal, QUICK_LENGTH if args.quick else args.length)
