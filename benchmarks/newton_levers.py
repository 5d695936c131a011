"""Newton levers on the main job's first lateral steps: LUs and iterations per step.

Run: .venv/bin/python benchmarks/newton_levers.py TENSIONED_H5 [variant …]
(TENSIONED_H5: ``tensioned.h5`` of a run of the default case, ``strand run cardinal``; variants:
newton (default), lag2, amf, reuse_lu, lbfgs; none named: all, one after the other in this
process), or ``newton_levers.py --quick [variant …]``: the default case over 0.05 m, its
tensioned state made first by a run of its own

From the tensioned state, the first four steps of leg 1 (250, 437.5, 578.125, 718.75 N: the
default case's own) are solved from the converged state before each, with the case's Newton
settings, and each variant's Newton iterations, Jacobian evaluations (= LU factorisations) and
residual histories are printed. ``lag2`` lags the Jacobian by 2 (``snes_lag_jacobian``) with the
stall test off and 30 iterations allowed (a lagged iteration does not halve the residual);
``amf`` factorises with MUMPS's AMF ordering. ``reuse_lu`` and ``lbfgs`` are ``[steps] iteration``'s
cheaper iterations (GMRES on each Jacobian with an earlier LU; L-BFGS on each solve's first LU),
each falling back to Newton on a failed solve. Per step: LU factorisations, MUMPS solves (one per
GMRES iteration; a pair of triangular solves each) and wall time; then each variant's totals
and the time of one LU and of one solve (PETSc's log: MatLUFactorNum, MatSolve).
"""

import strand  # noqa: F401

# isort: split

import os
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path

from harness import parser, stamp
from petsc4py import PETSc

from strand.app.build import build_problem
from strand.app.case import load_case
from strand.app.run import run_case
from strand.model.checkpoint import read_checkpoint, restore

LOADS = (250.0, 437.5, 578.125, 718.75)
VARIANTS = {
    "newton": ([], {}),
    "lag2": (["steps.stall=false", "steps.max_iterations=30"], {"snes_lag_jacobian": 2}),
    "amf": ([], {"mat_mumps_icntl_7": 2}),
    "reuse_lu": (['steps.iteration="reuse_lu"'], {}),
    "lbfgs": (['steps.iteration="lbfgs"'], {}),
}


#: ``--quick``: the case's length
QUICK = ["mesh.length=0.05"]


def tensioned(folder: Path, settings: list[str]) -> Path:
    """``tensioned.h5`` of the default case under ``settings``, pulled to its tension alone by a
    run into ``folder``."""
    outputs = ["output.fields=false", "output.plots=false", "fatigue.outputs=false"]
    case = load_case(None, [*settings, "load.cycle=[0.0]", *outputs])
    with open(os.devnull, "w") as sink:
        result = run_case(case, folder, stream=sink, overwrite=True)
    if result.failure:
        raise SystemExit(f"the tension stopped: {result.failure}")
    return folder / "tensioned.h5"


def run(path: str | Path, name: str, case_settings: Sequence[str] = ()) -> None:
    """The first steps of leg 1 from the tensioned state in ``path`` under variant ``name``,
    the case under ``case_settings``: a table row per step, then the variant's totals."""
    settings, options = VARIANTS[name]
    problem, _ = build_problem(load_case(None, [*case_settings, *settings]))
    s = problem.solver
    prefix = s.solver.getOptionsPrefix()
    for key, value in options.items():
        PETSc.Options()[prefix + key] = value
    s.solver.setFromOptions()
    restore(problem, read_checkpoint(path))
    history: list[float] = []
    s.monitor = lambda i, r: history.append(r)
    lu, solve = PETSc.Log.Event("MatLUFactorNum"), PETSc.Log.Event("MatSolve")
    totals = {"its": 0, "lus": 0, "solves": 0, "s": 0.0}
    lu0, solve0 = lu.getPerfInfo(), solve.getPerfInfo()
    for P in LOADS:
        problem.setup.set_lateral(P)
        history.clear()
        solves = solve.getPerfInfo()["count"]
        t0 = time.perf_counter()
        result = s.solve()
        seconds = time.perf_counter() - t0
        solves = solve.getPerfInfo()["count"] - solves
        totals["its"] += result.iterations
        totals["lus"] += result.factorisations
        totals["solves"] += solves
        totals["s"] += seconds
        print(
            f"| {name} | {P:g} | {result.converged}{' (fell back)' if result.fallback else ''} "
            f"| {result.iterations} | {result.factorisations} | {solves} | {seconds:.1f} | "
            + " ".join(f"{r:.1e}" for r in history)
            + " |",
            flush=True,
        )
        if not result.converged:
            break
        s.commit()
    lu1, solve1 = lu.getPerfInfo(), solve.getPerfInfo()
    per_lu = (lu1["time"] - lu0["time"]) / max(lu1["count"] - lu0["count"], 1)
    per_solve = (solve1["time"] - solve0["time"]) / max(solve1["count"] - solve0["count"], 1)
    print(
        f"| {name}: all steps | | | {totals['its']} | {totals['lus']} | {totals['solves']} | "
        f"{totals['s']:.1f} | one LU {per_lu:.2f} s, one solve {per_solve:.3f} s |",
        flush=True,
    )
    s.destroy()


if __name__ == "__main__":
    cli = parser(__doc__, "0.05 m, its tensioned state made first")
    cli.add_argument("tensioned", nargs="?", metavar="TENSIONED_H5", help="(not with --quick)")
    cli.add_argument("variants", nargs="*", metavar="variant", help=f"of {list(VARIANTS)}")
    args = cli.parse_args()
    names = args.variants
    if args.quick and args.tensioned is not None:  # --quick [variant …]: no file
        names = [args.tensioned, *names]
    elif not args.quick and args.tensioned is None:
        cli.error("the tensioned state to start from (TENSIONED_H5) is required")
    unknown = [n for n in names if n not in VARIANTS]
    if unknown:
        cli.error(f"unknown variant(s) {unknown}; choose from {list(VARIANTS)}")
    names = names or list(VARIANTS)
    PETSc.Log.begin()
    print(f"stamp: {stamp()}\n")
    print(
        "| variant | lateral (N) | converged | iterations | LUs | solves | s | residual norms (N) |"
    )
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        if args.quick:
            path, settings = tensioned(Path(scratch) / "tension", QUICK), QUICK
        else:
            path, settings = args.tensioned, []
        for name in names:
            run(path, name, settings)
