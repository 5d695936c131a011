"""Displacement-controlled saddle cycles (``[load] control = "displacement"``):
the midspan deflection or the conductor practice's Y_b is prescribed, every step finds the saddle
load that gives it (``strand.solver.displacement_control``). The prescribed displacement is
reached to the stated tolerance, the force-controlled test at the loads found gives the same
displacements back, the half-turn symmetry of the 1+6 holds exactly, sweeps run over displacement
amplitudes, and bad settings are refused in one line."""

from __future__ import annotations

import csv
import io
import subprocess
import sys
import tomllib
from types import SimpleNamespace

import numpy as np
import pytest

from strand.analytical import TensionedBeam
from strand.analytical.fibre import bending_stiffness_bounds
from strand.app.case import CaseError, case_from_dict, load_case
from strand.app.cli import main
from strand.app.kinds.saddle import CONTROL_TOLERANCE
from strand.app.run import build_problem, run_programme_with_outputs
from strand.setups.saddle import beam_compliance
from strand.solver import LoadStepper, NewtonResult
from strand.solver.displacement_control import DisplacementControl
from strand_cases import MPIRUN, SEVEN_WIRE, needs_mpirun

QUIET = ["output.plots=false", "output.fields=false", "fatigue.outputs=false"]
DELTA, FIRST = 0.09e-3, 0.025e-3  # m: the midspan amplitude (about 300 N) and first increment
TOL = CONTROL_TOLERANCE * FIRST  # m, the control's tolerance on the deflection
DISPLACEMENT = [
    'load.control="displacement"',
    f"load.deflection={DELTA}",
    f"steps.deflection={FIRST}",
    f"steps.deflection_max={2 * FIRST}",
]
#: the 1+6 (0.1 m, 10 kN) without a saddle load amplitude
CASE = SEVEN_WIRE.replace("lateral = 300.0\n", "")


def rows(folder) -> list[dict[str, str]]:
    with open(folder / "steps.csv") as f:
        return list(csv.DictReader(f))


def cycle(folder) -> list[dict[str, str]]:
    return [r for r in rows(folder) if r["stage"].startswith("leg")]


@pytest.fixture(scope="module")
def case_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("saddle_displacement") / "seven.toml"
    path.write_text(CASE)
    return path


def run(case_file, name: str, *settings: str):
    """A run of the 1+6 with ``settings``; its folder."""
    out = case_file.parent / name
    sets = [x for s in [*QUIET, *settings] for x in ("--set", s)]
    assert main(["run", str(case_file), "--out", str(out), *sets]) == 0
    return out


@pytest.fixture(scope="module")
def up(case_file):
    """The 1+6 pressed to a midspan deflection of +DELTA from the tensioned state."""
    return run(case_file, "up", *DISPLACEMENT, "load.cycle=[1.0]")


def test_the_midspan_deflection_is_the_prescribed_one(up, case_file, capsys):
    """Every step's midspan deflection (steps.csv) is within the stated tolerance (1e-3 of the
    first increment: 25 nm) of the prescribed one, the peak's of DELTA; the saddle load found is
    recorded (lateral_N, growing with the deflection)."""
    steps = cycle(up)
    assert len(steps) >= 3
    for r in steps:
        assert abs(float(r["deflection_m"]) - float(r["prescribed_m"])) <= TOL
        assert r["measured_m"] == r["deflection_m"]  # measured where the deflection is read
        assert int(r["solves"]) >= 1
    assert float(steps[-1]["prescribed_m"]) == DELTA
    assert abs(float(steps[-1]["deflection_m"]) - DELTA) <= TOL
    loads = [float(r["lateral_N"]) for r in steps]
    assert loads[0] > 0 and np.all(np.diff(loads) > 0)
    summary = (up / "summary.txt").read_text()
    assert "displacement control of deflection at midspan" in summary
    assert f"saddle load +{loads[-1] / 1e3:.3f} kN" in summary


def test_the_force_controlled_test_at_the_loads_found_gives_the_displacements_back(up, case_file):
    """Both ways agree. Through the same loads (one step each), the force-controlled test gives
    each step's deflection back within the control's tolerance (measured: 1 nm, Newton's
    tolerance); in its own load steps to the peak load, within its load-step error (measured:
    0.03 %, asserted 0.5 %)."""
    steps = cycle(up)
    loads = [float(r["lateral_N"]) for r in steps]
    peak = loads[-1]
    fractions = "[" + ", ".join(repr(p / peak) for p in loads) + "]"
    same = run(
        case_file,
        "same_loads",
        f"load.lateral={peak!r}",
        f"load.cycle={fractions}",
        f"steps.lateral={2 * peak}",
        f"steps.lateral_max={2 * peak}",
    )
    forced = cycle(same)
    assert [float(r["lateral_N"]) for r in forced] == pytest.approx(loads, rel=1e-14)
    for a, b in zip(steps, forced, strict=True):
        assert abs(float(a["deflection_m"]) - float(b["deflection_m"])) <= TOL
    own = run(case_file, "own_steps", f"load.lateral={peak!r}", "load.cycle=[1.0]")
    assert float(cycle(own)[-1]["deflection_m"]) == pytest.approx(DELTA, rel=5e-3)


@pytest.mark.slow  # 11–12 s on a fresh clone
def test_plus_and_minus_deflections_need_opposite_loads(up, case_file):
    """The 1+6 and its set-up are their own image by a half turn about the strand axis (six
    wires: a helix handedness is kept by a rotation), which maps a deflection +δ on −δ: from the
    tensioned state, the virgin loads at ±DELTA are opposite to 1e-9 (measured: 3e-14). Through
    the whole cycle, the peak loads at +DELTA and −DELTA lie between the clamped–clamped
    tensioned beams of EI_min and EI_max (all wires slipping, all sticking)."""
    p_up = float(cycle(up)[-1]["lateral_N"])
    down = run(case_file, "down", *DISPLACEMENT, "load.cycle=[-1.0]")
    p_down = float(cycle(down)[-1]["lateral_N"])
    assert abs(p_up + p_down) <= 1e-9 * p_up
    full = cycle(run(case_file, "full", *DISPLACEMENT, "load.cycle=[1.0, 0.0, -1.0, 0.0]"))
    cable = load_case(case_file).cable
    stiffness = [
        1.0 / TensionedBeam(0.1, 10e3, lambda m, ei=ei: m / ei).deflection(1.0)
        for ei in bending_stiffness_bounds(cable)
    ]
    for target in (DELTA, -DELTA):
        peak = next(r for r in full if float(r["prescribed_m"]) == target)
        assert stiffness[0] * DELTA < abs(float(peak["lateral_N"])) < stiffness[1] * DELTA
        assert np.sign(float(peak["lateral_N"])) == np.sign(target)


def test_y_b_is_reached_at_the_clamp_distance(case_file, tmp_path):
    """Under ``yb`` control the core's displacement 89 mm from the clamp, interpolated from the
    nodal unknowns here (not by the set-up), is ±yb/2 at the cycle's peaks (to the tolerance):
    a peak-to-peak Y_b of yb; the progress lines are in mm."""
    yb = 0.2e-3
    settings = [
        *QUIET,
        'load.control="displacement"',
        f"load.yb={yb}",
        "steps.yb=0.05e-3",
        "steps.yb_max=0.1e-3",
        "load.cycle=[1.0, -1.0]",
        "mesh.length=0.2",
    ]
    case = load_case(case_file, settings)
    tol = CONTROL_TOLERANCE * 0.05e-3 / 2
    problem, programme = build_problem(case, io.StringIO())
    stream = io.StringIO()
    try:
        tmp_path.joinpath("yb").mkdir()
        result = run_programme_with_outputs(case, problem, programme, tmp_path / "yb", stream)
        assert not result.failure
        g = problem.geometry
        core = np.flatnonzero(g.point_wire == 0)
        u = problem.model.node_values()[core, 0]  # along the load direction, x
        z = g.points[core, 2]
        order = np.argsort(z)
        assert abs(np.interp(0.089, z[order], u[order]) + yb / 2) <= tol  # the last peak
    finally:
        problem.solver.destroy()
    measured = [float(r["measured_m"]) for r in cycle(tmp_path / "yb")]
    assert abs(max(measured) - yb / 2) <= tol and abs(min(measured) + yb / 2) <= tol
    assert "    0.20 mm yb" in stream.getvalue()
    assert "Y_b reached 0.200 mm peak-to-peak at 89 mm from the clamp" in stream.getvalue()


@pytest.mark.slow  # 8–12 s on a fresh clone
def test_a_sweep_of_y_b_amplitudes(case_file):
    """``[load] sweep`` under yb control: one member per amplitude (``yb_<A>``), each reaching
    its own Y_b; sweep.csv gives the amplitude in m and the peak saddle load, which grows with
    it; the second member is a separate run of its amplitude (the control starts afresh from
    the tensioned state)."""
    yb = [
        'load.control="displacement"',
        "load.cycle=[1.0]",
        "mesh.length=0.2",
        "steps.yb=0.05e-3",
        "steps.yb_max=0.1e-3",
    ]
    out = run(case_file, "sweep", *yb, "load.yb=0.2e-3", "load.sweep=[0.1e-3, 0.2e-3]")
    with open(out / "sweep.csv") as f:
        table = list(csv.DictReader(f))
    assert [float(r["amplitude_m"]) for r in table] == [0.1e-3, 0.2e-3]
    assert 0 < float(table[0]["peak_lateral_N"]) < float(table[1]["peak_lateral_N"])
    for amplitude in (0.1e-3, 0.2e-3):
        last = cycle(out / f"yb_{amplitude:g}")[-1]
        assert abs(float(last["measured_m"]) - amplitude / 2) <= CONTROL_TOLERANCE * 0.025e-3
    alone = cycle(run(case_file, "alone", *yb, "load.yb=0.2e-3"))
    member = cycle(out / "yb_0.0002")
    assert [r["lateral_N"] for r in member] == [r["lateral_N"] for r in alone]


@needs_mpirun
@pytest.mark.slow
def test_y_b_control_is_the_same_on_2_ranks(case_file):
    """The secant's solves, measures and decisions are collective: on 2 ranks (the saddle and
    the point 89 mm from the clamp on different ranks) the loads found and the displacements
    are the serial run's to 1e-8 (measured: 1e-13), in as many solves."""
    sets = [
        'load.control="displacement"',
        "load.yb=0.2e-3",
        "steps.yb=0.05e-3",
        "steps.yb_max=0.1e-3",
        "mesh.length=0.2",
        *QUIET,
    ]
    args = [x for s in sets for x in ("--set", s)]
    serial = run(case_file, "serial", *sets)
    out = case_file.parent / "two_ranks"
    cmd = [
        str(MPIRUN),
        "-n",
        "2",
        sys.executable,
        "-m",
        "strand.app",
        "run",
        str(case_file),
        "--out",
        str(out),
        *args,
    ]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    a, b = cycle(serial), cycle(out)
    assert [r["solves"] for r in a] == [r["solves"] for r in b]
    for name in ("lateral_N", "measured_m", "deflection_m"):
        x, y = (np.array([float(r[name]) for r in t]) for t in (a, b))
        assert np.abs(x - y).max() <= 1e-8 * np.abs(x).max(), name


# -- the controller on a spring of its own, and the beam it starts from ----------------------------


class Spring:
    """A stiffening spring δ(P) = P/k + c P³ as a solver of one node's six unknowns (δ the
    first): a solve converges unless the load jumps by more than ``reach`` from the committed
    one (a stalling Newton)."""

    def __init__(self, k: float, c: float, reach: float = np.inf):
        self.k, self.c, self.reach = k, c, reach
        self.load = self.committed = 0.0
        self.w = SimpleNamespace(x=SimpleNamespace(array=np.zeros(6)))
        self.saved = np.zeros(6)

    def solve(self) -> NewtonResult:
        ok = abs(self.load - self.committed) <= self.reach
        if ok:
            self.w.x.array[0] = self.load / self.k + self.c * self.load**3
        return NewtonResult(ok, 1, "converged" if ok else "stalled", [0.0], 0.0)

    def commit(self) -> None:
        self.committed, self.saved = self.load, self.w.x.array.copy()

    def rollback(self) -> None:
        self.w.x.array[:] = self.saved

    def stop_requested(self) -> bool:
        return False


@pytest.mark.parametrize("reach", [np.inf, 5.0])
def test_the_control_finds_the_load_of_a_nonlinear_spring(reach):
    """Ramped by a ``LoadStepper`` to 1 mm and back below zero, the control keeps the spring's
    displacement within its tolerance at every step, at the load the spring's law gives; with
    solves that stall on load jumps over 5 N (the steps take 10–20 N), by trying again closer."""
    spring = Spring(k=1e5, c=1e-9, reach=reach)

    def set_load(p: float) -> None:
        spring.load = p

    target = {"d": 0.0}
    control = DisplacementControl(
        spring,
        lambda: spring.load,
        set_load,
        lambda: float(spring.w.x.array[0]),
        lambda: target["d"],
        lambda: 2e5,
        tolerance=1e-9,
    )
    stepper = LoadStepper(control, 1e-4, 1e-7, max_step=2e-4)
    for end in (1e-3, -0.5e-3):
        control.start()  # each ramp a stage
        stepper.ramp(lambda d: target.update(d=d), target["d"], end)
        d = float(spring.w.x.array[0])
        assert abs(d - end) <= 1e-9
        p = spring.load
        assert p / 1e5 + 1e-9 * p**3 == pytest.approx(d, abs=1e-12)
        assert control.solves <= 8


def test_the_beam_compliance_is_the_tensioned_beams():
    """``beam_compliance`` at midspan is ``TensionedBeam``'s deflection per newton with a
    linear law, and tends to the untensioned clamped beam's PL³/192EI."""
    ei, T, L = 60.0, 10e3, 0.3
    beam = TensionedBeam(L, T, lambda m: m / ei)
    assert beam_compliance(ei, T, L, L / 2) == pytest.approx(beam.deflection(1.0), rel=1e-8)
    assert beam_compliance(ei, 1e-12, L, L / 2) == pytest.approx(L**3 / (192 * ei), rel=1e-9)


# -- case-file errors ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "load, steps, fatigue, message",
    [
        ({"control": "displacement"}, {}, {}, 'control = "displacement" needs its amplitude'),
        ({"control": "displacement", "deflection": 1e-4, "yb": 1e-4}, {}, {}, "both given"),
        (
            {"control": "displacement", "deflection": 1e-4, "lateral": 300.0},
            {},
            {},
            "[load] lateral = 300 N is a force amplitude",
        ),
        (
            {"control": "displacement", "yb": 1e-4},
            {},
            {},
            "[fatigue] clamp_distance = 0.089 m, where yb is measured, is not short of midspan",
        ),
        (
            {"control": "displacement", "yb": 1e-4},
            {},
            {"clamp_distance": 0.06},
            "clamp_distance = 0.06 m",
        ),
        ({"deflection": 1e-4}, {}, {}, "[load] deflection = 0.0001 m is a displacement amplitude"),
        (
            {"control": "stroke"},
            {},
            {},
            "[load] control = 'stroke' is unknown; choose force or displacement",
        ),
        (
            {"control": "displacement", "yb": -1e-4},
            {},
            {},
            "[load] yb = -0.0001 m: expected a positive amplitude",
        ),
        (
            {"control": "displacement", "yb": 1e-4},
            {"yb": 1e-3},
            {},
            "[steps] yb = 0.001 m exceeds yb_max = 0.0002 m",
        ),
    ],
)
def test_bad_displacement_settings_are_refused_in_one_line(load, steps, fatigue, message):
    data = tomllib.loads(CASE)
    data["load"] = {k: v for k, v in data["load"].items() if k != "lateral"} | load
    data["steps"] |= steps
    data["fatigue"] = fatigue
    with pytest.raises(CaseError) as e:
        case_from_dict(data, source="case.toml")
    assert message in str(e.value) and "\n" not in str(e.value)


def test_the_displacement_case_file_reads():
    """cases/quick_1x6_yb.toml: a Y_b of 1 mm at 89 mm on 0.3 m, the cycle in yb."""
    from pathlib import Path

    from strand.app.kinds import kind_of

    case = load_case(Path(__file__).parents[1] / "cases" / "quick_1x6_yb.toml")
    kind = kind_of(case)
    assert (kind.parameter, kind.unit, kind.measure) == ("yb", "m", "lateral")
    assert kind.amplitude(case) == 1e-3 and case.fatigue.clamp_distance == 0.089
    assert [s.target for s in kind.programme(case).stages[1:]] == [1e-3, 0.0, -1e-3, 0.0]
