"""Layer states in uniform bending: Cardinal's moment–curvature for each state its geometry allows.

Run: .venv/bin/python benchmarks/layer_states.py [state ...] [--ranks N] [--quick] [--keep DIR]

Each state is a set of ``[contact]`` settings (or a cable edit) on ``cases/cardinal_bending.toml``
(1 m, 40 kN, measuring zone 0.4 m), run to the end of the first leg (κ = 0.5 1/m) by the
application on ``--ranks`` processes (default 2), without field, checkpoint, figure or fatigue
outputs:

* ``packed`` (the default): every layer's spare circumference bunched in one gap;
* ``nominal``: spread evenly over the gaps;
* ``random``: split at random (``gap_seed`` 0);
* ``ring``: packed, the steel layer a vault standing off the core (``first_layer = "ring"``);
* ``king``: packed, on a king wire 3.40 mm thick (the cable's ``core.diameter``): the steel
  layer's gaps open; ``king-microslip``: the same with Mindlin–Deresiewicz's kink-free law
  (``compliance = "hertz_microslip"``);
* ``mu0.7``, ``mu1.0``: packed, the Coulomb coefficient of layers 1–3 (with the next layer out
  and between their own wires) 0.7 or 1.0 instead of the seed's 0.5; ``core0.6``: the core's
  (with layer 1) 0.6 instead of 0.3;
* ``lay-short``, ``lay-long``: packed, every layer at the shortest or longest lay length EN 50182
  allows (``EN50182``; Cardinal's own are within it).

One row per state: the first step's secant M/κ over EI_max; the zone's moment M (N m) at the
curvatures of ``KAPPAS`` (the zone's own curvature, interpolated between steps), the stick–slip
law (``strand.analytical.StickSlipLaw``, cumulative pressure, the same friction and lay angles)
in brackets; the mean crossing force per interface after tension (N; N/m for the core's line
contact); the slip onset per interface (the first curvature at which 10 % of its pairs in the
zone slip, ``>`` none); and the cost: wall time, Newton iterations (+ failed), LUs. ``--quick``
runs 0.1 m to 0.02 1/m on one process (a smoke test: its numbers mean nothing). Prints the stamp
first; a state whose run stops says so in its row.
"""

from __future__ import annotations

import strand  # noqa: F401  (dolfinx's environment first)

# isort: split

import csv
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from harness import ROOT, parser, stamp, table

from strand.analytical import StickSlipLaw
from strand.app.case import load_case
from strand.cable.description import cardinal

#: curvatures (1/m) at which M is reported: the held-back test's points, and the end of the leg
KAPPAS = (0.0035, 0.0083, 0.0132, 0.0167, 0.049, 0.103, 0.143, 0.239, 0.428, 0.5)
CASE = ROOT / "cases" / "cardinal_bending.toml"
#: state: its settings (``--set`` items)
STATES = {
    "packed": [],
    "nominal": ['contact.same_layer="nominal"'],
    "random": ['contact.same_layer="random"', "contact.gap_seed=0"],
    "ring": ['contact.first_layer="ring"'],
    "king": ["cable.core.diameter=3.40e-3"],
    "king-microslip": ["cable.core.diameter=3.40e-3", 'contact.compliance="hertz_microslip"'],
    # the friction's weight: packed, with other Coulomb coefficients
    "mu0.7": [f"cable.layer.{i}.friction=0.7" for i in (1, 2, 3)],
    "mu1.0": [f"cable.layer.{i}.friction=1.0" for i in (1, 2, 3)],
    "core0.6": ["cable.core.friction=0.6"],
}
#: EN 50182's lay ratios (lay length over the layer's outer diameter; its §5.5.4–5.5.5 as RTE's
#: pallas encodes them, ``strdcable.overheadlines.laybounds_EN50182``): steel layer of a 1+6
#: core, inner aluminium layers, outer aluminium layer
EN50182 = {"steel": (16.0, 26.0), "inner": (10.0, 16.0), "outer": (10.0, 14.0)}


def lay_angles(ratio_at: int) -> list[str]:
    """``--set`` items giving Cardinal's layers the shortest (``ratio_at`` 0) or longest (1) lay
    lengths EN 50182 allows, at their radii."""
    layers = cardinal().layers[1:]
    items = []
    for i, layer in enumerate(layers, start=1):
        kind = "steel" if i == 1 else "outer" if i == len(layers) else "inner"
        pitch = EN50182[kind][ratio_at] * (2 * layer.radius + layer.wire.diameter)
        angle = np.degrees(np.arctan(2 * np.pi * layer.radius / pitch))
        items.append(f"cable.layer.{i}.lay_angle={angle:.3f}")
    return items


STATES |= {"lay-short": lay_angles(0), "lay-long": lay_angles(1)}
#: the first leg alone, no outputs but the tables
COMMON = [
    "load.cycle=[1.0]",
    "output.fields=false",
    "output.plots=false",
    "output.checkpoint=false",
    "fatigue.outputs=false",
]
QUICK = ["mesh.length=0.1", "load.zone=0.04", "load.curvature=0.02", "steps.curvature=0.01"]


def run_state(name: str, ranks: int, quick: bool, folder: Path) -> tuple[dict, float]:
    """Runs state ``name`` into ``folder``; returns what it wrote and its wall time (s)."""
    items = STATES[name] + COMMON + (QUICK if quick else [])
    command = [sys.executable, "-m", "strand.app", "run", str(CASE), "--out", str(folder)]
    command += [a for item in items for a in ("--set", item)]
    if ranks > 1:
        command = [str(Path(sys.executable).parent / "mpirun"), "-n", str(ranks), *command]
    t0 = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if not (folder / "summary.txt").is_file():
        raise RuntimeError(f"{name}: no summary ({done.stderr.strip()[-300:]})")
    return read_run(folder), seconds


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_run(folder: Path) -> dict:
    """The curvature, moment, slip and cost of a bending run's tables."""
    mc = _rows(folder / "moment_curvature.csv")
    steps = _rows(folder / "steps.csv")
    slip = _rows(folder / "slip.csv")
    summary = (folder / "summary.txt").read_text()
    forces = re.search(r"mean contact force, middle half: (.*)", summary)
    secant = re.search(r"first step M/κ = \S+ N m² = (\S+) EI_max", summary)
    if not mc:
        failure = re.search(r"failure: (.{0,120})", summary)
        raise RuntimeError(f"stopped before bending: {failure.group(1) if failure else '?'}")
    kappa = np.array([float(r["curvature_1_per_m"]) for r in mc])
    moment = np.array([float(r["moment_zone_middle_Nm"]) for r in mc])
    leg = np.arange(int(np.argmax(kappa)) + 1)  # the loading leg: up to the largest curvature
    interfaces = [k for k in slip[0] if k.startswith("slipping_")]
    return {
        "kappa": kappa[leg],
        "moment": moment[leg],
        "secant": float(secant.group(1)) if secant else np.nan,
        "forces": forces.group(1).replace(" N/m", "").replace(" N", "") if forces else "–",
        "slip_kappa": np.array([float(r["curvature_1_per_m"]) for r in slip]),
        "slipping": np.array([[float(r[k]) for k in interfaces] for r in slip]),
        "iterations": sum(int(r["iterations"]) for r in steps),
        "failed": sum(int(r["failed_iterations"]) for r in steps),
        "lus": sum(int(r["factorisations"]) for r in steps),
        "stopped": summary.startswith("FAILED"),
    }


def moment_at(run: dict, kappas) -> list[float]:
    """M (N m) at ``kappas`` on the loading leg (NaN beyond the curvature it reached)."""
    k, m = run["kappa"], run["moment"]
    return [float(np.interp(x, k, m)) if k[0] <= x <= k[-1] else np.nan for x in kappas]


def onsets(run: dict) -> str:
    """Per interface, the first curvature at which 10 % of its zone pairs slip."""
    k, share = run["slip_kappa"], run["slipping"]
    out = []
    for i in range(share.shape[1]):
        hit = np.flatnonzero((share[:, i] >= 0.1) & (k > 0))
        out.append(f"{k[hit[0]]:.3g}" if len(hit) else ">")
    return " / ".join(out)


def row(name: str, run: dict, seconds: float, law) -> list[str]:
    cells = [
        f"{m:.1f} ({float(law.moment(k)):.1f})" if np.isfinite(m) else "–"
        for m, k in zip(moment_at(run, KAPPAS), KAPPAS, strict=True)
    ]
    stopped = " (stopped)" if run["stopped"] else ""
    return [
        name + stopped,
        f"{run['secant']:.3f}",
        *cells,
        run["forces"],
        onsets(run),
        f"{seconds:.0f} s, {run['iterations']} + {run['failed']} its, {run['lus']} LUs",
    ]


def main() -> None:
    cli = parser(__doc__, "0.1 m to 0.02 1/m, one process")
    # choices are checked below: argparse checks a list default of nargs="*" against them whole
    cli.add_argument("states", nargs="*", default=list(STATES), help=f"of {list(STATES)}")
    cli.add_argument("--ranks", type=int, default=2, help="MPI ranks per state (default 2)")
    cli.add_argument("--keep", type=Path, help="keep each state's run in this folder")
    args = cli.parse_args()
    if unknown := set(args.states) - set(STATES):
        cli.error(f"unknown state {sorted(unknown)}: choose from {list(STATES)}")
    ranks = 1 if args.quick else args.ranks
    print(stamp())
    head = ["state", "M/κ / EI_max", *(f"M at {k:g}" for k in KAPPAS)]
    head += ["crossing force after tension 0|1 … 3|4", "slip onset κ 0|1 … 3|4", "cost"]
    print(table([], head))
    with tempfile.TemporaryDirectory() as scratch:
        base = args.keep or Path(scratch)
        for name in args.states:
            case = load_case(CASE, STATES[name] + (QUICK if args.quick else []))
            law = StickSlipLaw(case.cable, case.load.tension)
            try:
                run, seconds = run_state(name, ranks, args.quick, base / name)
                cells = row(name, run, seconds, law)
            except RuntimeError as e:
                cells = [f"{name}: {e}"] + ["–"] * (len(head) - 1)
            print(table([cells], head, head=False), flush=True)


if __name__ == "__main__":
    main()
