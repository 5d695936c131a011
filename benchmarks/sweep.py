"""A sweep of lateral amplitudes from one tensioned state against the same runs made separately.

Run: .venv/bin/python benchmarks/sweep.py [length_m] [n_amplitudes] [--quick]   (default 0.25 m,
10; --quick: 0.1 m, 2 amplitudes, one leg to +A)

Both sides run the Cardinal case (all outputs but the figures) with the cycle ±A at A = 0.1 … 1
× 1 kN: the sweep (``[load] sweep``) builds the strand and tensions it once, then restores that
state for every amplitude; the separate runs build and tension it every time. Prints per
amplitude the steps and Newton iterations of both (equal: a sweep member is the separate run
from its tensioned state on) and the wall times, then the cost ratio.
"""

import strand  # noqa: F401

# isort: split

import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from harness import parser, stamp

from strand.app.case import load_case
from strand.app.run import run_case, run_sweep

ROOT = Path("results/benchmark_sweep")


def main(length: float = 0.25, n: int = 10, extra: Sequence[str] = ()) -> None:
    print(f"stamp: {stamp()}\n")
    amplitudes = [round(1000.0 * (k + 1) / n, 6) for k in range(n)]
    settings = [f"mesh.length={length}", "output.plots=false", *extra]
    sink = open("/dev/null", "w")  # noqa: SIM115
    t0 = time.perf_counter()
    case = load_case(None, [*settings, f"load.sweep={amplitudes}"])
    swept = run_sweep(case, ROOT / "sweep", stream=sink, overwrite=True)
    t_sweep = time.perf_counter() - t0
    separate = []
    for a in amplitudes:
        t0 = time.perf_counter()
        r = run_case(
            load_case(None, [*settings, f"load.lateral={a}"]),
            ROOT / f"alone_{a:g}",
            stream=sink,
            overwrite=True,
        )
        separate.append((r, time.perf_counter() - t0))
    tension = swept[0]
    print(
        f"Cardinal {length} m, cycle ±A, {n} amplitudes; tension once: {len(tension.steps)} "
        f"steps, {tension.iterations} iterations, {tension.seconds:.1f} s"
    )
    print(
        f"{'A (N)':>7s} {'sweep steps/its':>16s} {'alone steps/its':>16s} {'sweep s':>8s} "
        f"{'alone s':>8s}"
    )
    for a, member, (alone, seconds) in zip(amplitudes, swept[1:], separate, strict=True):
        m_its = sum(s.iterations for s in member.cycle_steps)
        a_its = sum(s.iterations for s in alone.cycle_steps)
        print(
            f"{a:7.0f} {len(member.cycle_steps):7d}/{m_its:<8d} {len(alone.cycle_steps):7d}/"
            f"{a_its:<8d} {member.seconds:8.1f} {seconds:8.1f}"
        )
    t_alone = float(np.sum([s for _, s in separate]))
    print(f"sweep {t_sweep:.0f} s, separate runs {t_alone:.0f} s: ratio {t_sweep / t_alone:.2f}")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "0.1 m, 2 amplitudes, one leg to +A")
    cli.add_argument("length", nargs="?", type=float, default=0.25, help="m (default 0.25)")
    cli.add_argument("n", nargs="?", type=int, default=10, help="amplitudes (default 10)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    if args.quick:
        main(0.1, 2, ["load.cycle=[1.0]"])
    else:
        main(args.length, args.n)
