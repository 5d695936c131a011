"""Contact compliance and the strand's moment–curvature: penalty + elastic slip against Hertz + Mindlin.

Run: .venv/bin/python benchmarks/bending_compliance.py [kappa_max] [length] [--quick]
(--quick: the seed's penalty and Hertz + Mindlin on 0.1 m to 0.01 1/m)

Runs the uniform bending test (Cardinal, 40 kN, first loading leg to kappa_max, default 0.1 1/m,
on a length default 1 m) with the seed paper's penalty (K_N = 5e4 N/mm) and elastic slips g_lim of
0.5, 1, 5 (the seed's) and 25 µm, and with contact mechanics (``[contact] compliance = "hertz"``).
Prints, per variant: the first-step slope M/κ against EI_max, M at 0.01, 0.05 and 0.1 1/m beside the
stick–slip law (cumulative pressure), the curvature at which 10 % of each interface's pairs slip, and
the cost (wall time, Newton iterations).
"""

import strand  # noqa: F401

# isort: split

import io
import time

from harness import parser, peak_mib, stamp

from strand.analytical import StickSlipLaw
from strand.analytical.fibre import bending_stiffness_bounds
from strand.app.case import case_from_dict
from strand.app.run import run_case
from strand.cable.description import cardinal

#: variant: (output folder, [contact] settings)
VARIANTS = {
    "penalty, g_lim 0.5 µm": ("penalty_0.5um", {"compliance": "penalty", "g_lim": 0.5e-6}),
    "penalty, g_lim 1 µm": ("penalty_1um", {"compliance": "penalty", "g_lim": 1e-6}),
    "penalty, g_lim 5 µm": ("penalty_5um", {"compliance": "penalty", "g_lim": 5e-6}),
    "penalty, g_lim 25 µm": ("penalty_25um", {"compliance": "penalty", "g_lim": 25e-6}),
    "Hertz + Mindlin": ("hertz", {"compliance": "hertz"}),
}
KAPPAS = (0.01, 0.05, 0.1)
#: ``--quick``: kappa_max (1/m), length (m), variants
QUICK = (0.01, 0.1, ("penalty, g_lim 5 µm", "Hertz + Mindlin"))


def main(
    kappa_max: float = 0.1, length: float = 1.0, variants: tuple[str, ...] = tuple(VARIANTS)
) -> None:
    print(f"stamp: {stamp()}\n")
    rows = []
    for name in variants:
        key, contact = VARIANTS[name]
        case = case_from_dict(
            {
                "mesh": {"length": length},
                "load": {
                    "kind": "bending",
                    "curvature": kappa_max,
                    "cycle": [1.0],
                    "zone": 0.4 * length,
                },
                "steps": {"curvature": 0.0025, "curvature_max": 0.025},
                "contact": contact,
            }
        )
        folder = f"results/benchmark_bending/{key}"
        t0 = time.perf_counter()
        result = run_case(case, folder, stream=io.StringIO(), overwrite=True)
        seconds = time.perf_counter() - t0
        report = result.reference  # the run's BendingReport (None before a bending step)
        moments = {k: (m, law) for k, m, law, _ in (report.table if report else [])}
        rows.append((name, report, moments, seconds, result))
        print(f"  done: {name} ({seconds:.0f} s)", flush=True)
    ei_min, ei_max = bending_stiffness_bounds(cardinal())
    print(
        f"\nCardinal, L = {length} m, T = 40 kN, uniform bending to {kappa_max} 1/m "
        f"(EI_max {ei_max:.0f}, EI_min {ei_min:.1f} N m²)"
    )
    head = f"{'variant':24s} {'M/κ₀ / EI_max':>13s}"
    head += "".join(f" {'M(' + str(k) + ') N m':>13s}" for k in KAPPAS)
    head += f" {'slip onset 0|1 1|2 2|3 3|4 (1/m)':>34s} {'time s':>7s} {'its':>5s}"
    print(head)
    law_row = f"{'stick–slip law':24s} {'':>13s}"
    for name, report, moments, seconds, result in rows:
        if not report:
            print(f"{name:24s} FAILED before the first bending step: {result.failure}")
            continue
        line = f"{name:24s} {report.initial_slope / report.ei_max:13.3f}"
        line += "".join(
            f" {moments[k][0]:13.2f}" if k in moments else f" {'-':>13s}" for k in KAPPAS
        )
        onset = " ".join(f"{v:6.3f}" for v in report.slip_onset)
        line += f" {onset:>34s} {seconds:7.0f} {result.iterations:5d}"
        if result.failure:
            line += f"  FAILED: {result.failure}"
        print(line)
    law = StickSlipLaw(cardinal(), 40e3, "cumulative")
    law_row += "".join(f" {float(law.moment(k)):13.2f}" for k in KAPPAS)
    law_row += f" {' '.join(f'{v:6.3f}' for v in law.slip_onset):>34s}"
    print(law_row)
    peak = peak_mib()
    print(f"peak memory (MiB): {peak:.0f}")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "two variants on 0.1 m to 0.01 1/m")
    cli.add_argument("kappa_max", nargs="?", type=float, default=0.1, help="1/m (default 0.1)")
    cli.add_argument("length", nargs="?", type=float, default=1.0, help="m (default 1)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    if args.quick:
        main(*QUICK)
    else:
        main(args.kappa_max, args.length)
