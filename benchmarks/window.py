"""The main job's window, one commit or setting against another in one run: time and load-step error.

Run: .venv/bin/python benchmarks/window.py [--quick] [--ranks N] [variant …]
(no variant named: those of DEFAULT_RUN; --quick: 0.1 m to 1 kN, a smoke test of the script)

The window is the main job (Cardinal, 1 m, 40 kN) up to the first peak: the tension, then the
first leg of the saddle load to +4.3 kN, on 2 ranks, with no outputs (the library's
``run_programme``; the results compared are taken in memory at the ends of the stages). Each variant runs in a process of its own, one after the other, so that each has the
machine to itself. A variant is a commit (its code from a git worktree made here, under
/tmp/strand-<commit>, put first on PYTHONPATH; None: this tree) and case settings. Prints per
variant its wall time (and against the first variant's), steps, Newton iterations (and in failed
attempts), LU factorisations, time per LU and per iteration, peak memory of the largest rank;
then, at the end of the tension and at the peak, each variant's results against the same variant
with every load step halved (its load-step error: the largest difference of midspan deflection
and end displacement, µm, and of any element's axial force, contact pair force and same-layer
pair force against the largest), and against the first variant.
"""

import strand  # noqa: F401  (before petsc4py: the wheel's MPI; a variant's own code in its process)

# isort: split

import argparse
import os
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from harness import parser, peak_mib, print_result, run_variants, stamp, table

ROOT = Path("results/benchmark_window")
#: the window: tension and the first leg; no field series, checkpoints, figures or histories
WINDOW = [
    "load.cycle=[1.0]",
    "output.fields=false",
    "output.plots=false",
    "output.checkpoint=false",
    "fatigue.outputs=false",
]
QUICK = ["mesh.length=0.1", "load.lateral=1000"]
#: the issue's starting commit (issue 39)
START = "ef5ccec"


@dataclass(frozen=True)
class Variant:
    """A commit's code (None: this tree) with case settings, its load increments (first and
    largest, tension and lateral) scaled by ``steps`` (0.5: every step halved)."""

    commit: str | None = None
    settings: list[str] = field(default_factory=list)
    steps: float = 1.0


def _with_halved(variants: dict[str, Variant]) -> dict[str, Variant]:
    """Each variant, and the same with its steps halved (``<name>, steps halved``)."""
    out = {}
    for name, v in variants.items():
        out[name] = v
        out[f"{name}, steps halved"] = Variant(v.commit, v.settings, 0.5 * v.steps)
    return out


VARIANTS = _with_halved(
    {
        START: Variant(START),
        "default": Variant(None),
        "two-node same-layer pairs": Variant(None, ['contact.same_layer_stencil="node"']),
        "microslip": Variant(None, ['contact.compliance="hertz_microslip"']),
        "facing stations": Variant(None, ['contact.same_layer_stencil="facing"']),
        "balance 1e-3": Variant(None, ["steps.balance=1e-3"]),
        # the stepper before each halved increment was tried from both starting guesses
        "retry once per step": Variant("c1f19c1"),
    }
)
#: a run without named variants: the issue's start, today's default and the two-node same-layer
#: pairs, each with halved steps
DEFAULT_RUN = [
    START,
    f"{START}, steps halved",
    "default",
    "default, steps halved",
    "two-node same-layer pairs",
    "two-node same-layer pairs, steps halved",
]


def slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name).strip("_")


def worktree(commit: str) -> Path:
    """A checkout of ``commit`` under /tmp (made once), for its code on PYTHONPATH."""
    path = Path(f"/tmp/strand-{commit}")
    if not (path / "strand").is_dir():
        subprocess.run(
            ["git", "worktree", "add", "--detach", str(path), commit],
            check=True,
            capture_output=True,
        )
    return path


def _api() -> dict:
    """What a variant's code offers the window, wherever its layout puts it: today's, the
    sub-packages of the re-cut before ``model/post.py`` was split, or the flat package of the
    commits before the re-cut (ef5ccec)."""
    from importlib import import_module

    where = {
        "build_problem": ("strand.app.build", "strand.build"),
        "step_control": ("strand.app.build", "strand.build"),
        "load_case": ("strand.app.case", "strand.case"),
        "cell_results": ("strand.model.cell_results", "strand.model.post", "strand.post"),
        "run_programme": ("strand.model.programme", "strand.programme"),
    }
    api = {}
    for name, modules in where.items():
        for module in modules:
            try:
                api[name] = getattr(import_module(module), name)
                break
            except ImportError:
                continue
        else:
            raise ImportError(f"{name} in none of {modules}")
    return api


def measures(problem) -> dict:
    """The results compared between variants, at a stage's end: midspan deflection and end
    displacement (m), every element's axial force (N, the geometry's order), and the normal
    force of every contact pair and same-layer pair (N, the geometry's order)."""
    cell_results = _api()["cell_results"]
    m = problem.model
    s = problem.setup.state()
    same = m.same_layer_history().get("force", np.zeros(0))
    return {
        "deflection": s.deflection,
        "end": s.end_displacement,
        "N": cell_results(m).axial,
        "pairs": m.pair_results().force,
        "same": same,
    }


def run_variant(name: str, quick: bool) -> dict:
    """Run one variant in this process (the code on the path), outputs off; its measurements,
    and its results at the ends of the stages in ``ROOT/<name>.npz``."""
    from mpi4py import MPI
    from petsc4py import PETSc

    api = _api()
    build_problem, step_control = api["build_problem"], api["step_control"]
    load_case, run_programme = api["load_case"], api["run_programme"]
    comm = MPI.COMM_WORLD
    PETSc.Log.begin()
    variant = VARIANTS[name]
    settings = [*WINDOW, *variant.settings, *(QUICK if quick else [])]
    case = load_case(None, settings)
    if variant.steps != 1.0:  # the variant's own increments (its code's defaults), scaled
        s = case.steps
        scaled = {"tension": s.tension, "lateral": s.lateral, "lateral_max": s.lateral_max}
        case = load_case(
            None, [*settings, *(f"steps.{k}={variant.steps * v!r}" for k, v in scaled.items())]
        )
    t0 = time.perf_counter()
    problem, programme = build_problem(case)
    ends, steps = [], []

    def on_step(stage, record, position):
        steps.append(record)
        if abs(record.load - stage.target) <= 1e-9 * max(1.0, abs(stage.target)):
            ends.append(measures(problem))

    failure = None
    try:
        run_programme(problem, programme, on_step=on_step, **step_control(case))
    except RuntimeError as e:  # LoadStepFailure
        failure = str(e)
    seconds = time.perf_counter() - t0
    problem.solver.destroy()
    lu = PETSc.Log.Event("MatLUFactorNum").getPerfInfo()
    peak = peak_mib(comm)
    if comm.rank == 0:
        ROOT.mkdir(parents=True, exist_ok=True)
        np.savez(
            ROOT / f"{slug(name)}.npz",
            **{f"{k}_{i}": np.asarray(v) for i, e in enumerate(ends) for k, v in e.items()},
        )
    return {
        "seconds": seconds,
        "steps": len(steps),
        "iterations": sum(r.iterations for r in steps),
        "failed_iterations": sum(r.failed_iterations for r in steps),
        "lu": lu["count"],
        "lu_seconds": lu["time"],
        "peak_mib": peak,
        "failure": failure,
    }


def ends_of(name: str) -> list[dict]:
    """The results of ``name`` at the ends of its stages."""
    data = np.load(ROOT / f"{slug(name)}.npz")
    count = 1 + max((int(k.rsplit("_", 1)[1]) for k in data.files), default=-1)  # none: failed
    return [
        {k.rsplit("_", 1)[0]: data[k] for k in data.files if k.endswith(f"_{i}")}
        for i in range(count)
    ]


def differences(name: str, reference: str) -> dict[str, float]:
    """The largest differences of ``name`` from ``reference`` at the ends of the stages both
    reached: deflection and end displacement (µm); element axial forces, pair forces and
    same-layer pair forces, each against the reference's largest; nan where either reached
    no stage's end."""
    out = {"deflection": 0.0, "end": 0.0, "N": 0.0, "pairs": 0.0, "same": 0.0}
    ours, theirs = ends_of(name), ends_of(reference)
    if not ours or not theirs:
        return dict.fromkeys(out, np.nan)
    for a, b in zip(ours, theirs, strict=False):
        for key in ("deflection", "end"):
            out[key] = max(out[key], 1e6 * abs(float(a[key]) - float(b[key])))
        for key in ("N", "pairs", "same"):
            if a[key].shape == b[key].shape and len(b[key]):
                out[key] = max(out[key], np.abs(a[key] - b[key]).max() / np.abs(b[key]).max())
            else:
                out[key] = np.nan
    return out


def main(names: list[str], quick: bool, ranks: int) -> None:
    print(f"stamp: {stamp()}")

    def env(name: str) -> dict[str, str] | None:
        commit = VARIANTS[name].commit
        if commit is None:
            return None
        return dict(os.environ, PYTHONPATH=f"{worktree(commit)}:{os.environ.get('PYTHONPATH', '')}")

    rows = run_variants(__file__, names, ["--quick"] if quick else [], ranks, env)
    first = rows[names[0]]["seconds"]
    columns = [
        "variant",
        "time (s)",
        "/first",
        "steps",
        "its",
        "+failed",
        "LUs",
        "s/LU",
        "s/it",
        "peak MiB",
    ]
    cells = []
    for name, r in rows.items():
        its = r["iterations"] + r["failed_iterations"]
        cells.append(
            [
                name,
                f"{r['seconds']:.0f}",
                f"{r['seconds'] / first:.2f}",
                r["steps"],
                r["iterations"],
                r["failed_iterations"],
                r["lu"],
                f"{r['lu_seconds'] / max(r['lu'], 1):.2f}",
                f"{r['seconds'] / max(its, 1):.2f}",
                f"{r['peak_mib']:.0f}",
            ]
        )
    print("\n" + table(cells, columns, plain=True))
    for name, r in rows.items():
        if r["failure"]:
            print(f"{name}: FAILED: {r['failure']}")
    print(
        "\nat the end of the tension and at the peak, the largest differences: deflection and "
        "end displacement (µm), element axial forces, contact pair and same-layer pair forces "
        "(each against the largest)"
    )
    cells = []
    for name in rows:
        compared = [(f"{name} against its steps halved", f"{name}, steps halved")]
        if name != names[0] and not name.endswith("steps halved"):
            compared.append((f"{name} against {names[0]}", names[0]))
        for label, reference in compared:
            if reference in rows:
                d = differences(name, reference)
                cells.append(
                    [
                        label,
                        f"{d['deflection']:.3f}",
                        f"{d['end']:.3f}",
                        f"{d['N']:.1e}",
                        f"{d['pairs']:.1e}",
                        f"{d['same']:.1e}",
                    ]
                )
    if cells:
        print(table(cells, ["", "deflection", "end", "axial", "pairs", "same"], plain=True))


if __name__ == "__main__":
    cli = parser(__doc__, "0.1 m to 1 kN")
    cli.add_argument(
        "variants", nargs="*", metavar="variant", help="named in VARIANTS (none: DEFAULT_RUN's)"
    )
    cli.add_argument("--ranks", type=int, default=2, help="MPI ranks per variant (default 2)")
    cli.add_argument("--one", help=argparse.SUPPRESS)  # a variant's own process
    args = cli.parse_args()
    if args.one:
        measured = run_variant(args.one, args.quick)
        from mpi4py import MPI

        print_result(measured, MPI.COMM_WORLD)
    else:
        unknown = [a for a in args.variants if a not in VARIANTS]
        if unknown:
            cli.error(f"unknown variant(s) {unknown}; choose from {list(VARIANTS)}")
        main(args.variants or DEFAULT_RUN, args.quick, args.ranks)
