"""The whole Cardinal case (the default of ``strand run``): time, steps, Newton iterations.

Run: .venv/bin/python benchmarks/cardinal.py [case.toml] [--set key=value …] [--quick]
(--quick: the case over 0.05 m, one leg to +0.5 kN)

Runs the case on one process with all its outputs (XDMF, CSV, figures) and prints total time,
steps, Newton iterations, time per iteration split into assembly, contact and LU, and peak memory.
The main job's own time, on 2 ranks, is in docs/benchmarks.md ("The main job whole").
"""

import strand  # noqa: F401

# isort: split

import io
import time

from harness import add_settings, parser, peak_mib, stamp

from strand.app.case import load_case
from strand.app.run import run_case

#: ``--quick``: a short piece, one leg
QUICK = ["mesh.length=0.05", "load.lateral=500", "load.cycle=[1.0]"]


def main(case_file: str | None = None, settings: list[str] | None = None) -> None:
    print(f"stamp: {stamp()}\n")
    case = load_case(case_file, settings or [])
    t0 = time.perf_counter()
    log = io.StringIO()
    result = run_case(case, "results/benchmark_cardinal", stream=log, overwrite=True)
    total = time.perf_counter() - t0
    tm = result.timings
    its = max(result.iterations, 1)
    callbacks = tm["residual"] + tm["jacobian"]
    contact = tm["terms"] + tm["insert"]
    lu = tm["solve"] - callbacks
    peak = peak_mib()
    stages = {}
    for s in result.steps:
        stages.setdefault(s.stage, []).append(s.iterations)
    print(f"{case.cable.name}, L = {case.mesh.length} m, normal = {case.contact.normal}")
    print(f"{'stage':10s} {'steps':>5s} {'Newton its':>10s}  iterations per step")
    for stage, its_list in stages.items():
        print(f"{stage:10s} {len(its_list):5d} {sum(its_list):10d}  {its_list}")
    cuts = sum(s.cuts for s in result.steps)
    rows = [
        ("total wall time (s)", f"{total:.1f}"),
        ("  set-up: mesh, forms, pattern (s)", f"{result.setup_seconds:.1f}"),
        ("  Newton solves (s)", f"{tm['solve']:.1f}"),
        ("  outputs per step: CSV, XDMF (s)", f"{tm['output']:.1f}"),
        (
            "  figures and the rest (s)",
            f"{total - result.setup_seconds - tm['solve'] - tm['output']:.1f}",
        ),
        ("converged steps / failed attempts", f"{len(result.steps)} / {cuts}"),
        ("Newton iterations (converged steps)", f"{result.iterations}"),
        ("time per iteration (s)", f"{tm['solve'] / its:.2f}"),
        ("  beam assembly share", f"{100 * (callbacks - contact) / tm['solve']:.1f} %"),
        ("  contact share", f"{100 * contact / tm['solve']:.1f} %"),
        ("  LU share", f"{100 * lu / tm['solve']:.1f} %"),
        ("peak memory (MiB)", f"{peak:.0f}"),
        ("outcome", "FAILED: " + result.failure if result.failure else "completed"),
    ]
    for name, value in rows:
        print(f"{name:38s} {value}")
    print(
        "outputs by recorder (s): "
        + ", ".join(
            f"{k} {v:.1f}" for k, v in sorted(result.output_timings.items(), key=lambda kv: -kv[1])
        )
    )


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "the case over 0.05 m, one leg to +0.5 kN")
    cli.add_argument("case", nargs="?", help="a case file (default: the built-in Cardinal case)")
    add_settings(cli)
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    main(args.case, [*(QUICK if args.quick else []), *args.settings])
