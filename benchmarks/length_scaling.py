"""Cost against cable length: Cardinal at 0.25, 0.5, 1 and 2 m, tension and a first lateral leg.

Run: .venv/bin/python benchmarks/length_scaling.py [lengths…] [setting=value …] [--quick]
(settings as `strand run --set`, e.g. 'steps.line_search="basic"' for full Newton steps;
--quick: 0.05 and 0.1 m, each to 200 N)

Every length runs the default case's tension (40 kN) and a first leg to a lateral load scaled to
give the same midspan moment, P = 1 kN × (1 m / L) (PL/8 for the clamped span), so that the
work per length is alike; outputs are off but the step table. Prints per length the unknowns,
steps, Newton iterations (in converged steps, and in failed attempts), wall time, time per
converged iteration and its LU share, and peak memory (of the process so far), then the
exponents b of time ∝ L^b fitted over the lengths (goal: b ≤ 1.1).
"""

import strand  # noqa: F401

# isort: split

import time
from pathlib import Path

import numpy as np
from harness import parser, peak_mib, stamp

from strand.app.case import load_case
from strand.app.run import run_case
from strand.cable.geometry import build_geometry

#: ``--quick``: the lengths (m) and the lateral load, over every length's own
QUICK_LENGTHS = [0.05, 0.1]
QUICK_LATERAL = "load.lateral=200"


def main(lengths: list[float], extra: list[str]) -> None:
    print(f"stamp: {stamp()}\n")
    rows = []
    sink = open("/dev/null", "w")  # noqa: SIM115
    for L in lengths:
        settings = [
            f"mesh.length={L}",
            f"load.lateral={1000.0 / L}",
            "load.cycle=[1.0]",
            f"steps.lateral={250.0 / L}",
            f"steps.lateral_max={400.0 / L}",
            "output.plots=false",
            "output.fields=false",
            "fatigue.outputs=false",
            "output.checkpoint=false",
            *extra,
        ]
        case = load_case(None, settings)
        t0 = time.perf_counter()
        r = run_case(case, Path(f"results/benchmark_length/{L:g}"), stream=sink, overwrite=True)
        seconds = time.perf_counter() - t0
        tm = r.timings
        lu = tm["solve"] - tm["residual"] - tm["jacobian"]
        memory = peak_mib()
        g = build_geometry(case.cable, case.mesh.length, case.mesh.h_max)
        rows.append((L, r, seconds, lu, memory, 6 * len(g.points)))
    print(
        f"{'L (m)':>6s} {'unknowns':>9s} {'steps':>6s} {'its':>5s} {'+failed':>7s} "
        f"{'time (s)':>9s} {'s/it':>6s} {'LU share':>9s} {'peak MiB':>9s}"
    )
    for L, r, seconds, lu, memory, unknowns in rows:
        its = max(r.iterations, 1)
        failed = r.failed_iterations
        print(
            f"{L:6.2f} {unknowns:9d} {len(r.steps):6d} {r.iterations:5d} {failed:7d} "
            f"{seconds:9.1f} {r.timings['solve'] / its:6.3f} {100 * lu / r.timings['solve']:8.0f} % "
            f"{memory:9.0f}{'  FAILED' if r.failure else ''}"
        )
    x = np.log([row[0] for row in rows])
    fits = {
        "wall time": [row[2] for row in rows],
        "time per iteration": [row[1].timings["solve"] / max(row[1].iterations, 1) for row in rows],
        "LU time": [row[3] for row in rows],
    }
    for name, y in fits.items():
        b = np.polyfit(x, np.log(y), 1)[0]
        print(f"exponent of {name}: {b:.2f}")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "0.05 and 0.1 m, each to 200 N")
    cli.add_argument(
        "items", nargs="*", metavar="length or setting", help="m (default 0.25 0.5 1 2); key=value"
    )
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    settings = [a for a in args.items if "=" in a]
    try:
        lengths = [float(a) for a in args.items if "=" not in a]
    except ValueError as e:
        cli.error(f"a length (m) or a setting key=value: {e}")
    if args.quick:
        lengths, settings = QUICK_LENGTHS, [*settings, QUICK_LATERAL]
    main(lengths or [0.25, 0.5, 1.0, 2.0], settings)
