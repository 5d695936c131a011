"""What each per-step output costs at Cardinal size (1 m, 61 wires, 7,386 pairs, 21,521 elements).

Run: .venv/bin/python benchmarks/fatigue_outputs.py [steps] [--length L] [--quick]
(default 10 steps on 1 m; --quick: 2 steps on 0.1 m)

Pulls the default case's strand to 40 kN and takes one lateral step (250 N, friction on), as a run
does (``strand.model.programme.run_programme`` with the case's step control), then records that state
``steps`` times (default 10) with every recorder of a run, side by side, into a scratch folder:
time per step (s) and disk per step (MB) of the fatigue histories (contact pairs with their ParaView
index, wire sections) beside the axial-force CSV and the field series. The fatigue report's own
time is in every run's ``fatigue.txt`` (it needs a cycle, which one repeated state is not).
"""

import strand  # noqa: F401

# isort: split

import os
import tempfile
import time
from pathlib import Path

from harness import parser, stamp

from strand.app.build import build_problem, step_control
from strand.app.case import load_case
from strand.app.fatigue.recorders import PairHistory, WireSectionHistory
from strand.app.recorders import AxialForceTable, FieldSeries
from strand.app.step_records import RunStep, StepContext
from strand.model.cell_results import CellEvaluator, cell_results
from strand.model.programme import run_programme

LATERAL = 250.0  # N, the recorded state's lateral load


def _size(paths) -> int:
    total = 0
    for p in paths:
        p = Path(p)
        total += sum(f.stat().st_size for f in p.rglob("*")) if p.is_dir() else p.stat().st_size
    return total


def main(steps: int = 10, length: float = 1.0) -> None:
    print(f"stamp: {stamp()}\n")
    case = load_case(
        None,
        [
            f"mesh.length={length}",
            f"load.lateral={LATERAL}",
            "load.cycle=[1.0]",
            f"steps.lateral={LATERAL}",
            f"steps.lateral_max={LATERAL}",
        ],
    )
    with open(os.devnull, "w") as sink:
        problem, programme = build_problem(case, sink)
    run_programme(problem, programme, **step_control(case))  # the tension, then 250 N
    evaluator = CellEvaluator(problem.model)
    direction = problem.setup.direction
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        initial = cell_results(problem.model, direction, evaluator)
        recorders = {
            "contact pairs (h5 + xdmf)": (
                PairHistory(folder, problem.model, "lateral"),
                ["contact_pairs.h5", "contact_points.xdmf"],
            ),
            "wire sections (h5)": (
                WireSectionHistory(folder, problem.model, initial, direction, "lateral"),
                ["wire_sections.h5"],
            ),
            "axial forces (csv)": (
                AxialForceTable(folder, "lateral", "N"),
                ["axial_forces.csv"],
            ),
            "fields (xdmf + vtx)": (FieldSeries(folder, problem), ["fields.h5", "fields.bp"]),
        }
        seconds = dict.fromkeys(recorders, 0.0)
        t_cells = 0.0
        for k in range(steps):
            t0 = time.perf_counter()
            cells = cell_results(problem.model, direction, evaluator)
            t_cells += time.perf_counter() - t0
            step = RunStep(k + 1, "leg 1", "lateral", LATERAL, 1.0 + k, 1, 0, 0.0, 0.0, None)
            ctx = StepContext(step, problem, k > 0, _cells=cells)
            for name, (r, _) in recorders.items():
                t0 = time.perf_counter()
                r.record(ctx)
                seconds[name] += time.perf_counter() - t0
        for r, _ in recorders.values():
            r.close()
        print(
            f"Cardinal {length:g} m, 40 kN + {LATERAL:g} N, {steps} recorded steps (cell results: "
            f"{t_cells / steps:.3f} s per step, shared)"
        )
        print(f"{'output':28s} {'s per step':>11s} {'MB per step':>12s}")
        for name, (_, files) in recorders.items():
            size = _size([folder / f for f in files]) / 1e6
            print(f"{name:28s} {seconds[name] / steps:11.3f} {size / steps:12.2f}")
    problem.solver.destroy()


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "2 steps on 0.1 m")
    cli.add_argument("steps", nargs="?", type=int, default=10, help="recorded (default 10)")
    cli.add_argument("--length", type=float, default=1.0, help="m (default 1)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    main(*((2, 0.1) if args.quick else (args.steps, args.length)))
