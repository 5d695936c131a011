"""Building a run from a case: its results folder (checked first, written with the whole case
once the strand is built), the strand in its set-up kind's test set-up with the Newton solver,
its load programme, and the state a restart continues from. Units: SI."""

from __future__ import annotations

import functools
from pathlib import Path

from forms import ReissnerBeam, has_elastic_stresses

from ..beam.parallel import on_root
from ..cable.geometry import build_geometry
from ..model.checkpoint import CheckpointError, restore
from ..model.model import BeamFactory
from ..model.problem import StrandProblem
from ..model.programme import LoadProgramme
from ..setups import TestSetup
from ..solver import ErrorControl, NewtonOptions, keep_freed_memory
from ..solver.convergence import STALL_AFTER
from .case import check_loads_given
from .case_toml import case_toml
from .errors import CaseError
from .folder import RUN_MARKER, check_results_folder, prepare_results_folder
from .kinds import SetupKind, kind_of
from .run_result import Start
from .settings import Case
from .step_records import RunStep

__all__ = [
    "settings_text",
    "check_folder",
    "results_folder",
    "newton_options",
    "setup_and_programme",
    "build_problem",
    "check_beam_law",
    "restart_from",
    "LARGE_MESH",
    "BYTES_PER_UNKNOWN",
    "size_announcement",
]

#: elements from which a run announces its mesh's size before building it
LARGE_MESH = 1_000_000
#: a run's peak memory per unknown (bytes), for that announcement: the default Cardinal case
#: (129,492 unknowns) peaks at 871 MiB in a serial run (benchmarks/speed.py, docs/benchmarks.md)
BYTES_PER_UNKNOWN = 7e3


def settings_text(case: Case) -> str:
    """The settings of ``case``, a ``key = value`` line each under its section's name (a
    sweep's ``sweep.txt`` until its table replaces it; a run writes ``case.toml``)."""
    lines = [f"case: {case.source}", f"cable: {case.cable.name}"]
    for name in ("mesh", "contact", "load", "steps", "output"):
        lines.append(f"[{name}]")
        section = getattr(case, name)
        items = section.items() if name in ("load", "steps") else vars(section).items()
        for k, v in items:
            lines.append(f"{k} = {v!r}")
    return "\n".join(lines) + "\n"


def check_folder(case: Case, folder, overwrite: bool) -> Path:
    """Refuse, before anything is built or written, a case that leaves Cardinal's loads on a
    cable of its own (``check_loads_given``) and a results folder the run may not use
    (``folder.check_results_folder``, on rank 0; every rank gets the verdict)."""
    check_loads_given(case)
    return on_root(lambda: check_results_folder(folder, overwrite))


def results_folder(case: Case, folder, overwrite: bool, restart=None) -> Path:
    """The run's folder, prepared on rank 0 (``folder.prepare_results_folder``) with the whole
    case written first (``case.toml``, ``strand.app.case_toml``); every rank gets the verdict.
    A run calls it once its strand is built, so that a case that cannot be built writes
    nothing (``check_folder`` refuses the folder, and a case without its loads, before)."""

    def prepare() -> Path:
        path = prepare_results_folder(folder, overwrite)
        text = case_toml(case, str(folder), None if restart is None else str(restart))
        (path / RUN_MARKER).write_text(text)
        return path

    return on_root(prepare)


def newton_options(case: Case) -> NewtonOptions:
    """Newton's settings from ``[steps]``: the residual tolerance, and the balance test against
    the mean wire tension (forces) and that force on the largest wire diameter (moments)."""
    s = case.steps
    force = s.balance * case.load.tension / case.cable.n_wires
    diameter = case.cable.largest_wire_diameter
    return NewtonOptions(
        atol=s.tolerance,
        max_it=s.max_iterations,
        force_tol=force,
        moment_tol=force * diameter,
        stall_after=STALL_AFTER if s.stall else 0,
        linesearch=s.line_search,
        iteration=s.iteration,
    )


def step_control(case: Case) -> dict:
    """``run_programme``'s step control from ``[steps]``: the error controller (``control =
    "error"``, aiming at ``error_tolerance``) or None, ``retry``, the contact springs of
    ``stabilise`` (N/m; None: off) and the same-layer onset while they hold, ``held_onset`` (m;
    None: as it is), and the relaxation after them, ``relax`` (N/m; None: none)."""
    s = case.steps
    controller = ErrorControl(tol=s.error_tolerance) if s.control == "error" else None
    return {
        "controller": controller,
        "retry": s.retry,
        "stabilisation": s.stabilise if s.stabilise > 0 else None,
        "held_onset": s.held_onset if s.held_onset > 0 else None,
        "relaxation": s.relax if s.relax > 0 else None,  # with stabilise > 0 (checks.py)
    }


def setup_and_programme(case: Case, kind: SetupKind):
    """The test set-up factory (taking the model) and the load programme of ``case``, a case
    of ``kind`` (``kinds.kind_of(case)``, resolved once where the run starts)."""
    return kind.setup(case), kind.programme(case)


def size_announcement(n_elements: int, n_unknowns: int) -> str:
    """The line a mesh of more than ``LARGE_MESH`` elements is announced with: its elements and
    unknowns, and the memory a run of it takes, roughly (``BYTES_PER_UNKNOWN``)."""
    gigabytes = n_unknowns * BYTES_PER_UNKNOWN / 1e9
    return (
        f"strand: a large mesh: {n_elements:,} elements, {n_unknowns:,} unknowns; a run of it "
        f"needs roughly {gigabytes:.2g} GB of memory (about {BYTES_PER_UNKNOWN / 1e3:g} kB per "
        "unknown); a shorter [mesh] length or a larger h_max makes it smaller"
    )


def _law_class(beam: BeamFactory) -> type | None:
    """The class a beam factory builds, where it shows without calling it: the factory
    itself, or the class a ``functools.partial`` wraps; None for another callable."""
    while isinstance(beam, functools.partial):
        beam = beam.func
    return beam if isinstance(beam, type) else None


def check_beam_law(case: Case, beam) -> None:
    """Refuse, in one line (``CaseError``), a beam law whose wire stresses the case's fatigue
    outputs cannot recover: they apply Navier's elastic formula to the law's N and M, so the
    law must declare it (``forms.has_elastic_stresses``). ``beam``: the law's class, or the
    beam built."""
    if case.fatigue.outputs and not has_elastic_stresses(beam):
        name = (beam if isinstance(beam, type) else type(beam)).__name__
        raise CaseError(
            f"{case.source}: the beam law {name} does not declare elastic_stresses, and the "
            "fatigue outputs compute the wires' stresses from its N and M with Navier's "
            "elastic formula: set [fatigue] outputs = false (or elastic_stresses = True in "
            f"{name} if its stresses are those of a linear elastic round wire)"
        )


def build_problem(
    case: Case,
    stream=None,
    *,
    kind: SetupKind | None = None,
    beam: BeamFactory = ReissnerBeam,
) -> tuple[StrandProblem[TestSetup], LoadProgramme]:
    """The strand of ``case`` in its test set-up, with the Newton solver, and its programme;
    one line about it on ``stream``, and before the finite-element mesh is built, a line on its
    size when it has more than ``LARGE_MESH`` elements. ``kind``: the case's set-up kind, as
    the run resolved it (None: resolved here, for a caller that starts from the case).
    ``beam``: the wires' beam law, ``beam(w, section)`` (``StrandModel``), refused before
    anything is built where its class shows, else once built, by ``check_beam_law``."""
    kind = kind_of(case) if kind is None else kind
    if _law_class(beam) is not None:
        check_beam_law(case, _law_class(beam))
    keep_freed_memory()  # each LU factorisation reuses the last one's workspace
    geometry = build_geometry(
        case.cable,
        case.mesh.length,
        case.mesh.h_max,
        facing=case.contact.facing_stations,
    )
    if len(geometry.cells) > LARGE_MESH:
        print(
            size_announcement(len(geometry.cells), 6 * len(geometry.points)),
            file=stream,
            flush=True,
        )
    options = newton_options(case)
    setup, programme = setup_and_programme(case, kind)
    problem = StrandProblem(geometry, case.contact, options, setup=setup, beam=beam)
    try:
        check_beam_law(case, problem.model.beam)
    except CaseError:
        problem.solver.destroy()
        raise
    size = problem.model.comm.size
    print(
        f"{case.cable.name}: L = {case.mesh.length:g} m, {len(geometry.wire_layer)} wires, "
        f"{len(geometry.cells)} elements, {6 * len(geometry.points)} unknowns, "
        f"{len(geometry.pairs)} contact pairs, normal = {case.contact.normal}, friction "
        f"{'on' if case.contact.friction else 'off'}" + (f"; {size} MPI ranks" if size > 1 else ""),
        file=stream,
        flush=True,
    )
    name, flops = problem.ordering
    if flops:
        others = ", ".join(f"{k.upper()} {v:.2g}" for k, v in flops.items() if k != name)
        print(
            f"MUMPS ordering {name.upper()}: {flops[name]:.2g} operations per LU ({others})",
            file=stream,
            flush=True,
        )
    if not case.contact.friction and case.contact.normal == "frozen":
        print(
            "frictionless: contact normals frozen at t = 0 (geometry-following normals do not "
            "converge without friction); gaps are approximate in bending (docs/benchmarks.md, "
            "Contact normals), so pair forces are indicative only",
            file=stream,
            flush=True,
        )
    return problem, programme


def restart_from(
    problem: StrandProblem[TestSetup], programme: LoadProgramme, checkpoint, path
) -> Start:
    """Put ``checkpoint`` into ``problem`` and say where the programme continues from; a
    checkpoint of another strand or programme is refused in one line (``CheckpointError``)."""
    g = problem.geometry
    if checkpoint.w.shape != (len(g.points), 6) or any(
        len(v) != len(g.pairs) for v in checkpoint.pairs.values()
    ):
        raise CheckpointError(
            f"{path}: written for another strand ({len(checkpoint.w)} points, "
            f"{len(next(iter(checkpoint.pairs.values()), []))} contact pairs; this case has "
            f"{len(g.points)} and {len(g.pairs)}): give the case it was written with"
        )
    if not 0 <= checkpoint.stage < len(programme.stages):
        raise CheckpointError(
            f"{path}: its stage {checkpoint.stage} is not in this case's load programme "
            f"({len(programme.stages)} stages)"
        )
    position = restore(problem, checkpoint)
    stage = programme.stages[checkpoint.stage]
    state = problem.setup.state()
    step = RunStep(
        checkpoint.number,
        stage.name,
        stage.parameter,
        problem.setup.get(stage.parameter),
        checkpoint.time,
        0,
        0,
        0.0,
        0.0,
        state,
    )
    return Start(position, step)
