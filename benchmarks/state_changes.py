"""Where Newton's iterations go: contact pairs changing state between iterations, per interface.

Run: [.venv/bin/mpirun -n 2] .venv/bin/python benchmarks/state_changes.py [--case case.toml]
[--set key=value …] [--residuals] [--attempts] [--quick]
(--quick: the window on 0.1 m to 1 kN, as ``window.py --quick``)

Runs the window of the main job (Cardinal, 1 m: the tension, then the first leg to +4.3 kN,
outputs off; ``--set`` changes any setting, e.g. ``--set load.lateral=1000``) and watches every
Jacobian evaluation (one per Newton iteration). Between consecutive iterations of a solve it
counts the pairs that opened or closed (normal force zero against positive) and those that went
from stick to slip or back, per interface: crossings ``i|i+1``, the core line pairs ``0|1``, and
the same-layer pairs of layer i, ``Li-Li``. Prints, per stage, the iterations and for each
interface its pairs, the flips per iteration of each kind, and the pairs carrying no force and
slipping at the stage's end. ``--residuals``: every solve's residual norms. ``--attempts``: for
each solve that failed (the last ``ATTEMPTS``), the flips of each interface at each iteration,
``open/close/stick-slip/back``, back counting the pairs that return to their state of two
iterations before (a chatter): where a step that will not converge spends its iterations.
"""

import strand  # noqa: F401

# isort: split

import os
import time
from collections import defaultdict

import numpy as np
from harness import add_settings, parser, stamp, table
from mpi4py import MPI
from window import QUICK, WINDOW  # the main job's window (this folder, the script's first path)

from strand.contact.group import PairGroup
from strand.model.model import StrandModel
from strand.solver import LoadStepper

#: (stage, interface) -> counts
COUNTS: dict = defaultdict(lambda: defaultdict(float))
ITERATIONS: dict = defaultdict(int)
STAGE = ["?"]
SOLVE = [0]
#: (stage, converged, residual norms) of every solve
SOLVES: list = []
#: solve -> interface -> iteration -> [open/close, stick/slip, back] (``--attempts``)
PER_SOLVE: dict = defaultdict(lambda: defaultdict(lambda: defaultdict(lambda: np.zeros(3, int))))
#: the failed solves ``--attempts`` prints, the last ones
ATTEMPTS = 6


def _label(model: StrandModel) -> None:
    """Give every group of ``model`` the interface label of each of its pairs."""
    pairs = model.geometry.pairs
    for g in model.contact:
        g._labels = np.array([f"{i}|{i + 1}" for i in pairs.interface[g.index]])
    for g in model.same_layer:
        layer = model.same_layer_pairs.layer[g.index]
        g._labels = np.array([f"L{i}-L{i}" for i in layer])


def _patch() -> None:
    init, evaluate, ramp = StrandModel.__init__, PairGroup.evaluate, LoadStepper.ramp
    solve = None

    def model_init(self, *args, **kwargs):
        init(self, *args, **kwargs)
        _label(self)

    def group_evaluate(self, w, jacobian=True):
        out = evaluate(self, w, jacobian)
        labels = getattr(self, "_labels", None)
        if not jacobian or labels is None:
            return out
        closed, slipping = self.state.force > 0, self.state.slipping.copy()
        previous = getattr(self, "_previous", None)
        stage = STAGE[0]
        if previous is not None and previous[0] == SOLVE[0]:
            flips = closed != previous[1]
            slips = slipping != previous[2]
            k = previous[3] + 1  # this solve's iteration
            before = getattr(self, "_before", None)  # two iterations back, same solve
            back = np.zeros_like(flips)
            if before is not None and before[0] == SOLVE[0]:
                back = (flips & (closed == before[1])) | (slips & (slipping == before[2]))
            for name in np.unique(labels):
                mine = labels == name
                COUNTS[stage, name]["open/close"] += np.count_nonzero(flips & mine)
                COUNTS[stage, name]["stick/slip"] += np.count_nonzero(slips & mine)
                PER_SOLVE[SOLVE[0]][name][k] += [
                    np.count_nonzero(flips & mine),
                    np.count_nonzero(slips & mine),
                    np.count_nonzero(back & mine),
                ]
        for name in np.unique(labels):
            mine = labels == name
            COUNTS[stage, name]["pairs"] = np.count_nonzero(mine)
            COUNTS[stage, name]["open at end"] = np.count_nonzero(~closed & mine)
            COUNTS[stage, name]["slipping at end"] = np.count_nonzero(slipping & mine)
        if self is _first_group[0]:
            ITERATIONS[stage] += 1
        same = previous is not None and previous[0] == SOLVE[0]
        self._before = previous if same else None
        self._previous = (SOLVE[0], closed, slipping, previous[3] + 1 if same else 0)
        return out

    _first_group = [None]

    def stepper_ramp(self, set_load, start, end, stage="load", resume=None):
        STAGE[0] = stage
        nonlocal solve
        if solve is None:
            original = self.solver.solve

            def counted_solve():
                SOLVE[0] += 1
                result = original()
                SOLVES.append((STAGE[0], result.converged, result.residuals))
                return result

            solve = counted_solve
            self.solver.solve = counted_solve
        groups = [g for g in self.solver._pairs.terms if hasattr(g, "_labels")]
        _first_group[0] = groups[0] if groups else None
        return ramp(self, set_load, start, end, stage, resume)

    StrandModel.__init__ = model_init
    PairGroup.evaluate = group_evaluate
    LoadStepper.ramp = stepper_ramp


def attempt_lines(comm) -> list[str]:
    """Per failed solve (the last ``ATTEMPTS``): its residuals, then per interface its flips at
    each iteration, ``open/close/stick-slip/back`` (rank 0's list; [] on the others)."""
    mine = {
        s: {name: {k: v.tolist() for k, v in its.items()} for name, its in d.items()}
        for s, d in PER_SOLVE.items()
    }
    parts = comm.gather(mine)
    if comm.rank != 0:
        return []
    total: dict = defaultdict(lambda: defaultdict(lambda: defaultdict(lambda: np.zeros(3, int))))
    for part in parts:
        for s, d in part.items():
            for name, its in d.items():
                for k, v in its.items():
                    total[s][name][k] += v
    failed = [i + 1 for i, (_, converged, _) in enumerate(SOLVES) if not converged]
    lines = []
    for s in failed[-ATTEMPTS:]:
        stage, _, norms = SOLVES[s - 1]
        lines.append(
            f"solve {s} ({stage}, failed): residuals " + " ".join(f"{r:.1e}" for r in norms)
        )
        for name in sorted(total[s]):
            its = total[s][name]
            lines.append(
                f"  {name:8s} " + " ".join("/".join(map(str, its[k])) for k in sorted(its))
            )
    return lines


def main(
    settings: list[str], case_file: str | None, residuals: bool = False, attempts: bool = False
) -> None:
    from strand.app.case import load_case
    from strand.app.run import run_case

    _patch()
    comm = MPI.COMM_WORLD
    case = load_case(case_file, [*WINDOW, *settings])
    t0 = time.perf_counter()
    with open(os.devnull, "w") as sink:
        result = run_case(case, f"results/state_changes_{comm.size}", stream=sink, overwrite=True)
    seconds = time.perf_counter() - t0
    keys = sorted(COUNTS)
    failed_attempts = attempt_lines(comm) if attempts else []
    gathered = comm.gather({k: dict(COUNTS[k]) for k in keys})
    iterations = comm.gather(dict(ITERATIONS))
    if comm.rank != 0:
        return
    total: dict = defaultdict(lambda: defaultdict(float))
    for part in gathered:
        for k, v in part.items():
            for name, n in v.items():
                total[k][name] += n
    its = iterations[0]
    print(f"stamp: {stamp()}")
    print(
        f"{len(result.steps)} steps, {result.iterations} iterations in converged steps, "
        f"{result.failed_iterations} in failed attempts, {seconds:.0f} s "
        f"on {comm.size} rank(s); {' '.join(settings)}"
    )
    if residuals:
        for stage, converged, residuals in SOLVES:
            print(
                f"{stage:10s} {'ok  ' if converged else 'FAIL'} "
                + " ".join(f"{r:.1e}" for r in residuals)
            )
    cells = []
    for stage in dict.fromkeys(k[0] for k in sorted(total)):
        n = max(its.get(stage, 0), 1)
        for (s, name), v in sorted(total.items()):
            if s != stage:
                continue
            cells.append(
                [
                    stage,
                    its.get(stage, 0),
                    name,
                    f"{v['pairs']:.0f}",
                    f"{v['open/close'] / n:.1f}",
                    f"{v['stick/slip'] / n:.1f}",
                    f"{v['open at end']:.0f}",
                    f"{v['slipping at end']:.0f}",
                ]
            )
    if attempts:
        print("the failed solves' flips at each iteration, open/close/stick-slip/back:")
        print("\n".join(failed_attempts) or "  no solve failed")
    print("flips per iteration (open/close, stick/slip) per stage and interface:")
    print(
        table(
            cells,
            [
                "stage",
                "its",
                "interface",
                "pairs",
                "open/close",
                "stick/slip",
                "open@end",
                "slip@end",
            ],
            plain=True,
        )
    )


if __name__ == "__main__":
    cli = parser(__doc__, "the window on 0.1 m to 1 kN")
    cli.add_argument(
        "--case",
        help="a case file (default: the built-in Cardinal case), run to the end of its first "
        "leg with its outputs off (the window's settings over it)",
    )
    add_settings(cli)
    cli.add_argument("--residuals", action="store_true", help="every solve's residual norms")
    cli.add_argument(
        "--attempts", action="store_true", help="the failed solves' flips at each iteration"
    )
    args = cli.parse_args()
    main([*(QUICK if args.quick else []), *args.settings], args.case, args.residuals, args.attempts)
