"""Stick bending: what the slip measure and same-layer contact do to a strand's moment–curvature.

Run: .venv/bin/python benchmarks/stick_bending.py [strand ...] [--length L] [--slip M ...]
[--same-layer S ...] [--quick]
(--quick: the 1+6+12 over 0.1 m, surface slip, packed layers, to κ = 0.01 1/m)

Strands: "19" (Cardinal's core and layers 1–2, 0.3 m, 10 kN) and "cardinal" (0.6 m, 40 kN), each
with its own friction and Hertz + Mindlin contact. For each slip measure (surface, centreline:
``strand.contact.element``) and same-layer setting (off, nominal, packed:
``strand.model.same_layer``) it loads the uniform bending test monotonically through κ = 0.002,
0.01, 0.05, 0.1, 0.25, 0.5 1/m (nominal end curvature) and prints, one row per variant: the smeared
estimate's stick slope with the spin free (``strand.analytical.stick_bending_estimate``), the first
step's M/κ over EI_max, the zone moment M at each curvature beside the stick–slip law (cumulative
pressure), the slip onset per interface (the first of those κ at which 10 % of the interface's pairs
in the measuring zone slip; ">" none by 0.5), the share of same-layer pairs closed at the first
step, and the cost (wall time and Newton iterations, failed ones included). Loop areas need a full
cycle and are not measured here (the bending case's summary gives them). Prints the stamp (date,
commit, cores, command) first; a variant that stops prints why.
"""

import strand  # noqa: F401

# isort: split

import time
from functools import partial

import numpy as np
from harness import parser, stamp, table

from strand.analytical import StickSlipLaw, stick_bending_estimate
from strand.analytical.fibre import bending_stiffness_bounds
from strand.cable.description import Cable, cardinal
from strand.cable.geometry import build_geometry
from strand.contact.element import SLIP
from strand.model.cell_results import cell_results
from strand.model.contact_settings import ContactSettings
from strand.model.layer_states import SAME_LAYER
from strand.model.problem import StrandProblem
from strand.setups.bending import UniformBendingTest
from strand.solver import LoadStepFailure, LoadStepper, NewtonOptions

KAPPAS = (0.002, 0.01, 0.05, 0.1, 0.25, 0.5)  # 1/m, nominal
#: ``--quick``: strand, span (m), slip measure, same-layer setting, the curvatures of KAPPAS
QUICK = ("19", 0.1, "surface", "packed", KAPPAS[:2])


def strands() -> dict[str, tuple[Cable, float, float]]:
    """name: (cable, length m, tension N)."""
    c = cardinal()
    return {"19": (Cable("1+6+12", c.layers[:3]), 0.3, 10e3), "cardinal": (c, 0.6, 40e3)}


def bend(
    cable: Cable,
    length: float,
    tension: float,
    same_layer: str,
    slip: str,
    kappas: tuple[float, ...] = KAPPAS,
):
    """Tension, then the curvatures ``kappas`` (1/m) in turn; yields (zone record, problem,
    Newton iterations so far)."""
    geometry = build_geometry(cable, length, 4e-3)
    problem = StrandProblem(
        geometry,
        ContactSettings(same_layer=same_layer, slip=slip),
        NewtonOptions(atol=1e-3, max_it=15),
        setup=partial(UniformBendingTest, zone=length / 3),
    )
    setup = problem.setup
    pull = LoadStepper(problem.solver, 1e3, 1e3 / 64)  # as a run's [steps] tension and cuts
    pull.ramp(partial(setup.set, "tension"), 0.0, tension)
    bends = LoadStepper(problem.solver, KAPPAS[0], KAPPAS[0] / 64, extrapolate=True)
    for kappa in kappas:
        bends.ramp(partial(setup.set, "curvature"), setup.get("curvature"), kappa)
        cells = cell_results(problem.model, setup.direction)
        zone = setup.moment_curvature(cells, problem.solver.unconstrained_residual())
        its = sum(r.iterations + r.failed_iterations for r in pull.history + bends.history)
        yield zone, problem, its


def zone_slipping(problem) -> list[float]:
    """Per interface i | i + 1: the share of its pairs in the measuring zone that slip."""
    g = problem.model.geometry
    z = g.points[g.pairs.a, 2]
    lo, hi = problem.setup.measuring_zone
    inside = (z >= lo) & (z <= hi)
    slipping = problem.pair_results().slipping
    shares = []
    for i in range(len(g.cable.layers) - 1):
        mine = inside & (g.pairs.interface == i)
        shares.append(float(slipping[mine].mean()) if mine.any() else np.nan)
    return shares


def onset(shares: list[list[float]]) -> str:
    """The first κ of ``KAPPAS`` at which ≥ 10 % of each interface's zone pairs slip."""
    out = []
    for i in range(len(shares[0]) if shares else 0):
        hit = [k for k, row in zip(KAPPAS, shares, strict=False) if row[i] >= 0.1]
        out.append(f"{hit[0]:g}" if hit else ">")
    return "/".join(out) or "–"


def row(
    name: str,
    same_layer: str,
    slip: str,
    length: float | None,
    kappas: tuple[float, ...] = KAPPAS,
) -> list[str]:
    """The table's row of strand ``name`` under ``slip`` and ``same_layer``, bent through
    ``kappas`` (a start of ``KAPPAS``; the rest of the row's moments "–")."""
    cable, default_length, tension = strands()[name]
    length = length or default_length
    _, ei_max = bending_stiffness_bounds(cable)
    law = StickSlipLaw(cable, tension)
    estimate = stick_bending_estimate(cable).ratio
    cells, slope, closed, effort, shares = [], "", "", 0, []
    t0 = time.perf_counter()
    try:
        for zone, problem, its in bend(cable, length, tension, same_layer, slip, kappas):
            k, M, effort = zone.curvature, zone.moment_zone_middle, its
            if not cells:
                slope = f"{M / k / ei_max:.3f}"
                groups = problem.model.same_layer
                closed = f"{(groups[0].state.force > 0).mean():.2f}" if groups else "-"
            cells.append(f"{M:.2f} ({float(law.moment(k)):.2f})")
            shares.append(zone_slipping(problem))
        problem.solver.destroy()
        outcome = ""
    except LoadStepFailure as e:
        outcome = f" stopped: {str(e)[:90]}"
    cells += ["–"] * (len(KAPPAS) - len(cells))
    seconds = time.perf_counter() - t0
    return [
        f"{cable.name}, {length:g} m, {tension / 1e3:g} kN",
        slip,
        same_layer,
        f"{estimate:.3f}",
        slope or "–",
        *cells,
        onset(shares),
        closed,
        f"{seconds:.0f} s, {effort} its{outcome}",
    ]


def main() -> None:
    cli = parser(__doc__, "the 1+6+12 over 0.1 m, surface slip, packed layers, to 0.01 1/m")
    # choices are checked below: argparse checks a list default of nargs="*" against them whole
    cli.add_argument("strand", nargs="*", default=["19", "cardinal"], help=f"of {list(strands())}")
    cli.add_argument("--same-layer", nargs="*", default=["off", "nominal", "packed"])
    cli.add_argument("--slip", nargs="*", default=["surface", "centreline"])
    cli.add_argument("--length", type=float, help="span, m (default: the strand's)")
    given = cli.parse_args([])  # the defaults, to tell what was given
    args = cli.parse_args()
    for option, allowed in (("strand", strands()), ("same_layer", SAME_LAYER), ("slip", SLIP)):
        if unknown := set(getattr(args, option)) - set(allowed):
            cli.error(f"unknown {option} {sorted(unknown)}: choose from {list(allowed)}")
    kappas = KAPPAS
    if args.quick:
        mixed = [
            o
            for o in ("strand", "same_layer", "slip", "length")
            if getattr(args, o) != getattr(given, o)
        ]
        if mixed:
            cli.error(f"--quick runs its own strand and settings: drop {', '.join(mixed)}")
        name, length, slip, same_layer, kappas = QUICK
        args.strand, args.length, args.slip, args.same_layer = [name], length, [slip], [same_layer]
    print(stamp())
    head = [
        "strand",
        "slip",
        "same layer",
        "estimate",
        "M/κ / EI_max",
        *(f"M at {k:g} (law)" for k in KAPPAS),
        "slip onset κ",
        "closed",
        "cost",
    ]
    print(table([], head))
    for name in args.strand:
        for slip in args.slip:
            for same_layer in args.same_layer:
                print(
                    table([row(name, same_layer, slip, args.length, kappas)], head, head=False),
                    flush=True,
                )


if __name__ == "__main__":
    main()
