"""strand's command line: ``strand run``, ``strand mesh``, ``strand compare`` and ``strand
spectrum`` (see ``USAGE``, printed by ``strand --help``)."""

from __future__ import annotations

import argparse
import sys
import textwrap
import time

import numpy as np

#: the name that runs the built-in default case (the seed paper's test on Cardinal)
DEFAULT_CASE = "cardinal"

USAGE = """\
strand run  case.toml     the main job: tension, then the case's cycle; writes fields, CSV tables,
                          figures and the whole case (case.toml) into its results folder
strand run  cardinal      the built-in case: the seed paper's saddle test on Cardinal, 1 m, 40 kN
                          (~370 MB of results in results/cardinal; its time: the README, `make run`)
strand mesh [case.toml]   build the strand mesh and contact pairs, print the table, draw them
strand compare case.toml | cardinal
                          run the case with small- and large-sliding contact; compare forces,
                          deflections and cost
strand spectrum history.csv --column lateral_N [--bins 3] [--time-column time_s --period 1y]
                          count the cycles of a load history by rainflow and print the
                          [fatigue] spectrum to paste into a case file

--set section.key=value changes one setting of the case (repeatable), e.g. --set mesh.length=0.5;
in the cable: --set cable.core.nu=0.28, --set cable.layer.2.E=60e9 (layer 1: the innermost).
Exit codes: 0 done, 2 bad input (one line on stderr, nothing computed), 3 a load step failed,
130 interrupted (Ctrl-C); a stopped run keeps every step written so far, with its summary.
"""


def mesh_table(geometry) -> str:
    """The mesh table (per layer) and the pair counts (per interface and type), as text."""
    g = geometry
    lengths = g.cell_lengths()
    lines = [
        f"{g.cable.name}: L = {g.length * 1e3:g} mm, h_max = {g.h_max * 1e3:g} mm, "
        f"{len(g.wire_layer)} wires, {len(g.cells)} elements, {len(g.points)} nodes",
        "",
        "layer  wires  elements/wire  mean length (mm)  max length (mm)",
    ]
    for i, lay in enumerate(g.cable.layers):
        m = g.cell_layer == i
        lines.append(
            f"{'core' if i == 0 else i:>5}  {lay.wires:>5}  {m.sum() / lay.wires:>13.1f}  "
            f"{lengths[m].mean() * 1e3:>16.3f}  {lengths[m].max() * 1e3:>15.3f}"
        )
    lines += ["", "interface  type      pairs  closed form  max |gap| (m)"]
    p, gaps = g.pairs, g.gaps()
    for i in range(len(g.cable.layers) - 1):
        for kind, name in ((1, "line"), (0, "crossing")):
            m = (p.interface == i) & (p.kind == kind)
            if not m.any():
                continue
            if kind == 0:
                a, b = g.cable.layers[i], g.cable.layers[i + 1]
                closed = f"{a.wires * b.wires * g.length * (1 / a.pitch + 1 / b.pitch):11.1f}"
            else:
                closed = f"{'-':>11}"
            lines.append(
                f"{i:>4}|{i + 1:<4}  {name:<8}  {m.sum():>5}  {closed}  {np.abs(gaps[m]).max():.1e}"
            )
    lines.append(f"{'all':<9}  {'':<8}  {len(p):>5}")
    if g.facing is not None:
        lines += _facing_table(g)
    return "\n".join(lines)


def _facing_table(g) -> list[str]:
    """The same-layer pairs on facing stations per layer: their count, the layer's facing offset
    δ and how far from it the pairs' nodes lie."""
    from ..cable.facing import facing_offset

    f = g.facing
    layer = g.wire_layer[g.point_wire[f.a]]
    dz = g.points[f.c, 2] - g.points[f.a, 2]
    lines = ["", "layer  facing pairs  offset δ (µm)  max |Δz − δ| (m)"]
    for i in np.unique(layer):
        m = layer == i
        delta = facing_offset(g.cable.layers[i])
        error = np.abs(dz[m] - delta).max()
        lines.append(f"{i:>5}  {m.sum():>12}  {delta * 1e6:>+13.2f}  {error:.1e}")
    return lines


def _mesh(args) -> int:
    from ..beam.parallel import is_root, on_root
    from ..cable.geometry import build_geometry
    from .case import load_case
    from .folder import writable_folder

    case = load_case(args.case, args.set)
    out = on_root(lambda: writable_folder(args.out))
    t0 = time.perf_counter()
    geometry = build_geometry(
        case.cable,
        case.mesh.length,
        case.mesh.h_max,
        facing=case.contact.facing_stations,
    )
    t_geo = time.perf_counter() - t0
    from ..cable.mesh import cable_mesh, write_centrelines
    from ..model.model import strand_stencils

    t0 = time.perf_counter()
    stencils = strand_stencils(geometry, case.contact)
    mesh = cable_mesh(geometry, stencils=stencils).mesh
    t_mesh = time.perf_counter() - t0
    if not is_root():  # the table, the file and the picture once
        return 0
    print(mesh_table(geometry))
    ranks = mesh.comm.size
    where = f" on {ranks} MPI ranks (axial slabs)" if ranks > 1 else ""
    print(f"\nbuilt in {t_geo:.3f} s (geometry and pairs) + {t_mesh:.3f} s (dolfinx mesh{where})")
    write_centrelines(geometry, out / "centrelines.vtu")
    if not args.no_picture:
        from ..cable.pictures import strand_picture

        print("picture:", strand_picture(geometry, out / "mesh.png"))
    return 0


def _case_to_run(args, parser):
    """The case ``args.case`` names (a case file, or ``DEFAULT_CASE`` for the built-in one),
    every setting checked before any computing (its loads, by the run: ``build.check_folder``);
    None, after the usage, if none is named."""
    from pathlib import Path

    from .case import load_case

    if args.case is None:
        parser.print_usage(sys.stderr)
        print(
            f"strand {args.command}: give a case file, or '{DEFAULT_CASE}' for the built-in case "
            f"(strand {args.command} {DEFAULT_CASE}: the seed paper's test on Cardinal, 1 m, "
            "40 kN; ~370 MB of results, and the time the README gives for `make run`)",
            file=sys.stderr,
        )
        return None
    builtin = args.case.lower() == DEFAULT_CASE and not Path(args.case).exists()
    return load_case(None if builtin else args.case, args.set)


def _run(args, parser) -> int:
    from .errors import CaseError

    if args.template:
        from .settings_schema import template

        print(template(), end="")
        return 0
    case = _case_to_run(args, parser)  # every setting is checked here, before computing
    if case is None:
        return 2
    from .run import run_case

    if case.load.sweep:
        from .run import run_sweep

        if args.restart:
            raise CaseError("--restart: a sweep starts from its own tensioned state; give one")
        results = run_sweep(case, args.out, overwrite=args.overwrite)
        if any(r.interrupted for r in results):
            return 130
        return 3 if any(r.failure for r in results) else 0
    result = run_case(case, args.out, overwrite=args.overwrite, restart=args.restart)
    return 130 if result.interrupted else 3 if result.failure else 0


def _compare(args, parser) -> int:
    case = _case_to_run(args, parser)
    if case is None:
        return 2
    from .compare import compare_case

    compare_case(case, args.out, overwrite=args.overwrite)
    return 0


def _spectrum(args) -> int:
    from .fatigue.load_history import HistoryError, history_spectrum, parse_period, spectrum_block

    if args.bins < 1:
        raise HistoryError(f"--bins {args.bins}: expected a positive whole number of classes")
    h = history_spectrum(
        args.history,
        args.column,
        args.bins,
        args.time_column,
        args.tension_column,
        args.scale,
        None if args.period is None else parse_period(args.period),
    )
    text = spectrum_block(h, args.history)
    if args.output:
        from pathlib import Path

        try:
            Path(args.output).write_text(text)
        except OSError as e:
            raise HistoryError(
                f"--output {args.output}: cannot be written ({e.strerror})"
            ) from None
    print(text, end="")
    return 0


class _Parser(argparse.ArgumentParser):
    """An argument parser whose description may end with the text of ``more_description()``,
    made only when the help is printed (``strand run``'s settings: they import every set-up
    kind, and with them dolfinx)."""

    def __init__(self, *args, more_description=None, **kwargs):
        super().__init__(*args, **kwargs)
        self.more_description = more_description

    def format_help(self) -> str:
        if self.more_description is not None:
            self.description = (self.description or "") + self.more_description()
            self.more_description = None
        return super().format_help()


def main(argv: list[str] | None = None) -> int:
    from ..beam.parallel import abort_on_error

    abort_on_error()  # an error on one rank of a distributed run ends them all
    parser = argparse.ArgumentParser(
        prog="strand", description=USAGE, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    from .. import __version__

    parser.add_argument("--version", action="version", version=f"strand {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    from .settings_reference import help_text

    run = sub.add_parser(
        "run",
        help=f"tension then the case's cycle ({DEFAULT_CASE!r}: the seed paper's test)",
        description=textwrap.fill(
            "Run a tension-bending case. Every setting lives in a TOML case file; a case lists "
            "only what it changes, and --set section.key=value changes one more. The settings, "
            "their defaults and what they mean (in full: the settings reference of the docs):",
            100,
        )
        + "\n\n",
        more_description=help_text,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    run.add_argument(
        "case", nargs="?", help=f"case file (TOML), or {DEFAULT_CASE!r} for the built-in case"
    )
    run.add_argument("--out", help="results folder (default: [output] folder, or results/<case>)")
    run.add_argument(
        "--template",
        action="store_true",
        help="print a case file with every setting at its default, its unit and meaning; "
        "run nothing",
    )
    run.add_argument(
        "--overwrite",
        action="store_true",
        help="replace the results of an earlier run in the folder (refused otherwise)",
    )
    run.add_argument(
        "--restart",
        metavar="CHECKPOINT",
        help="continue from a checkpoint of an earlier run of the same strand (its "
        "checkpoint.h5 or tensioned.h5) with this case's loads; give a new --out",
    )
    mesh = sub.add_parser(
        "mesh", help="build the strand mesh and contact pairs; print and draw them"
    )
    mesh.add_argument(
        "case", nargs="?", help="case file (TOML) or cable file; default: Cardinal, 1 m"
    )
    mesh.add_argument("--out", default="results/mesh", help="output folder (default: %(default)s)")
    mesh.add_argument("--no-picture", action="store_true", help="skip the PNG")
    compare = sub.add_parser(
        "compare",
        help="run a case with small- and large-sliding contact and compare them",
        description="Run a case twice, with contact.model = small and large, on the same mesh, "
        "laws and solver; print and write the cost of each, the deflections, and the largest "
        "differences of the wire axial forces per layer and 45° sector, with an overlay figure.",
    )
    compare.add_argument(
        "case", nargs="?", help=f"case file (TOML), or {DEFAULT_CASE!r} for the built-in case"
    )
    compare.add_argument(
        "--out", help="results folder (default: <case output folder>/sliding_comparison)"
    )
    compare.add_argument(
        "--overwrite", action="store_true", help="replace the results of an earlier comparison"
    )
    spectrum = sub.add_parser(
        "spectrum",
        help="reduce a load history (CSV) by rainflow to a [fatigue] spectrum",
        description="Count the cycles of one column of a load history (a CSV in time, as a "
        "global analysis writes it) by rainflow (ASTM E1049), sort their amplitudes (range/2) "
        "into classes of equal width from 0, each run at its upper edge, and print the "
        "[fatigue] spectrum as a table [fatigue.spectrum] with classes = [[amplitude, cycles], "
        "...], to paste at the end of a case file (beside its [fatigue] table, if any).",
    )
    spectrum.add_argument("history", help="the history file: a header line of column names")
    spectrum.add_argument(
        "--column",
        required=True,
        help="the column to count, in the unit of the case's parameter (lateral N, curvature "
        "1/m, tension_swing N); a force in kN or MN (tension_kN, or a units line) is read in N",
    )
    spectrum.add_argument("--bins", type=int, default=3, help="classes (default: %(default)s)")
    spectrum.add_argument("--time-column", default="", help="the time column: the duration")
    spectrum.add_argument(
        "--tension-column",
        default="",
        help="a tension column (N; kN or MN read in N): its mean, for [load] tension, and a "
        "line if it varies more",
    )
    spectrum.add_argument(
        "--period",
        help="scale the counts from the record's duration (--time-column, in s unless its unit "
        "says otherwise) to this period: seconds, or 3h, 30d, 1y (365.25 d)",
    )
    spectrum.add_argument(
        "--scale",
        type=float,
        help="multiply the counts: the times the history recurs in the spectrum's period "
        "(instead of --period)",
    )
    spectrum.add_argument("--output", help="also write the lines to this file")
    for p in (run, mesh, compare):
        p.add_argument(
            "--set",
            action="append",
            default=[],
            metavar="SECTION.KEY=VALUE",
            help="change one setting of the case (TOML value), e.g. --set load.tension=20e3; "
            "repeatable",
        )
    args = parser.parse_args(argv)
    from ..cable.description import CableError
    from ..model.checkpoint import CheckpointError
    from .errors import CaseError
    from .fatigue.load_history import HistoryError
    from .folder import FolderError

    try:
        if args.command == "spectrum":
            return _spectrum(args)
        if args.command == "mesh":
            return _mesh(args)
        if args.command == "compare":
            return _compare(args, compare)
        return _run(args, run)
    except (CableError, CaseError, FolderError, CheckpointError, HistoryError) as e:
        from ..beam.parallel import is_root

        if is_root():  # one line, not one per rank
            print(f"strand: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # a second Ctrl-C, or one outside the load steps
        print("strand: interrupted; the steps written so far are kept", file=sys.stderr)
        return 130
