"""Contact stabilisation (``[steps] stabilise``): a near-mechanism's tension start, per spring.

Run: .venv/bin/python benchmarks/stabilisation.py [--quick] [--length L] [k …]

The strand: Cardinal's core and first two layers (1+6+12), its steel ring vaulted over the core
(``first_layer = "ring"``: a ring of touching circles holds only by its wires' bending), ``L``
long (default 0.5 m), pulled to 15 kN on one process, outputs off. One run per spring stiffness
k (N/m per pair; 0: no stabilisation; default 0 1e3 1e4 1e5). Prints per run: steps, Newton
iterations (+ in failed attempts), LUs, wall time, the steps held and the largest energy
fraction of the springs, and the strain against the fibre model; then, at 15 kN, each run's
largest differences from the first converged run with springs: element axial forces and
contact pair forces, each against the largest. ``--quick``: 0.2 m to 2 kN (a smoke test).
"""

from __future__ import annotations

import strand  # noqa: F401  (dolfinx's environment first)

# isort: split

import io
import tempfile
import time
from pathlib import Path

import numpy as np
from harness import parser, stamp, table

from strand.analytical.fibre import fibre_model
from strand.app.case import case_from_dict
from strand.app.case_toml import cable_table
from strand.app.run import run_case
from strand.cable.description import cardinal


def ring_case(length: float, tension: float, k: float) -> dict:
    """The vaulted 1+6+12 (module docstring) with springs of ``k`` N/m."""
    cable = cable_table(cardinal())
    cable["layer"] = cable["layer"][:2]
    return {
        "cable": cable | {"name": "1+6+12"},
        "mesh": {"length": length},
        "load": {"tension": tension, "cycle": [0.0]},
        "contact": {"first_layer": "ring"},
        "steps": {"stabilise": k},
        "output": {"fields": False, "plots": False, "checkpoint": False},
        "fatigue": {"outputs": False},
    }


def main(springs: list[float], length: float, tension: float) -> None:
    print(f"stamp: {stamp()}")
    rows, ends = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        for k in springs:
            case = case_from_dict(ring_case(length, tension, k))
            t0 = time.perf_counter()
            r = run_case(case, Path(tmp) / f"k{k:g}", stream=io.StringIO())
            seconds = time.perf_counter() - t0
            held = [s.stabilisation for s in r.steps if s.stabilisation]
            reached = r.steps[-1].load if r.steps else 0.0
            strain = np.nan
            if not r.failure:
                ends[k] = (r.tension_end.axial, r.tension_end_pairs.force)
                end = [s for s in r.steps if s.parameter == "tension"][-1]
                fibre = fibre_model(case.cable, tension)["strain"]
                strain = end.state.end_displacement / length / fibre - 1
            rows.append(
                [
                    f"{k:g}",
                    "FAILED at " + f"{reached:g} N" if r.failure else f"{reached:g} N",
                    len(r.steps),
                    f"{r.iterations} + {r.failed_iterations}",
                    r.factorisations,
                    f"{seconds:.0f}",
                    len(held),
                    f"{max(held):.1e}" if held else "-",
                    f"{100 * strain:+.1f} %",
                ]
            )
    columns = ["k (N/m)", "reached", "steps", "its + failed", "LUs", "s", "held", "energy"]
    print("\n" + table(rows, [*columns, "strain vs fibre model"]))
    if not ends:
        return
    first = next(iter(ends))
    N0, p0 = ends[first]
    print(f"\nat {tension:g} N, against k = {first:g} (each against the largest):")
    cells = [
        [
            f"{k:g}",
            f"{np.abs(N - N0).max() / np.abs(N0).max():.1e}",
            f"{np.abs(p - p0).max() / np.abs(p0).max():.1e}",
        ]
        for k, (N, p) in ends.items()
    ]
    print(table(cells, ["k (N/m)", "axial forces", "pair forces"]))


if __name__ == "__main__":
    cli = parser(__doc__, "0.2 m to 2 kN")
    cli.add_argument("springs", nargs="*", type=float, default=[0.0, 1e3, 1e4, 1e5], help="N/m")
    cli.add_argument("--length", type=float, default=0.5, help="m (default 0.5)")
    args = cli.parse_args()
    if args.quick:
        main(args.springs, 0.2, 2e3)
    else:
        main(args.springs, args.length, 15e3)
