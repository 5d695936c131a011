"""Small vs large sliding on the same mesh, laws and solver: forces, deflections, cost.

Run: .venv/bin/python benchmarks/sliding_comparison.py [helix|cardinal] [P_max_N] [length_m]
[--quick]   (--quick: the helix over 0.05 m to 200 N)

Contacts use the seed paper's penalty compliance (compliance = "penalty"), as in the README table.
(a) helix: a 1+6 strand (Cardinal's core and first layer: six helices wound on a straight core),
    0.2 m, 40 kN, saddle to 600 N;
(b) cardinal: the full conductor, 1 m, 40 kN, saddle to 4.3 kN (one loading leg).
Prints, for each model, the steps, Newton iterations and wall time measured in this run, the
matrix size and MUMPS factor memory, the midspan deflection, and per layer (and per 45° sector)
the largest difference of the wire axial forces at the largest load relative to that layer's
force range. Writes results/sliding_comparison_<case>.png: the axial forces of both models along
z per layer, and their difference coloured by sector. (`strand compare [case.toml]` does the same
for the full cycle of a case, with every output of `strand run` for both models.)
"""

import strand  # noqa: F401

# isort: split

import time
from pathlib import Path

from harness import parser, stamp

from strand.app.compare import difference_table, overlay_figure
from strand.cable.description import Cable, cardinal
from strand.cable.geometry import build_geometry
from strand.model.cell_results import cell_results
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups import SaddleTest
from strand.solver import LoadStepper, NewtonOptions


def run(geometry, model: str, tension: float, p_max: float, p_step: float) -> dict:
    t0 = time.perf_counter()
    problem = StrandProblem(
        geometry,
        ContactSettings(model=model, compliance="penalty"),
        NewtonOptions(atol=1e-2, max_it=15),
        setup=SaddleTest,
    )
    setup = time.perf_counter() - t0
    steps = LoadStepper(problem.solver, tension / 4, tension / 256)
    steps.ramp(problem.setup.set_tension, 0.0, tension, "tension")
    lateral = LoadStepper(
        problem.solver, p_step, p_step / 64, max_step=1.6 * p_step, extrapolate=True
    )
    lateral.ramp(problem.setup.set_lateral, 0.0, p_max, "lateral")
    seconds = time.perf_counter() - t0
    history = steps.history + lateral.history
    factor = problem.solver.solver.getKSP().getPC().getFactorMatrix()
    timings = problem.solver.timings
    return {
        "model": model,
        "seconds": seconds,
        "setup": setup,
        "contact": timings["terms"],
        "iterations": sum(r.iterations for r in history),
        "steps": len(history),
        "cuts": sum(r.cuts for r in history),
        "deflection": problem.setup.midspan_deflection(),
        "cells": cell_results(problem.model),
        "nnz": problem.solver.A.getInfo()["nz_used"],
        "mumps_mb": factor.getMumpsInfog(22),  # MB used by the factorisation (all processes)
    }


def main(which: str = "helix", p_max: float | None = None, length: float | None = None) -> None:
    print(f"stamp: {stamp()}\n")
    if which == "helix":
        c = cardinal()
        geometry = build_geometry(
            Cable("1+6 (Cardinal core and layer 1)", c.layers[:2]), length or 0.2
        )
        p_max, p_step = p_max or 600.0, 100.0
    elif which == "cardinal":
        geometry = build_geometry(cardinal(), length or 1.0)
        p_max, p_step = p_max or 4300.0, 250.0
    else:
        raise SystemExit(f"unknown case {which!r}: helix or cardinal")
    res = [run(geometry, m, 40e3, p_max, p_step) for m in ("small", "large")]
    small, large = res
    print(f"{geometry.cable.name}, L = {geometry.length} m, T = 40 kN, saddle 0 → {p_max:.0f} N")
    print(
        f"{'model':6s} {'steps':>5s} {'cuts':>4s} {'Newton its':>10s} {'time s':>7s} "
        f"{'s/it':>5s} {'contact s':>9s} {'nnz':>9s} {'MUMPS MB':>8s} {'δ mm':>7s}"
    )
    for r in res:
        print(
            f"{r['model']:6s} {r['steps']:5d} {r['cuts']:4d} {r['iterations']:10d} "
            f"{r['seconds']:7.1f} {r['seconds'] / r['iterations']:5.2f} {r['contact']:9.1f} "
            f"{r['nnz']:9.3g} {r['mumps_mb']:8d} {1e3 * r['deflection']:7.3f}"
        )
    n_layers = len(geometry.cable.layers)
    print(difference_table(small["cells"], large["cells"], n_layers))
    print(
        f"deflection difference {100 * (large['deflection'] / small['deflection'] - 1):+.2f} %; "
        f"speed ratio (large / small wall time): {large['seconds'] / small['seconds']:.2f}"
    )
    title = f"{geometry.cable.name}, L = {geometry.length:g} m: wire axial forces at {p_max:g} N"
    out = Path("results") / f"sliding_comparison_{which}.png"
    overlay_figure(small["cells"], large["cells"], n_layers, title, out)
    print(f"overlay: {out}")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    cli = parser(__doc__, "the helix over 0.05 m to 200 N")
    cli.add_argument("case", nargs="?", default="helix", choices=["helix", "cardinal"])
    cli.add_argument("p_max", nargs="?", type=float, help="N (default 600 helix, 4300 cardinal)")
    cli.add_argument("length", nargs="?", type=float, help="m (default 0.2 helix, 1 cardinal)")
    args = cli.parse_args()
    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    if args.quick:
        main("helix", 200.0, 0.05)
    else:
        main(args.case, args.p_max, args.length)
