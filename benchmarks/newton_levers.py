"""Newton levers on the main job's first lateral steps: LUs and iterations per step.

Run: .venv/bin/python benchmarks/newton_levers.py TENSIONED_H5 [variant …]
(TENSIONED_H5: ``tensioned.h5`` of a run of the default case, ``strand run cardinal``; variants:
newton (default), lag2, amf; none named: all, one after the other in this process)

From the tensioned state, the first four steps of leg 1 (250, 437.5, 578.125, 718.75 N: the
default case's own) are solved from the converged state before each, with the case's Newton
settings, and each variant's Newton iterations, Jacobian evaluations (= LU factorisations) and
residual histories are printed. ``lag2`` lags the Jacobian by 2 (``snes_lag_jacobian``) with the
stall test off and 30 iterations allowed (a lagged iteration does not halve the residual);
``amf`` factorises with MUMPS's AMF ordering.
"""

import strand  # noqa: F401

# isort: split

import sys
import time

from petsc4py import PETSc

from strand.build import build_problem
from strand.case import load_case
from strand.checkpoint import read_checkpoint, restore

LOADS = (250.0, 437.5, 578.125, 718.75)
VARIANTS = {
    "newton": ([], {}),
    "lag2": (["steps.stall=false", "steps.max_iterations=30"], {"snes_lag_jacobian": 2}),
    "amf": ([], {"mat_mumps_icntl_7": 2}),
}


def run(path: str, name: str) -> None:
    settings, options = VARIANTS[name]
    problem, _ = build_problem(load_case(None, settings))
    s = problem.solver
    prefix = s.solver.getOptionsPrefix()
    for key, value in options.items():
        PETSc.Options()[prefix + key] = value
    s.solver.setFromOptions()
    restore(problem, read_checkpoint(path))
    history: list[float] = []
    s.monitor = lambda i, r: history.append(r)
    for P in LOADS:
        problem.setup.set_lateral(P)
        history.clear()
        calls = s.timings["jacobian_calls"]
        t0 = time.perf_counter()
        result = s.solve()
        print(f"| {name} | {P:g} | {result.converged} | {result.iterations} | "
              f"{s.timings['jacobian_calls'] - calls} | {time.perf_counter() - t0:.1f} | "
              + " ".join(f"{r:.1e}" for r in history) + " |", flush=True)  # fmt: skip
        if not result.converged:
            break
        s.commit()
    s.destroy()


if __name__ == "__main__":
    names = sys.argv[2:] or list(VARIANTS)
    print("| variant | lateral (N) | converged | iterations | LUs | s | residual norms (N) |")
    print("|---|---|---|---|---|---|---|")
    for name in names:
        run(sys.argv[1], name)
