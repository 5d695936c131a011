"""Cost against the number of wires: steel spiral strands of 7 to 127 wires on 1 and 2 ranks.

Run: .venv/bin/python benchmarks/wire_count.py [--quick] [--wires 7 19 …] [--ranks 1 2]
[--length L] [--no-analysis] [--report] [--folder NAME] [section.key=value …]
(--quick: 7 and 19 wires over 0.06 m, a smoke test of the benchmark itself, in its own folder;
--report: the table of the runs already made, without running; the settings, as ``strand run
--set``, go to every run, e.g. 'contact.same_layer="off"'; --folder: the runs' sub-folder, so
that those of other settings stay apart)

The strands: all-steel spiral strands 1+6, 1+6+12, … , 1+6+12+18+24+30+36 (7, 19, 37, 61, 91,
127 wires), every wire 3 mm (a mooring spiral strand's wire size), E = 200 GPa, ν = 0.3, every
layer at 14° to the axis, hands alternating with the outer layer right-hand (Z), layer radii from
wires touching the layer below (``strand.cable.description``), Coulomb friction 0.2 (lubricated
steel) at every interface and between the wires of each layer. Equal wires leave layer k (6k wires
on the radius k d) a circumferential fill 3/(π cos α), whatever k: 0.984 at 14°, and at 17.3° they
would overlap. The helices of layer 1 come 69 µm closer than touching (as in every 1+6 of equal
wires, Cardinal's too; ``strand.model.layer_states`` takes them as touching); layers 2–6 leave 19–45
µm between neighbours. Minimum breaking strength MBS = Σ wire areas × 1770 MPa (the wires' tensile
strength).

The programme, one for all once scaled by each strand's MBS: the saddle test (the default kind),
tension to 20 % of the MBS, then the saddle load to 10 % of that tension and back to zero
(``[load] cycle = [1, 0]``), with Cardinal's default case's ratios for the steps (first tension
step T/40, lateral steps P × 250/4300 to P × 400/4300, residual tolerance 2.5e-7 T), so that every
strand is loaded, and stepped, alike: the load ratio P/T sets the string part of the midspan
deflection, P L / 4T, the same for all (a thicker strand adds more beam stiffness to it). Every
output on, as a run writes them by default.

One span for all, 0.2 m by default: 5 outer diameters of the 127-wire strand (39 mm), long
enough for the LU's cost to grow in proportion to the span (``length_scaling.py``), and short
enough for every strand to run on the 2-core machine: MUMPS's flops per LU grow as wires^2.5
(7 → 19 wires; nested dissection of a rod predicts 2.5), so the 127-wire runs take most of the
time (2,267 of the 3,896 s of the stamped table's twelve runs, docs/benchmarks.md).

Each (strand, ranks) runs in a process of its own (``mpirun -n 2`` from the venv for 2 ranks), so
that its memory is its own; its folder and log are in ``results/benchmark_wire_count``. A run
that fails (out of memory, a load step that does not converge) is a row saying so. Per run: the
unknowns, contact pairs, steps, Newton iterations (converged, and in failed attempts), LU
factorisations, wall time (build, run, summary, report, figures), Newton time per iteration
(failed ones included), time per LU, the LU's analysis time (MUMPS's symbolic phase), the outputs'
time, MUMPS's flops per factorisation (RINFOG(3), of the run's last one), the factor's entries
(INFOG(29)) and memory (INFOG(22), MB summed over the ranks), and the peak memory of the largest
rank (ru_maxrss). Then the exponents p of wall time, time per iteration, LU flops, factor entries
and peak memory ∝ wires^p (least squares in log–log), per rank count.

Last (unless ``--no-analysis``), on 2 ranks and the largest strand, the Jacobian after the first
tension step is factorised with MUMPS's analysis in sequence (ICNTL(28) = 1) and in parallel
(ICNTL(28) = 2) by PT-SCOTCH (ICNTL(29) = 1) or ParMETIS (ICNTL(29) = 2), with the runs' other
MUMPS settings: analysis and factorisation time, the analysis and ordering MUMPS reports it did
(INFOG(32), INFOG(7)), flops, factor entries and memory, and the solve's residual; a variant the
wheel lacks reports MUMPS's error.
"""

import strand  # noqa: F401

# isort: split

import argparse
import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from harness import parser, peak_mib, stamp, table

#: the runs' folders and logs (``quick/`` under it for ``--quick``)
ROOT = Path("results/benchmark_wire_count")
MPIRUN = Path(sys.executable).parent / "mpirun"

WIRE_DIAMETER = 3e-3  # m
STEEL = {"E": 200e9, "nu": 0.3}  # Pa, -
LAY_ANGLE = 14.0  # degrees from the strand axis, every layer
FRICTION = 0.2
TENSILE_STRENGTH = 1770e6  # Pa, for the MBS
TENSION_SHARE = 0.2  # of the MBS
LATERAL_SHARE = 0.1  # of the tension
SIZES = (7, 19, 37, 61, 91, 127)
LENGTH = 0.2  # m
QUICK_SIZES, QUICK_LENGTH = (7, 19), 0.06
#: the MUMPS settings of a distributed run (``strand.model.problem.StrandProblem``): PORD ordering,
#: twice the workspace estimate
RUN_ICNTL = {7: 4, 14: 100}
#: MUMPS's analysis variants of the probe: name: ICNTL values over ``RUN_ICNTL``
ANALYSES = {
    "sequential, ICNTL(28)=1": {28: 1},
    "PT-SCOTCH, ICNTL(28)=2, (29)=1": {28: 2, 29: 1},
    "ParMETIS, ICNTL(28)=2, (29)=2": {28: 2, 29: 2},
}
#: INFOG(7), the ordering MUMPS used, by the analysis it did (INFOG(32): 1 sequential, 2 parallel)
ORDERINGS = {
    1: {0: "AMD", 2: "AMF", 3: "SCOTCH", 4: "PORD", 5: "METIS", 6: "QAMD"},
    2: {1: "PT-SCOTCH", 2: "ParMETIS"},
}


def layers_of(wires: int) -> int:
    """The layers around the core of the 1+6+12+… strand of ``wires`` (3k(k+1) + 1) wires."""
    k = 0
    while 3 * k * (k + 1) + 1 < wires:
        k += 1
    if 3 * k * (k + 1) + 1 != wires or k == 0:
        raise SystemExit(f"{wires} wires: a 1+6+12+… strand has 7, 19, 37, 61, 91, 127, … wires")
    return k


def strand_cable(wires: int) -> dict:
    """The cable table (``strand.cable.description.cable_from_dict``) of the steel spiral strand."""
    n = layers_of(wires)
    wire = {"diameter": WIRE_DIAMETER, **STEEL}
    layers = [
        {
            "wires": 6 * k,
            **wire,
            "lay_angle": LAY_ANGLE,
            "lay": "Z" if (n - k) % 2 == 0 else "S",
            "friction": FRICTION,
        }
        for k in range(1, n + 1)
    ]
    name = "steel spiral strand 1+" + "+".join(str(6 * k) for k in range(1, n + 1))
    return {"name": name, "core": {**wire, "friction": FRICTION}, "layer": layers}


def breaking_strength(wires: int) -> float:
    """MBS (N): the wires' areas × their tensile strength."""
    return wires * math.pi * WIRE_DIAMETER**2 / 4 * TENSILE_STRENGTH


def case_for(wires: int, length: float, settings: list[str]):
    """The case of the strand of ``wires`` over ``length`` (m), its loads scaled by its MBS;
    ``settings`` (``section.key=value``) over them."""
    from strand.app.case import case_from_dict
    from strand.app.case_overrides import merge_settings, parse_settings

    mbs = breaking_strength(wires)
    tension = TENSION_SHARE * mbs
    lateral = LATERAL_SHARE * tension
    data = {
        "cable": strand_cable(wires),
        "mesh": {"length": length},
        "load": {"kind": "saddle", "tension": tension, "lateral": lateral, "cycle": [1.0, 0.0]},
        "steps": {
            "tension": tension / 40,
            "lateral": lateral * 250 / 4300,
            "lateral_max": lateral * 400 / 4300,
            "tolerance": 2.5e-7 * tension,
        },
        "fatigue": {"breaking_strength": mbs},
    }
    return case_from_dict(
        merge_settings(data, parse_settings(settings)), source=f"{wires}-wire strand"
    )


def factor_info(factor) -> dict:
    """MUMPS's flops of the last factorisation, the factor's entries and its memory (MB, all
    ranks); NaN when there is no factor."""
    try:
        entries = factor.getMumpsInfog(29)
        analysis, ordering = factor.getMumpsInfog(32), factor.getMumpsInfog(7)
        return {
            "flops": factor.getMumpsRinfog(3),
            "entries": -1e6 * entries if entries < 0 else float(entries),  # < 0: in millions
            "factor_mb": float(factor.getMumpsInfog(22)),
            "ordering": ORDERINGS.get(analysis, {}).get(ordering, f"INFOG(7) = {ordering}"),
        }
    except Exception:  # the PC was reset after a failed factorisation
        return {"flops": math.nan, "entries": math.nan, "factor_mb": math.nan, "ordering": "–"}


def worker(wires: int, length: float, folder: Path, settings: list[str]) -> None:
    """One run of the strand (under mpirun for several ranks); rank 0 writes
    ``measured.json`` into its folder."""
    from mpi4py import MPI
    from petsc4py import PETSc

    from strand.beam.parallel import abort_on_error

    abort_on_error()  # an error on one rank ends both (else the other waits for ever)

    from strand.app.build import build_problem, results_folder
    from strand.app.runner import run_programme_with_outputs
    from strand.beam.parallel import root_stream

    comm = MPI.COMM_WORLD
    PETSc.Log.begin()
    case = case_for(wires, length, settings)
    stream = root_stream(sys.stdout)
    t0 = time.perf_counter()
    path = results_folder(case, folder, overwrite=True)
    problem, programme = build_problem(case, stream)
    try:
        result = run_programme_with_outputs(case, problem, programme, path, stream, None, t0)
        seconds = time.perf_counter() - t0
        factor = factor_info(problem.solver.solver.getKSP().getPC().getFactorMatrix())
        g = problem.geometry
        size = {"unknowns": 6 * len(g.points), "pairs": len(g.pairs), "elements": len(g.cells)}
    finally:
        problem.solver.destroy()
    lu = PETSc.Log.Event("MatLUFactorNum").getPerfInfo()
    analysis = PETSc.Log.Event("MatLUFactorSym").getPerfInfo()
    peak = peak_mib(comm)
    if comm.rank == 0:
        c = case.contact
        measured = {
            "wires": wires,
            "ranks": comm.size,
            "length": length,
            **size,
            **factor,
            "tension": case.load.tension,
            "lateral": case.load.lateral,
            "seconds": seconds,
            "setup_seconds": result.setup_seconds,
            "steps": len(result.steps),
            "iterations": result.iterations,
            "failed_iterations": result.failed_iterations,
            "cuts": sum(s.cuts for s in result.steps),
            "solve_seconds": result.timings["solve"],
            "output_seconds": result.timings["output"],
            "lu": lu["count"],
            "lu_seconds": lu["time"],
            "analyses": analysis["count"],
            "analysis_seconds": analysis["time"],
            "peak_mib": peak,
            "failure": result.failure,
            "contact": f"normal {c.normal}, {c.compliance}, same_layer {c.same_layer}, "
            f"slip {c.slip}, {c.model} sliding",
        }
        (path / "measured.json").write_text(json.dumps(measured))


def factorise(A, icntl: dict[int, int]) -> dict:
    """Factorise ``A`` with MUMPS under the ``icntl`` values, solve once; the analysis's and the
    factorisation's times (s), MUMPS's report, the residual, or the error."""
    from petsc4py import PETSc

    from strand.solver.ordering import mumps_lu

    ksp, F = mumps_lu(A, {**RUN_ICNTL, **icntl})
    events = [PETSc.Log.Event(e) for e in ("MatLUFactorSym", "MatLUFactorNum")]
    before = [e.getPerfInfo()["time"] for e in events]
    out: dict = {}
    try:
        ksp.setUp()
        b = A.createVecLeft()
        b.set(1.0)
        x, r = A.createVecRight(), A.createVecLeft()
        ksp.solve(b, x)
        A.mult(x, r)
        r.axpy(-1.0, b)
        out["residual"] = r.norm() / b.norm()
        out["reason"] = ksp.getConvergedReason()
    except PETSc.Error as e:
        out["error"] = f"PETSc error {e.ierr}"
    out["analysis_s"], out["factor_s"] = (
        e.getPerfInfo()["time"] - t for e, t in zip(events, before, strict=True)
    )
    out.update(analysis=F.getMumpsInfog(32), **factor_info(F))
    failed, detail = F.getMumpsInfog(1), F.getMumpsInfog(2)
    if failed < 0:
        out.update(flops=math.nan, entries=math.nan, factor_mb=math.nan, ordering="–")
        out["error"] = (
            out.get("error", "") + f" MUMPS INFOG(1) = {failed}, INFOG(2) = {detail}"
        ).strip()
    ksp.destroy()
    return out


def analysis_probe(wires: int, length: float, out: Path, settings: list[str]) -> None:
    """The strand's Jacobian after its first tension step, factorised under each of
    ``ANALYSES``; rank 0 writes them to ``out`` (JSON)."""
    from mpi4py import MPI
    from petsc4py import PETSc

    from strand.app.build import build_problem

    PETSc.Log.begin()
    case = case_for(wires, length, settings)
    problem, _ = build_problem(case)
    problem.setup.set("tension", case.steps.tension)
    first = problem.solver.solve()
    rows = {name: factorise(problem.solver.A, icntl) for name, icntl in ANALYSES.items()}
    problem.solver.destroy()
    if MPI.COMM_WORLD.rank == 0:
        info = {
            "wires": wires,
            "ranks": MPI.COMM_WORLD.size,
            "length": length,
            "first_step": first.converged,
        }
        out.write_text(json.dumps({**info, "rows": rows}))


def launch(args: list[str], ranks: int, log: Path) -> int:
    """Run this script with ``args`` on ``ranks`` ranks, its output into ``log``."""
    command = [sys.executable, __file__, *args]
    if ranks > 1:
        command = [str(MPIRUN), "-n", str(ranks), *command]
    with open(log, "w") as f:
        return subprocess.run(command, stdout=f, stderr=subprocess.STDOUT).returncode


def run_name(wires: int, ranks: int) -> str:
    return f"{wires}_wires_{ranks}_rank{'s' if ranks > 1 else ''}"


def saved(root: Path, wires: int, ranks: int, length: float) -> dict:
    """The measurements of an earlier run over ``length`` (``--report``)."""
    path = root / run_name(wires, ranks) / "measured.json"
    if path.exists() and json.loads(path.read_text()).get("length") == length:
        return json.loads(path.read_text())
    failure = f"no run over {length:g} m in {path.parent}"
    return {"wires": wires, "ranks": ranks, "seconds": math.nan, "failure": failure}


def run(root: Path, wires: int, ranks: int, length: float, settings: list[str]) -> dict:
    """One run in a process of its own (its folder and log in ``root``): its measurements, or
    its failure."""
    name = run_name(wires, ranks)
    folder = root / name
    (folder / "measured.json").unlink(missing_ok=True)
    print(f"running {name} …", file=sys.stderr, flush=True)
    t0 = time.perf_counter()
    code = launch(
        ["--worker", str(wires), str(length), str(folder), *settings], ranks, root / f"{name}.log"
    )
    if code != 0 or not (folder / "measured.json").exists():
        tail = (root / f"{name}.log").read_text().strip().splitlines()[-1:] or [""]
        print(f"{name}: FAILED (exit code {code})", file=sys.stderr, flush=True)
        return {
            "wires": wires,
            "ranks": ranks,
            "seconds": time.perf_counter() - t0,
            "failure": f"exit code {code}: {tail[0][:120]}",
        }
    r = json.loads((folder / "measured.json").read_text())
    print(
        f"{name}: {r['seconds']:.0f} s, {r['iterations']} (+{r['failed_iterations']}) "
        f"iterations, {per_iteration(r):.3f} s per iteration, {r['peak_mib']:.0f} MiB",
        file=sys.stderr,
        flush=True,
    )
    return r


def _g(value: float, digits: int = 3) -> str:
    return "–" if value is None or not math.isfinite(value) else f"{value:.{digits}g}"


def per_iteration(r: dict) -> float:
    """Newton's time per iteration (s), those of failed attempts included."""
    return r["solve_seconds"] / max(r["iterations"] + r["failed_iterations"], 1)


def run_table(rows: list[dict]) -> str:
    """The runs as a markdown table."""
    head = [
        "wires",
        "ranks",
        "unknowns",
        "pairs",
        "T (kN)",
        "P (kN)",
        "steps",
        "its (+failed)",
        "LUs",
        "wall (s)",
        "s/it",
        "s/LU",
        "analysis (s)",
        "outputs (s)",
        "LU flops",
        "factor entries",
        "factor MB",
        "peak MiB",
    ]
    lines = []
    for r in rows:
        if "steps" not in r:
            cells = [str(r["wires"]), str(r["ranks"]), *["–"] * 7, _g(r["seconds"])]
            lines.append(cells + ["–"] * (len(head) - len(cells)))
            continue
        cells = [
            str(r["wires"]),
            str(r["ranks"]),
            str(r["unknowns"]),
            str(r["pairs"]),
            f"{r['tension'] / 1e3:.1f}",
            f"{r['lateral'] / 1e3:.2f}",
            str(r["steps"]),
            f"{r['iterations']} (+{r['failed_iterations']})",
            str(r["lu"]),
            f"{r['seconds']:.1f}",
            f"{per_iteration(r):.3f}",
            f"{r['lu_seconds'] / max(r['lu'], 1):.3f}",
            f"{r['analysis_seconds']:.2f}",
            f"{r['output_seconds']:.1f}",
            _g(r["flops"]),
            _g(r["entries"]),
            _g(r["factor_mb"], 4),
            f"{r['peak_mib']:.0f}",
        ]
        lines.append(cells)
    return table(lines, head)


#: the fitted quantities: name: value of a run
FITS = {
    "wall time": lambda r: r["seconds"],
    "time per iteration": per_iteration,
    "LU flops": lambda r: r["flops"],
    "factor entries": lambda r: r["entries"],
    "peak memory": lambda r: r["peak_mib"],
}


def exponent(wires, values) -> float:
    """p of values ∝ wires^p, least squares in log–log (NaN with fewer than two points)."""
    w, v = np.asarray(wires, float), np.asarray(values, float)
    ok = np.isfinite(v) & (v > 0)
    if len(set(w[ok])) < 2:
        return math.nan
    return float(np.polyfit(np.log(w[ok]), np.log(v[ok]), 1)[0])


def exponents(rows: list[dict], ranks: int) -> str:
    done = [r for r in rows if r["ranks"] == ranks and "steps" in r and not r["failure"]]
    fits = [
        f"{name} {_g(exponent([r['wires'] for r in done], [f(r) for r in done]), 3)}"
        for name, f in FITS.items()
    ]
    return f"{ranks} rank{'s' if ranks > 1 else ''}: " + ", ".join(fits)


def probe_lines(probe: dict) -> list[str]:
    head = [
        "MUMPS analysis",
        "analysis (s)",
        "factorisation (s)",
        "INFOG(32)",
        "ordering",
        "LU flops",
        "factor entries",
        "factor MB",
        "residual",
        "error",
    ]
    lines = [
        f"\nMUMPS's analysis on {probe['ranks']} ranks, {probe['wires']} wires, the Jacobian "
        f"after the first tension step (converged: {probe['first_step']}):",
        "",
    ]
    rows = []
    for name, r in probe["rows"].items():
        cells = [
            name,
            f"{r['analysis_s']:.3f}",
            f"{r['factor_s']:.3f}",
            str(r["analysis"]),
            r["ordering"],
            _g(r["flops"]),
            _g(r["entries"]),
            _g(r["factor_mb"], 4),
            _g(r.get("residual", math.nan), 2),
            r.get("error", ""),
        ]
        rows.append(cells)
    return [*lines, table(rows, head)]


def main(args: argparse.Namespace, settings: list[str]) -> None:
    root = ROOT / "quick" if args.quick else ROOT
    if args.folder:
        root = root / args.folder
    root.mkdir(parents=True, exist_ok=True)
    sizes = args.wires or (QUICK_SIZES if args.quick else SIZES)
    length = args.length or (QUICK_LENGTH if args.quick else LENGTH)
    for w in sizes:
        layers_of(w)
    started = time.perf_counter()
    if args.report:
        rows = [saved(root, w, ranks, length) for w in sizes for ranks in args.ranks]
        out = root / "analysis.json"
        probe = json.loads(out.read_text()) if out.exists() else None
        probe = probe if probe and probe["length"] == length else None
    else:
        rows = [run(root, w, ranks, length, settings) for w in sizes for ranks in args.ranks]
        probe = None
    if not args.no_analysis and not args.report:
        out = root / "analysis.json"
        out.unlink(missing_ok=True)
        print(f"probing MUMPS's analysis on {max(sizes)} wires, 2 ranks …", file=sys.stderr)
        launch(
            ["--probe", str(max(sizes)), str(length), str(out), *settings], 2, root / "analysis.log"
        )
        probe = json.loads(out.read_text()) if out.exists() else None
    print(f"\nWire count: {stamp()}")
    contact = next((r["contact"] for r in rows if "contact" in r), "–")
    orderings = sorted({r["ordering"] for r in rows if "ordering" in r})
    print(
        f"steel spiral strands of {WIRE_DIAMETER * 1e3:g} mm wires, {LAY_ANGLE:g}° lay, "
        f"friction {FRICTION:g}, {_g(length)} m; saddle test: T = {TENSION_SHARE:g} MBS, P = "
        f"{LATERAL_SHARE:g} T up and back; contact: {contact}; MUMPS ordering: "
        f"{', '.join(orderings) or '–'}"
        + (f"; settings: {' '.join(settings)}" if settings else "")
        + "\n"
    )
    print(run_table(rows))
    for r in rows:
        if r["failure"]:
            print(f"{r['wires']} wires, {r['ranks']} ranks: FAILED: {r['failure']}")
    print("\nexponents p of ∝ wires^p (least squares in log–log):")
    for ranks in args.ranks:
        print(exponents(rows, ranks))
    if probe is not None:
        print("\n".join(probe_lines(probe)))
    elif not args.no_analysis and not args.report:
        print(f"\nMUMPS's analysis probe failed: see {root / 'analysis.log'}")
    print(f"\nwhole benchmark: {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--worker"]:
        worker(int(sys.argv[2]), float(sys.argv[3]), Path(sys.argv[4]), sys.argv[5:])
    elif sys.argv[1:2] == ["--probe"]:
        analysis_probe(int(sys.argv[2]), float(sys.argv[3]), Path(sys.argv[4]), sys.argv[5:])
    else:
        from strand.beam.parallel import serial_only

        serial_only("this benchmark (it launches its 2-rank runs itself)")
        cli = parser(__doc__, "7 and 19 wires over 0.06 m, in a folder of its own")
        cli.add_argument("--wires", type=int, nargs="+", help="strand sizes (7, 19, 37, …)")
        cli.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
        cli.add_argument("--length", type=float, help=f"span, m (default {LENGTH:g})")
        cli.add_argument(
            "--no-analysis", action="store_true", help="skip the probe of MUMPS's parallel analysis"
        )
        cli.add_argument(
            "--report",
            action="store_true",
            help="print the table of the runs already in the results folder",
        )
        cli.add_argument(
            "--folder",
            default="",
            help="a folder of its own (under the results folder) for the runs "
            'of these settings, e.g. steps.iteration="reuse_lu"',
        )
        args, settings = cli.parse_known_args()
        unknown = [s for s in settings if "=" not in s]
        if unknown:
            cli.error(f"unrecognised arguments {unknown}")
        main(args, settings)
