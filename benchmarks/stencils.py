"""Same-layer stencils against the mesh error: node to segment, nearest node, facing stations, at h
and h/2.

Run: .venv/bin/python benchmarks/stencils.py [--set key=value …] [--quick]
(default: Cardinal over 0.3 m, 40 kN, then the saddle to +4.3 kN; ``--set`` changes the case;
--quick: 0.05 m to +0.5 kN)

A discretisation change is acceptable where it moves the results by less than the mesh error.
Each stencil of ``[contact] same_layer_stencil`` runs at ``h_max`` and at ``h_max``/2; printed per
run, at the end of the tension and at the peak: midspan deflection and end displacement (µm),
the sum of the normal forces of the same-layer pairs of each layer and of the pairs of each
interface (N); then every run's difference from node-to-segment at h, beside the mesh error
(node-to-segment at h against h/2), with the element axial forces' largest difference against
the largest. Serial (the runs are small).
"""

import strand  # noqa: F401

# isort: split

import sys
import time

import numpy as np
from harness import add_settings, parser, stamp

from strand.app.build import build_problem
from strand.app.case import load_case
from strand.beam.parallel import serial_only
from strand.model.cell_results import cell_results
from strand.model.programme import run_programme

CASE = ["mesh.length=0.3", "load.cycle=[1.0]"]
QUICK = ["mesh.length=0.05", "load.lateral=500"]
#: ``[contact] same_layer_stencil``
VARIANTS = ["segment", "node", "facing"]


def state(problem) -> dict:
    """Measures of the current state: deflection, end displacement (m), same-layer forces per
    layer, pair forces per interface, and every wire's axial force at 19 stations from 0.05 to
    0.95 of the length (N; comparable between meshes)."""
    m = problem.model
    s = problem.setup.state()
    same = m.same_layer_history()["force"]
    layer = m.same_layer_pairs.layer
    pairs = m.pair_results().force
    interface = m.geometry.pairs.interface
    cells = cell_results(m)
    length = m.geometry.points[:, 2].max()
    stations = np.linspace(0.05, 0.95, 19) * length
    wires = np.unique(cells.wire)
    N = np.array(
        [np.interp(stations, cells.z[cells.wire == w], cells.axial[cells.wire == w]) for w in wires]
    )
    return {
        "deflection": s.deflection,
        "end": s.end_displacement,
        "same": np.array([same[layer == i].sum() for i in np.unique(layer)]),
        "pairs": np.array([pairs[interface == i].sum() for i in np.unique(interface)]),
        "N": N,
    }


def main(settings: list[str]) -> None:
    serial_only("benchmarks/stencils.py")
    print(f"stamp: {stamp()}\n")
    runs = {}
    for h in (1.0, 0.5):
        for stencil in VARIANTS:
            own = [f'contact.same_layer_stencil="{stencil}"']
            case = load_case(None, [*CASE, *own, *settings])
            case = load_case(None, [*CASE, *own, f"mesh.h_max={h * case.mesh.h_max}", *settings])
            problem, programme = build_problem(case)
            ends = []

            def on_step(stage, rec, position, problem=problem, ends=ends):
                if abs(rec.load - stage.target) < 1e-9 * max(1.0, abs(stage.target)):
                    ends.append(state(problem))

            t0 = time.perf_counter()
            run_programme(problem, programme, on_step=on_step)
            name = f"{stencil}, h{'' if h == 1 else '/2'}"
            runs[name] = (ends, time.perf_counter() - t0, len(problem.geometry.points) * 6)
            problem.solver.destroy()
            print(f"ran {name}: {runs[name][2]} unknowns, {runs[name][1]:.0f} s", file=sys.stderr)
    print(f"# same-layer stencils, {' '.join([*CASE, *settings])}\n")
    for k, label in enumerate(("end of tension", "peak")):
        print(
            f"{label}: {'run':14s} {'deflection µm':>13s} {'end µm':>9s}  same-layer per layer "
            f"(N) | pairs per interface (N)"
        )
        for name, (ends, _, _) in runs.items():
            e = ends[k]
            print(
                f"  {name:28s} {1e6 * e['deflection']:13.3f} {1e6 * e['end']:9.4f}  "
                + " ".join(f"{x:8.1f}" for x in e["same"])
                + " | "
                + " ".join(f"{x:8.1f}" for x in e["pairs"])
            )
        ref = runs["segment, h"][0][k]
        print(
            f"  differences from segment, h: {'deflection':>10s} {'end':>9s} {'N / max N':>10s} "
            "same-layer per layer | pairs per interface"
        )
        for name, (ends, _, _) in runs.items():
            if name == "segment, h":
                continue
            e = ends[k]
            dN = np.abs(e["N"] - ref["N"]).max() / np.abs(ref["N"]).max()
            print(
                f"  {name:28s} {1e6 * (e['deflection'] - ref['deflection']):10.3f} "
                f"{1e6 * (e['end'] - ref['end']):9.4f} {dN:10.1e} "
                + " ".join(f"{x:8.1f}" for x in e["same"] - ref["same"])
                + " | "
                + " ".join(f"{x:8.1f}" for x in e["pairs"] - ref["pairs"])
            )


if __name__ == "__main__":
    cli = parser(__doc__, "0.05 m to +0.5 kN")
    add_settings(cli, "steps.retry=true")
    args = cli.parse_args()
    main([*(QUICK if args.quick else []), *args.settings])
