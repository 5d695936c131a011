"""A beam law of one's own in a strand: the ``beam`` factory of ``StrandProblem`` and
``run_case`` reaches every wire.

The check is the full-slip bending stiffness of a frictionless strand, EI_min = Σ n EI of its
wires (``bending_stiffness_bounds``): each wire bends about its own axis, so a law that multiplies
every wire's EI by s multiplies the strand's M/κ by s. The strand: 0.2 m of a 1+6 (Cardinal's
steel, every friction off, objective ``director`` normals), T = 1 kN, bent to κ = 0.05 1/m
(uniform bending test, zone a third of the length). Measured: M/κ = 0.984 EI_min with the plain
law, 2.98 times that with EI × 3 (GJ kept, whose small share of a helix's bending is not
scaled); a factory that missed a wire, or was not called, would leave the slope near 1 × or
between the two.

Run as a script (``python tests/test_beam_law.py <folder>``, or under ``mpirun``), this module
runs the case through ``run_case`` with EI × 3 and prints the slope.
"""

from __future__ import annotations

import strand  # noqa: F401  (first: run as a script, the dolfinx wheel's MPI library loads)

# isort: split

import io
import subprocess
import sys
from functools import partial
from pathlib import Path

import pytest
from dolfinx import fem

from forms import CircularSection, ReissnerBeam, has_elastic_stresses
from strand.analytical.fibre import bending_stiffness_bounds
from strand.app.build import build_problem, check_beam_law
from strand.app.case import case_from_dict
from strand.app.errors import CaseError
from strand.app.run import run_case
from strand.cable.geometry import build_geometry
from strand.model.cell_results import cell_results
from strand.model.checkpoint import CheckpointError, restore
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups.bending import UniformBendingTest
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import MPIRUN, needs_mpirun

LENGTH, TENSION, CURVATURE = 0.2, 1e3, 0.05  # m, N, 1/m
WIRE = {"diameter": 3.34e-3, "E": 180e9, "nu": 0.3}
CASE = {
    "cable": {
        "name": "1+6 frictionless",
        "core": {**WIRE, "E": 210e9, "friction": 0.0},
        "layer": [{**WIRE, "wires": 6, "lay_angle": 6.06, "lay": "S", "friction": 0.0}],
    },
    "contact": {"friction": False, "normal": "director", "same_layer": "off"},
    "mesh": {"length": LENGTH},
    "load": {"kind": "bending", "tension": TENSION, "curvature": CURVATURE, "cycle": [1.0]},
    "steps": {"tension": TENSION, "curvature": CURVATURE / 4, "curvature_max": CURVATURE},
    "output": {"plots": False, "fields": False},
}
CASE["load"]["zone"] = LENGTH / 3


class BendingScaled(CircularSection):
    """The layers' section (``layer_section``) with every wire's EI × ``scale``; EA, κGA and GJ
    kept."""

    def __init__(self, section: CircularSection, scale):
        super().__init__(
            section.d, section.E, section.nu, section.shear_coefficient, section.torsional_stiffness
        )
        self.scale = scale

    @property
    def EI(self):
        return self.scale * super().EI


def scaled_bending(w: fem.Function, section: CircularSection, *, scale: float) -> ReissnerBeam:
    """A beam factory: ``ReissnerBeam`` on ``BendingScaled``. The scale is a ``Constant``, not a
    literal, so that every scale shares one compiled kernel."""
    mesh = w.function_space.mesh
    return ReissnerBeam(w, BendingScaled(section, fem.Constant(mesh, float(scale))))


def ei_min() -> float:
    """Σ n EI of the case's wires (N m²)."""
    return bending_stiffness_bounds(case_from_dict(CASE).cable)[0]


def script_slope(scale: float) -> float:
    """M/κ (N m²) of the strand built as a script does, with ``StrandProblem(beam=...)``."""
    case = case_from_dict(CASE)
    geometry = build_geometry(case.cable, LENGTH, case.mesh.h_max)
    problem = StrandProblem(
        geometry,
        ContactSettings(same_layer="off", normal="director", friction=False),
        NewtonOptions(atol=1e-3, max_it=15),
        setup=partial(UniformBendingTest, zone=LENGTH / 3),
        beam=partial(scaled_bending, scale=scale),
    )
    try:
        setup = problem.setup
        LoadStepper(problem.solver, TENSION, TENSION / 8).ramp(
            partial(setup.set, "tension"), 0.0, TENSION
        )
        LoadStepper(problem.solver, CURVATURE, CURVATURE / 4).ramp(
            partial(setup.set, "curvature"), 0.0, CURVATURE
        )
        cells = cell_results(problem.model, setup.direction)
        zone = setup.moment_curvature(cells, problem.solver.unconstrained_residual())
        return zone.moment_zone_middle / zone.curvature
    finally:
        problem.solver.destroy()


def run_case_slope(folder: Path, scale: float) -> float:
    """M/κ (N m²) at the end of the case run by ``run_case(beam=...)`` into ``folder``."""
    result = run_case(
        case_from_dict(CASE),
        folder,
        stream=io.StringIO(),
        beam=partial(scaled_bending, scale=scale),
    )
    assert not result.failure, result.failure
    zone = result.bending[-1].measures
    return zone.moment_zone_middle / zone.curvature


def test_a_beam_factory_scales_a_frictionless_strands_bending_stiffness():
    """From a script (``StrandProblem(beam=...)``): M/κ is EI_min with EI × 1 and 3 EI_min with
    EI × 3, within 3 % (measured 0.984 and 0.977), and their ratio is 3 within 1.5 % (2.980)."""
    plain, stiff = script_slope(1.0), script_slope(3.0)
    assert plain == pytest.approx(ei_min(), rel=0.03)
    assert stiff == pytest.approx(3 * ei_min(), rel=0.03)
    assert stiff / plain == pytest.approx(3.0, rel=0.015)


@needs_mpirun
def test_run_case_takes_the_beam_factory_on_1_and_2_ranks(tmp_path):
    """Through ``run_case`` (a script running a case file with a law of its own), serially and
    on 2 ranks: M/κ with EI × 3 is 3 EI_min within 3 %, the same number on both."""
    slopes = []
    for ranks in (1, 2):
        command = [sys.executable, __file__, str(tmp_path / f"n{ranks}")]
        if ranks > 1:
            command = [str(MPIRUN), "-n", str(ranks), *command]
        done = subprocess.run(command, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
        lines = done.stdout.split()
        assert len(lines) == 1, done.stdout  # printed once
        slopes.append(float(lines[0]))
    assert slopes[0] == pytest.approx(3 * ei_min(), rel=0.03)
    assert slopes[1] == pytest.approx(slopes[0], rel=1e-8)


#: the ``HalfMoments`` beams built (``id`` of their unknown)
BUILT: list[int] = []


class HalfMoments(ReissnerBeam):
    """A law of its own (its moments halved), which says nothing of its stresses."""

    def __init__(self, w, section):
        BUILT.append(id(w))
        super().__init__(w, section)

    @property
    def M(self):
        return 0.5 * super().M


class DeclaredHalfMoments(HalfMoments):
    """The same law, declaring Navier's stresses (as a linear elastic law may)."""

    elastic_stresses = True


class Renamed(ReissnerBeam):
    """ReissnerBeam's law under another name: it inherits the declaration."""


def test_a_law_declares_navier_stresses_or_has_none():
    """``ReissnerBeam`` declares Navier's stresses, and so does a subclass that keeps its law;
    one that overrides the law (``M``) does not inherit it, unless it sets it again, on its
    class or its instance; an object without the attribute does not declare it."""
    assert has_elastic_stresses(ReissnerBeam) and has_elastic_stresses(Renamed)
    assert not has_elastic_stresses(HalfMoments)
    assert has_elastic_stresses(DeclaredHalfMoments)
    own = HalfMoments.__new__(HalfMoments)
    own.elastic_stresses = True
    assert has_elastic_stresses(own)
    assert not has_elastic_stresses(object())


def half_moments(w: fem.Function, section: CircularSection) -> ReissnerBeam:
    """A factory whose law shows only once built (a function, not a class)."""
    return HalfMoments(w, section)


@pytest.mark.parametrize(
    "beam", [HalfMoments, partial(HalfMoments), half_moments], ids=["class", "partial", "function"]
)
def test_fatigue_outputs_refuse_a_law_without_navier_stresses(beam, tmp_path):
    """A case with the fatigue outputs (the default) run with ``HalfMoments`` stops in one line
    naming the law and the setting that lets it run, before any step and before its folder is
    written: before the strand is built where the factory shows its class, else once built."""
    folder = tmp_path / "run"
    BUILT.clear()
    with pytest.raises(CaseError) as refused:
        run_case(case_from_dict(CASE), folder, stream=io.StringIO(), beam=beam)
    message = str(refused.value)
    assert "\n" not in message
    assert "HalfMoments" in message and "[fatigue] outputs = false" in message
    assert not folder.exists()
    assert len(BUILT) == (1 if beam is half_moments else 0)
    case = case_from_dict({**CASE, "fatigue": {"outputs": False}})
    check_beam_law(case, HalfMoments)  # without the fatigue outputs, the law runs
    check_beam_law(case_from_dict(CASE), DeclaredHalfMoments)


class Counted:
    """A ``HistoryState`` that counts its commits."""

    def __init__(self):
        self.commits = 0

    def commit(self) -> None:
        self.commits += 1

    def rollback(self) -> None:
        pass


def with_history(w: fem.Function, section: CircularSection) -> ReissnerBeam:
    """``ReissnerBeam`` with a state of its own (``history``)."""
    beam = ReissnerBeam(w, section)
    beam.history = [Counted()]
    return beam


def test_a_laws_history_reaches_the_strand_solver_and_refuses_a_restore():
    """A law's ``history`` is the strand's Newton problem's: committed with each converged
    step. A checkpoint (or a sweep's kept state) does not hold it, so restoring one is refused
    in one line."""
    case = case_from_dict({**CASE, "fatigue": {"outputs": False}})
    problem, _ = build_problem(case, io.StringIO(), beam=with_history)
    try:
        state = problem.model.beam.history[0]
        assert problem.solver.history == [state]
        problem.solver.commit()
        assert state.commits == 1
        with pytest.raises(CheckpointError, match="has a state of its own"):
            restore(problem, None)
    finally:
        problem.solver.destroy()


if __name__ == "__main__":
    from mpi4py import MPI

    slope = run_case_slope(Path(sys.argv[1]), 3.0)
    if MPI.COMM_WORLD.rank == 0:
        print(repr(slope))
