"""Set-up kinds are registered in one place: a kind defined outside strand (here, a toy that
cycles an extra end force on top of the tension) runs through the command line like the built-in
ones, with its own settings, programme, measures, summary lines and sweep; an unknown kind is
refused in one line naming the known ones."""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import partial

import numpy as np
import pytest

from strand.analytical.fibre import fibre_model
from strand.app import kinds
from strand.app.case import CaseError, case_from_dict, load_case
from strand.app.cli import main
from strand.app.kinds import NoSettings, SetupKind
from strand.beam.records import quantity
from strand.beam.setting import setting
from strand.model.cell_results import section_resultants
from strand.setups.saddle import SaddleTest
from strand_cases import SEVEN_WIRE

QUICK = ["output.fields=false", "output.plots=false", "fatigue.outputs=false", 'load.kind="pull"']
#: the command line's options for them
QUICK_ARGS = [arg for setting in QUICK for arg in ("--set", setting)]


@dataclass(frozen=True)
class PullState:
    tension: float = quantity("N", "end force held through the cycle")
    pull: float = quantity("N", "extra end force, cycled")
    end_displacement: float = quantity("m", "axial displacement of the end section")

    def progress(self) -> str:
        return f"u = {1e6 * self.end_displacement:6.2f} µm"


@dataclass(frozen=True)
class PullSection:
    pull: float = quantity("N")
    axial_sum: float = quantity("N", "Σ N_z over the midspan section")


class PullTest(SaddleTest):
    """The saddle test's ends without its saddle: the end force is the tension plus ``pull``."""

    parameters = ("tension", "pull")
    units = {"tension": "N", "pull": "N"}
    cycle_parameter = "pull"
    state_type = PullState
    bending_type = PullSection

    def __init__(self, model, direction=(1.0, 0.0, 0.0)):
        super().__init__(model, direction=direction)
        self.loads = {"tension": 0.0, "pull": 0.0}

    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        self.loads[name] = value
        self.tension_load.factor = self.loads["tension"] + self.loads["pull"]

    def get(self, name: str) -> float:
        self.check_parameter(name)
        return self.loads[name]

    def state(self) -> PullState:
        return PullState(self.loads["tension"], self.loads["pull"], self.end_displacement())

    def moment_curvature(self, cells, residual=None) -> PullSection:
        _, force = section_resultants(self.model, cells, self.model.geometry.length / 2)
        return PullSection(self.loads["pull"], float(force[2]))


#: the toy's own setting, declared in this one place
PULL_MEANING = "Extra end force cycled on top of the tension, the toy's own setting."


@dataclass(frozen=True)
class PullLoad:
    pull: float = setting(2e3, PULL_MEANING, unit="N", sign="any")


@dataclass(frozen=True)
class PullSteps:
    pull: float = setting(1e3, "First pull increment of each leg.", unit="N")
    pull_max: float = setting(2e3, "Largest pull increment.", unit="N")


class Pull(SetupKind):
    name = "pull"
    parameter = "pull"
    unit = "N"
    progress_unit = ("kN", 1e3)
    measure = "end_displacement"
    load_settings = PullLoad
    step_settings = PullSteps

    def setup(self, case):
        return partial(PullTest, direction=case.load.direction)

    def reference(self, case, result) -> list[float]:
        """The fibre model's end displacement (m) at every cycle step."""
        ea = fibre_model(case.cable, 1.0)["EA"]
        return [
            (s.state.tension + s.state.pull) * case.mesh.length / ea for s in result.cycle_steps
        ]

    def summary_lines(self, case, result) -> list[str]:
        peak = result.peak_step
        if peak is None:
            return []
        ref = result.reference[result.cycle_steps.index(peak)]
        return [
            f"pull {peak.load:.0f} N: end displacement {1e6 * peak.state.end_displacement:.2f}"
            f" µm, fibre model {1e6 * ref:.2f} µm"
        ]


@pytest.fixture
def pull():
    kind = kinds.register(Pull())
    yield kind
    kinds.unregister(kind.name)


@pytest.fixture
def seven(tmp_path):
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    return path


def rows(path) -> list[dict[str, str]]:
    with open(path) as f:
        return list(csv.DictReader(f))


def test_a_kind_defined_outside_strand_runs_like_the_built_in_ones(pull, seven, tmp_path, capsys):
    """The toy's own settings come from the case file; its cycle is its parameter's, its measures
    are the CSV columns, its section carries the tension plus the pull exactly, the pull
    stretches the strand by the fibre model's compliance L/EA within 1 % (measured 0.05 %), and
    its summary line is written."""
    out = tmp_path / "out"
    assert main(["run", str(seven), "--out", str(out), "--set", "load.pull=3e3", *QUICK_ARGS]) == 0
    assert "pull" in capsys.readouterr().out
    steps = rows(out / "steps.csv")
    assert {"pull_N", "end_displacement_m"} <= set(steps[0])
    assert "deflection_m" not in steps[0]
    assert [s["stage"] for s in steps][-1] == "leg 2"
    assert max(float(s["pull_N"]) for s in steps) == pytest.approx(3e3)
    assert float(steps[-1]["pull_N"]) == 0.0
    sections = rows(out / "moment_curvature.csv")
    for s in sections:  # equilibrium: the midspan section carries the whole end force
        assert float(s["axial_sum_N"]) == pytest.approx(10e3 + float(s["pull_N"]), rel=1e-6)
    cycle = [s for s in steps if s["stage"] != "tension"]
    u = np.array([float(s["end_displacement_m"]) for s in cycle])
    P = np.array([float(s["pull_N"]) for s in cycle])
    tensioned = float([s for s in steps if s["stage"] == "tension"][-1]["end_displacement_m"])
    top = int(np.argmax(P))
    ea = fibre_model(load_case(seven).cable, 1.0)["EA"]
    assert (u[top] - tensioned) / P[top] == pytest.approx(0.1 / ea, rel=0.01)
    assert "pull 3000 N: end displacement" in (out / "summary.txt").read_text()


def test_a_sweep_reports_the_kinds_measure(pull, seven, tmp_path):
    out = tmp_path / "sweep"
    assert (
        main(
            [
                "run",
                str(seven),
                "--out",
                str(out),
                "--set",
                "load.sweep=[1e3, 2e3]",
                "--set",
                "load.cycle=[1.0]",
                *QUICK_ARGS,
            ]
        )
        == 0
    )
    table = rows(out / "sweep.csv")
    assert [r["amplitude_N"] for r in table] == ["1000", "2000"]
    peaks = [float(r["peak_end_displacement_m"]) for r in table]
    assert 0 < peaks[0] < peaks[1] and (out / "pull_2000" / "steps.csv").exists()


def test_a_kinds_own_settings_are_checked_and_refused_in_other_cases(pull):
    case = case_from_dict({"load": {"kind": "pull", "pull": 500.0}})
    assert pull.load(case).pull == 500.0 and case.load.pull == 500.0
    with pytest.raises(CaseError, match=r"\[steps\] pull = 3000.0 N exceeds pull_max = 2000.0 N"):
        case_from_dict({"steps": {"pull": 3e3}})
    kinds.unregister("pull")
    try:
        with pytest.raises(CaseError, match=r"unknown setting\(s\) in \[load\]: \['pull'\]"):
            case_from_dict({"load": {"pull": 500.0}})
    finally:
        kinds.register(pull)


@dataclass(frozen=True)
class ClashLoad:
    lateral: float = setting(1.0, "The saddle test's setting.", unit="N")


@dataclass(frozen=True)
class ClashSteps:
    tension: float = setting(1.0, "A setting every kind shares.", unit="N")


@dataclass(frozen=True)
class UndeclaredLoad:
    twist: float = 1.0  # rad: a setting without its declaration


def test_a_kind_may_not_take_another_kinds_settings():
    class Clash(Pull):
        name = "clash"
        load_settings = ClashLoad
        step_settings = NoSettings

    with pytest.raises(ValueError, match=r"settings \['lateral'\] belong to saddle"):
        kinds.register(Clash())
    Clash.load_settings, Clash.step_settings = NoSettings, ClashSteps
    with pytest.raises(ValueError, match=r"settings \['tension'\] belong to every kind"):
        kinds.register(Clash())
    Clash.load_settings, Clash.step_settings = UndeclaredLoad, NoSettings
    with pytest.raises(ValueError, match=r"settings \['twist'\] are not declared"):
        kinds.register(Clash())
    assert "clash" not in [k.name for k in kinds.registered()]


def test_an_unknown_kind_is_refused_in_one_line_naming_the_known_ones(seven, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(seven), "--out", str(out), "--set", 'load.kind="twist"']) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0]
    assert err[0].endswith(
        "[load] kind = 'twist' is unknown; choose saddle, bending, tension_cycle or fairlead"
    )
    assert not out.exists()


def test_figure_titles_name_the_kinds_own_load():
    """Figure titles give the largest load as the kind names its cycled parameter: the saddle
    load P in kN (as ever), the curvature κ of a bending run (not "P = 0.00 kN"), the tension
    swing ΔT, and a displacement-controlled saddle test's prescribed deflection in mm."""
    from strand.app.kinds.saddle import SaddleDisplacement

    assert kinds.lookup("saddle").load_text(4300.0) == "P = 4.30 kN"
    assert kinds.lookup("bending").load_text(0.0125) == "κ = 0.0125 1/m"
    assert kinds.lookup("tension_cycle").load_text(-2000.0) == "ΔT = -2.00 kN"
    assert SaddleDisplacement("deflection").load_text(1.5e-3) == "deflection = 1.50 mm"


def test_a_kinds_setting_declared_once_is_everywhere(pull, capsys):
    """The toy's ``[load] pull``, declared in one place (``PullLoad``), is read and checked from
    a case file (its unit in the refusal), listed by ``strand run --help``, the settings
    reference and the case template, written into ``case.toml`` and described by the JSON
    Schema, which checks its sign."""
    import json
    import tomllib

    import jsonschema

    from strand.app.case_toml import case_toml
    from strand.app.settings_reference import sections
    from strand.app.settings_schema import json_schema, template

    case = case_from_dict({"load": {"kind": "pull", "pull": 500.0}})
    assert case.load.pull == 500.0
    with pytest.raises(CaseError, match=r"\[load\] pull = 'much': expected a number"):
        case_from_dict({"load": {"pull": "much"}})
    with pytest.raises(CaseError, match=r"\[steps\] pull = -1 N: expected a positive number"):
        case_from_dict({"steps": {"pull": -1}})

    with pytest.raises(SystemExit):
        main(["run", "--help"])
    help_text = capsys.readouterr().out
    line = '  pull = 2000                 (kind = "pull") (N) Extra end force cycled'
    assert line in help_text

    own = {s.name: s for s in sections()["load"][1] if s.kind == "pull"}
    assert own["pull"].meaning == PULL_MEANING and own["pull"].unit == "N"

    text = template()
    assert 'pull = 2000               # N, kind = "pull": Extra end force cycled' in text
    default = case_from_dict(tomllib.loads(text))
    assert default.load.pull == 2e3 and default.steps.pull_max == 2e3

    assert "pull = 500.0" in case_toml(case).split("[load]")[1].split("[steps]")[0]

    schema = json_schema()
    pull_schema = schema["properties"]["load"]["properties"]["pull"]
    assert PULL_MEANING in pull_schema["description"] and pull_schema["default"] == 2e3
    steps_schema = schema["properties"]["steps"]["properties"]["pull"]
    assert steps_schema["exclusiveMinimum"] == 0
    validator = jsonschema.Draft7Validator(json.loads(json.dumps(schema)))
    assert validator.is_valid({"load": {"kind": "pull", "pull": -3.0}, "steps": {"pull": 1.0}})
    assert not validator.is_valid({"steps": {"pull": -1.0}})
    assert not validator.is_valid({"load": {"pul": 1.0}})
