"""The main job: case settings, the runner's outputs, and the analytical references it reports."""

from __future__ import annotations

import csv
import tomllib

import numpy as np
import pytest

from strand.analytical.fibre import bending_stiffness_bounds, fibre_model
from strand.app.case import CaseError, load_case
from strand.app.cli import main
from strand.cable.description import cardinal
from strand.contact.element import ContactGroup
from strand.contact.normal_laws import PenaltyLaw
from strand_cases import SEVEN_WIRE


def test_default_case_is_the_seed_papers_test():
    case = load_case()
    assert case.cable.name.startswith("Cardinal") and case.mesh.length == 1.0
    assert case.load.tension == 40e3 and case.load.lateral == 4.3e3
    assert case.load.cycle == (1.0, 0.0, -1.0, 0.0) and case.load.saddle_length == 0.02
    assert case.contact.normal == "director" and case.contact.friction
    assert case.output.folder == "results/cardinal"


def test_a_case_file_writes_to_results_named_after_it(tmp_path):
    path = tmp_path / "short_span.toml"
    path.write_text("[mesh]\nlength = 0.3\n")
    assert load_case(path).output.folder == "results/short_span"
    path.write_text('[output]\nfolder = "elsewhere"\n')
    assert load_case(path).output.folder == "elsewhere"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[contact]\nnormal = 'radial'\n", "normal = 'radial' is unknown"),
        ("[contact]\nkn = 1e7\n", r"unknown setting\(s\) in \[contact\]: \['kn'\]"),
        ("[load]\ntension = 'big'\n", r"\[load\] tension = 'big': expected a number"),
        ("[load]\ncycle = []\n", "expected at least one lateral target"),
        ("[load]\ncycle = [0.0]\nsweep = [1e3]\n", r"needs a cycle with a target other than 0"),
        ("[load]\ndirection = [0, 0, 1]\n", "a direction across the strand axis"),
        ("[steps]\nmax_iterations = 2.5\n", "expected a whole number"),
        ("[steps]\nlateral = 500.0\n", "exceeds lateral_max"),
        ("[steps]\ntolerance = -1\n", r"\[steps\] tolerance = -1 N: expected a positive number"),
        (
            "[steps]\nbalance = -1e-4\n",
            r"balance = -0.0001: expected a positive number, or 0 for off",
        ),
        ("[steps]\nstall = 1\n", r"\[steps\] stall = 1: expected true or false"),
        (
            "[steps]\nline_search = 'nl'\n",
            r"\[steps\] line_search = 'nl' is unknown; choose cp, basic, bt or l2",
        ),
        ("[output]\nplots = 1\n", "expected true or false"),
        ("[solver]\natol = 1\n", r"unknown setting\(s\) \['solver'\]"),
    ],
)
def test_bad_settings_are_named_before_computing(tmp_path, capsys, text, message):
    path = tmp_path / "case.toml"
    path.write_text(text)
    with pytest.raises(CaseError, match=message):
        load_case(path)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "case.toml" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()  # nothing computed, nothing written


def test_fibre_model_and_stiffness_bounds_match_the_reference_numbers():
    """docs/theory.md §5.1, §5.3 worked out for Cardinal: EA = 39.44 MN, ε(40 kN) = 1014 µε, wire forces 1866/1582/546/547/541 N,
    EI_min = 28.81 N m², EI_max = 1800 N m²."""
    ref = fibre_model(cardinal(), 40e3)
    assert ref["EA"] == pytest.approx(39.44e6, rel=2e-3)
    assert ref["strain"] == pytest.approx(1014e-6, rel=2e-3)
    assert np.allclose(ref["wire_force"], [1866, 1582, 546, 547, 541], rtol=3e-3)
    ei_min, ei_max = bending_stiffness_bounds(cardinal())
    assert ei_min == pytest.approx(28.81, rel=2e-3)
    assert ei_max == pytest.approx(1800, rel=2e-3)


def test_run_writes_every_output_and_balances_the_section(tmp_path, capsys):
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE)
    out = tmp_path / "out"
    assert main(["run", str(case), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "[" in text and "Newton its" in text and "done:" in text
    for name in (
        "fields.xdmf",
        "fields.h5",
        "steps.csv",
        "axial_forces.csv",
        "moment_curvature.csv",
        "summary.txt",
        "case.toml",
        "README.txt",
    ):
        assert (out / name).stat().st_size > 0, name
    assert (out / "fields.bp").is_dir()
    with open(out / "steps.csv") as f:
        steps = list(csv.DictReader(f))
    times = [float(s["time"]) for s in steps]  # the fields' time axis: one unit per stage
    assert np.all(np.diff(times) > 0) and times[-1] == 3.0
    assert [float(s["time"]) for s in steps if s["stage"] == "tension"][-1] == 1.0
    assert float(steps[-1]["lateral_N"]) == 0.0
    assert max(float(s["lateral_N"]) for s in steps) == pytest.approx(300.0)
    assert all(float(s["tension_N"]) == pytest.approx(10e3) for s in steps[2:])
    # deflection grows with the load and a loop remains (friction): δ(0, unloaded) ≥ 0
    loaded = [float(s["deflection_m"]) for s in steps if s["stage"] == "leg 1"]
    assert np.all(np.diff(loaded) > 0)
    forces = np.loadtxt(out / "axial_forces.csv", delimiter=",", skiprows=1)
    assert len(np.unique(forces[:, 0])) == len(steps)
    # the section at midspan carries exactly the tension (moment-curvature file)
    mk = np.loadtxt(out / "moment_curvature.csv", delimiter=",", skiprows=1, ndmin=2)
    assert np.allclose(mk[:, 4], 10e3, rtol=1e-6)
    assert np.all(mk[np.argmax(mk[:, 1]), 2:4] > 0)  # positive load: positive κ and M
    summary = (out / "summary.txt").read_text()
    assert "fibre model" in summary and "wire force layer 1" in summary
    assert "tensioned beam with the stick–slip law" in summary


def test_tension_matches_the_fibre_model_when_contacts_are_stiff():
    """A 0.2 m piece of Cardinal at 40 kN: with contacts 10× stiffer than the seed paper's penalty
    the strand strain and the wire forces per layer are within 3 % of the fibre model (which takes
    the contacts as rigid); the seed paper's penalty adds about 5 % of strain, the default Hertz
    compliance 6 %."""
    from strand.app.case import case_from_dict
    from strand.cable.geometry import build_geometry
    from strand.model.cell_results import cell_results
    from strand.model.problem import StrandProblem
    from strand.setups import SaddleTest
    from strand.solver import LoadStepper, NewtonOptions

    case = case_from_dict(
        {"contact": {"compliance": "penalty", "k_point": 5e8, "k_line": 5e10, "same_layer": "off"}}
    )
    geometry = build_geometry(case.cable, 0.2, 4e-3)
    problem = StrandProblem(geometry, case.contact, NewtonOptions(atol=1e-2), setup=SaddleTest)
    LoadStepper(problem.solver, 10e3, 100.0).ramp(problem.setup.set_tension, 0.0, 40e3)
    ref = fibre_model(case.cable, 40e3)
    strain = problem.setup.end_displacement() / geometry.length
    assert strain == pytest.approx(ref["strain"], rel=0.03)
    cells = cell_results(problem.model)
    middle = np.abs(cells.z - 0.1) < 0.05
    for layer, expected in enumerate(ref["wire_force"]):
        assert cells.axial[middle & (cells.layer == layer)].mean() == pytest.approx(
            expected, rel=0.03
        )


@pytest.mark.slow  # 11–13 s on a fresh clone
def test_compare_runs_both_sliding_models_and_they_agree(tmp_path, capsys):
    """`strand compare`: both contact models run the same case into their own folders; on a short
    1+6 strand (sliding of micrometres) their deflections agree within 0.5 % and their wire axial
    forces within 2 % of each layer's force range; the table and figure are written."""
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE.replace("plots = false", "plots = true\nfields = false"))
    out = tmp_path / "cmp"
    assert main(["compare", str(case), "--out", str(out)]) == 0
    text = (out / "comparison.txt").read_text()
    assert text in capsys.readouterr().out
    rows = {line.split()[0]: line.split() for line in text.splitlines()[2:4]}
    assert set(rows) == {"small", "large"}
    d_small, d_large = float(rows["small"][7]), float(rows["large"][7])
    assert d_small > 0 and d_large == pytest.approx(d_small, rel=5e-3)
    layers = [line.split() for line in text.splitlines() if line.split()[:1] in (["core"], ["1"])]
    assert len(layers) == 2 and all(float(row[2]) < 0.02 for row in layers)
    assert (out / "sliding_comparison.png").stat().st_size > 0
    for model in ("small", "large"):
        assert (out / model / "steps.csv").stat().st_size > 0
        case_file = tomllib.loads((out / model / "case.toml").read_text())
        assert case_file["contact"]["model"] == model


def test_small_sliding_check_against_its_closed_form():
    """Crossing nodes moved round the strand by s: gap drift s²/(2R) (R the outer layer's helix
    radius); moved along the axis, or all together: none; the warning names the interface."""
    from strand.cable.geometry import LINE, build_geometry
    from strand.model.sliding_check import sliding_check

    g = build_geometry(cardinal(), 0.1, 4e-3)
    p = g.pairs
    gap = np.full(len(p.a), -10e-6)
    around = np.cross([0.0, 0.0, 1.0], p.normal)
    around /= np.linalg.norm(around, axis=1)[:, None]
    s = 0.2e-3
    radii = np.array([lay.radius for lay in g.cable.layers])
    for i in (1, 2, 3):  # the outer nodes of one interface's crossings moved round by s
        m = p.interface == i
        x = g.points.copy()
        x[p.b[m]] += s * around[m]
        check = sliding_check(g, x, gap)
        assert check.drift[i] == pytest.approx(s**2 / (2 * radii[i + 1]), rel=1e-12)
        assert check.drift[0] == 0.0  # core | layer 1: line pairs, not checked
        np.testing.assert_allclose(check.approach[1:], 10e-6)
        # 3.0 µm at 1|2 exceeds 25 % of 10 µm; 2.0 µm (2|3) and 1.5 µm (3|4) do not
        assert check.exceeded().tolist() == ([1] if i == 1 else [])
    assert check.share[3] == 0.0 and check.z[3] > 0
    x = g.points.copy()
    x[p.b[p.interface == 1]] += s * around[p.interface == 1]
    check = sliding_check(g, x, gap)
    closed = np.count_nonzero((p.interface == 1) & (p.kind != LINE))
    assert check.share[1] == 1.0 and check.beyond[1] == check.closed[1] == closed
    assert (
        f"interface 1|2: the wires slid round the strand so far that the gaps of {closed:,} of its {closed:,} closed pairs (100 %,"
        in check.message()
    )
    axial = g.points + np.where(np.isin(np.arange(len(x)), p.b)[:, None], [0, 0, 1e-3], 0.0)
    assert np.all(sliding_check(g, axial, gap).drift == 0.0)
    assert np.all(sliding_check(g, g.points + 1e-3, gap).drift < 1e-20)


@pytest.mark.parametrize("interface", [1, 2, 3])
def test_small_sliding_drift_is_the_elements_own_gap_drift(interface):
    """The outer wire of a Cardinal crossing slid along its helix by 1 mm (its node moved and
    turned with the helix): the contact element's gap (director normal) drifts by 70–100 % of
    s²/(2R), s the slide round the strand: the estimate the small-sliding check uses is an upper
    bound within 30 % (measured: 78 / 91 / 93 % at 1|2 / 2|3 / 3|4)."""
    from strand.cable.geometry import build_geometry

    g = build_geometry(cardinal(), 0.4, 4e-3)
    p, layers = g.pairs, g.cable.layers
    k = np.flatnonzero(p.interface == interface)[100]
    inner, outer = layers[interface], layers[interface + 1]

    def tangent(lay, x):
        phi, r, w = np.arctan2(x[1], x[0]), lay.radius, lay.angular_rate
        t = np.array([-r * w * np.sin(phi), r * w * np.cos(phi), 1.0])
        return t / np.linalg.norm(t)

    t0 = np.array([[tangent(inner, g.points[p.a[k]]), tangent(outer, g.points[p.b[k]])]])
    group = ContactGroup(
        np.array([[0, 1]]),
        g.points[[p.a[k], p.b[k]]][None],
        False,
        [p.radius_a[k]],
        [p.radius_b[k]],
        p.normal[k][None],
        PenaltyLaw(np.array([5e7])),
        friction_law=None,
        normal="director",
        tangent0=t0,
    )
    dz = 1e-3 * np.cos(outer.alpha)
    dphi = outer.angular_rate * dz
    c, s = np.cos(dphi), np.sin(dphi)
    w = np.zeros((2, 6))
    w[1, :3] = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ g.points[p.b[k]] + [0, 0, dz]
    w[1, :3] -= g.points[p.b[k]]
    w[1, 5] = dphi
    group.evaluate(w, False)
    drift = (outer.radius * dphi) ** 2 / (2 * outer.radius)
    assert 0.7 * drift < group.state.gap[0] <= drift


def test_programme_time_runs_one_unit_per_stage():
    from strand.model.programme import LoadProgramme, Stage

    stages = (
        Stage("tension", "tension", 40e3, 1.0, 0.1),
        *(Stage(f"leg {i}", "lateral", c, 1.0, 0.1) for i, c in enumerate((4e3, 0.0, -4e3))),
    )
    prog = LoadProgramme(stages, "lateral")
    assert prog.time(0, 10e3) == 0.25 and prog.time(0, 40e3) == 1.0
    assert prog.time(1, 1e3) == 1.25 and prog.time(2, 1e3) == 2.75 and prog.time(3, -4e3) == 4.0


def test_progress_weights_share_the_programme_also_when_the_cycle_stays_at_zero():
    """Progress shares sum to 1; a cycle that goes nowhere (``cycle = [0.0]``: tension only)
    leaves all of it to the tension instead of dividing by its zero path length."""
    from strand.model.programme import LoadProgramme, Stage

    tension = Stage("tension", "tension", 40e3, 10e3, 100.0)
    for targets, expected in [
        ((1.0, 0.0, -1.0, 0.0), [0.1, 0.225, 0.225, 0.225, 0.225]),
        ((0.0,), [1.0, 0.0]),
    ]:
        legs = [Stage(f"leg {i}", "lateral", 4.3e3 * c, 250.0, 4.0) for i, c in enumerate(targets)]
        weights = LoadProgramme((tension, *legs), "lateral").weights()
        assert weights == pytest.approx(expected)


def test_a_failed_runs_effort_line_counts_the_failed_steps_attempts(tmp_path):
    """The FAILED line's iterations and LUs hold the attempts of the step that failed (no step
    record does), so that its time per iteration is the run's."""
    from strand.app.run_result import RunResult
    from strand.app.summary import effort_line
    from strand.solver import StepRecord

    steps = (StepRecord("tension", 100.0, 4, [1.0], 1.0, 0, 0, factorisations=4),)
    ran = dict(folder=tmp_path, steps=steps, failure="no convergence", seconds=30.0)
    before = effort_line(RunResult(**ran))
    after = effort_line(RunResult(**ran, failed_step_effort=(56, 60)))
    assert before.startswith("FAILED: 1 steps, 4 Newton iterations (+ 0 in failed attempts")
    assert after.startswith("FAILED: 1 steps, 4 Newton iterations (+ 56 in failed attempts")
    assert "64 LUs" in after and "(0.50 s per iteration" in after
