"""The command line as a user meets it: bad input gets one line and nothing is computed, results
folders never mix two runs, Ctrl-C keeps what was computed, ``--set`` and ``--version``."""

from __future__ import annotations

import csv
import os
import re
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest

from strand import __version__
from strand.app.case import CaseError, case_from_dict, load_case
from strand.app.checks import tension_warning
from strand.app.cli import main
from strand_cases import SEVEN_WIRE, contents, earlier_run, one_line_error

ROOT = Path(__file__).parents[1]
QUICK = SEVEN_WIRE.replace("plots = false", "plots = false\nfields = false")


@pytest.fixture
def seven(tmp_path) -> Path:
    path = tmp_path / "seven.toml"
    path.write_text(QUICK)
    return path


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["{tmp}"], "is a folder; give a case file"),
        (["{case}", "--set", "mesh.h_max=0.2"], r"h_max = 0.2 m must be shorter than the span"),
        (["{case}", "--set", "load.saddle_length=0.5"], "saddle_length = 0.5 m must be shorter"),
        (["{case}", "--set", "load.saddle_length=1e-3"], "at least \\[mesh\\] h_max"),
        (["{case}", "--set", "load.tension=-5e3"], "compressed strand is outside the model"),
        (
            ["{case}", "--set", "steps.relax=1e5", "--set", "steps.stabilise=0"],
            r"\[steps\] relax = 100000 N/m needs \[steps\] stabilise > 0",
        ),
        (["{case}", "--set", "meshh_max"], "expected section.key=value"),
        (["{case}", "--set", "mesh.hmax=1"], r"unknown setting\(s\) in \[mesh\]: \['hmax'\]"),
        # elements from a tenth of the 3.34 mm wires to an eighth of the 198 mm lay length
        (
            ["{case}", "--set", "mesh.h_max=1e-6"],
            r"\[mesh\] h_max = 1e-06 m is out of range \[0\.000334, 0\.0247\] m for this cable",
        ),
        (["{case}", "--set", "mesh.h_max=0.03"], r"h_max = 0\.03 m is out of range \[0\.000334, "),
        (
            ["{case}", "--set", "mesh.length=-0.1"],
            r"\[mesh\] length = -0\.1 m: expected a positive",
        ),
        (
            ["{case}", "--set", "cable.core.nuu=0.3"],
            "the cable's core has no key 'nuu'; valid: E, diameter, friction, nu, "
            "shear_coefficient, tensile_strength, torsional_stiffness, yield_stress$",
        ),
        (
            ["{case}", "--set", "cable.layer.1.colour=1"],
            "a cable layer has no key 'colour'; valid: ",
        ),
        (["{case}", "--set", "cable.cor.nu=0.3"], "one of cable.name, cable.core.<key>, cable"),
        (["{case}", "--set", "cable.layer.2.E=60e9"], "has layers 1 to 1"),
        (
            ["{case}", "--set", "cable.core.nu=0.6"],
            r"cable: core\.nu = 0\.6 is out of range \(-1, ",
        ),
        (
            ["{case}", "--set", "cable.layer[1].diameter=2.5"],
            r"layer\[1\]\.diameter = 2\.5 m is out of range \(0, 1\) m$",
        ),
        (
            ["{case}", "--set", "cable.core.E=210"],
            r"cable: core\.E = 210 Pa: did you mean 210e9\? A wire's modulus is given in Pa",
        ),
        (["{case}", "--set", "cable.layer.1.E=180e3"], r"layer\[1\]\.E = 180000 Pa: did you"),
        (["{case}", "--out", "{case}"], "is a file, not a folder"),
        (["{case}", "--out", "{case}/sub"], "cannot create the results folder"),
    ],
)
def test_bad_input_gets_one_line_and_nothing_is_computed(tmp_path, seven, capsys, args, message):
    args = [a.format(tmp=tmp_path, case=seven) for a in args]
    before = sorted(tmp_path.rglob("*"))
    assert main(["run", *args]) == 2
    line = one_line_error(capsys)
    assert line.startswith("strand: error: ")
    assert re.search(message, line), line
    assert sorted(tmp_path.rglob("*")) == before  # nothing computed, nothing written


@pytest.mark.parametrize("command", ["run", "mesh", "compare"])
def test_a_modulus_in_gpa_is_refused_in_one_line_and_nothing_is_written(
    tmp_path, capsys, monkeypatch, command
):
    """E = 210 (meant as GPa) in a case's cable: refused as the case is read, naming E and the
    value meant; no results folder (the default one, results/<case>, under the working folder)
    nor any other file is written."""
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "gpa.toml"
    path.write_text(QUICK.replace("E = 210e9", "E = 210", 1))
    before = contents(tmp_path)
    assert main([command, str(path)]) == 2
    line = one_line_error(capsys)
    assert line == (
        f"strand: error: {path}: cable: core.E = 210 Pa: did you mean 210e9? A wire's modulus "
        "is given in Pa, and none is under 1 GPa"
    )
    assert contents(tmp_path) == before


def test_a_tension_far_from_the_breaking_strength_is_warned_of_in_one_line():
    """The mooring case (MBS 3.606 MN given) with its loads typed in kN (901.5, 180.3, 18):
    0.025 % of the MBS; 4 MN: 111 %; its own 901.5 kN (25 %): no warning. Without an MBS,
    the wires' aggregate yield force Σ A σ_y stands for it: a 1+6 of 3.34 mm wires at
    1540 MPa, 7 π/4 (3.34 mm)² 1540 MPa = 94.45 kN, of which 500 N is 0.529 %; a cable without
    yield stresses (Cardinal) has neither, and no warning."""
    mooring = ROOT / "cases" / "mooring_judge120.toml"
    in_kn = ["load.tension=901.5", "load.tension_swing=180.3", "load.fixed_lateral=18"]
    assert tension_warning(load_case(mooring, in_kn)) == (
        "[load] tension = 901.5 N is 0.025 % of the strand's breaking strength ([fatigue] "
        "breaking_strength), 3.606e+06 N: is it in kN? Forces are in N"
    )
    high = tension_warning(load_case(mooring, ["load.tension=4e6"]))
    assert high.startswith("[load] tension = 4e+06 N is 111 % of the strand's breaking strength")
    assert high.endswith("the strand would break")
    assert tension_warning(load_case(mooring)) == ""
    yielding = QUICK.replace("nu = 0.3\n", "nu = 0.3\nyield_stress = 1540e6\n")
    seven = tomllib.loads(yielding)
    force = 7 * np.pi / 4 * 3.34e-3**2 * 1540e6
    assert force == pytest.approx(94.45e3, rel=1e-4)
    seven["load"]["tension"] = 500.0
    assert tension_warning(case_from_dict(seven)) == (
        "[load] tension = 500 N is 0.529 % of the strand's wires' aggregate yield force Σ A σ_y "
        f"(no [fatigue] breaking_strength given), {force:.4g} N: is it in kN? Forces are in N"
    )
    seven["load"]["tension"] = 10e3
    assert tension_warning(case_from_dict(seven)) == ""
    seven["load"]["tension"] = 500.0  # a tensile strength is preferred to the yield stress
    strong = {"tensile_strength": 1770e6}
    seven["cable"]["core"] |= strong
    seven["cable"]["layer"][0] |= strong
    assert "tensile force Σ A σ_u (no [fatigue] breaking_strength given), 1.086e+05 N" in (
        tension_warning(case_from_dict(seven))
    )
    # Cardinal's wires give their tensile strengths (1600 and 165 MPa): Σ A σ_u = 175.3 kN
    assert tension_warning(load_case(None, ["load.tension=40.0"])).startswith(
        "[load] tension = 40 N is 0.0228 % of the strand's wires' aggregate tensile force"
    )
    assert tension_warning(load_case(None)) == ""


def test_a_run_warns_of_its_tension_once_and_its_summary_repeats_it(tmp_path, seven, capsys):
    """10 kN on a 1+6 given an MBS of 2 MN (0.5 %): the run prints the warning once, before its
    first step, runs to the end (exit 0), and summary.txt repeats it."""
    out = tmp_path / "out"
    args = ["run", str(seven), "--out", str(out), "--set", "load.cycle=[0.0]"]
    assert main([*args, "--set", "fatigue.breaking_strength=2e6"]) == 0
    printed = capsys.readouterr().out.splitlines()
    warned = [n for n, line in enumerate(printed) if "strand: warning: [load] tension" in line]
    assert len(warned) == 1 and "= 10000 N is 0.5 % of the strand's breaking" in printed[warned[0]]
    first_step = next(n for n, line in enumerate(printed) if "Newton its" in line)
    assert warned[0] < first_step
    summary = (out / "summary.txt").read_text()
    assert "warning: [load] tension = 10000 N is 0.5 % of the strand's breaking" in summary


def test_run_help_lists_every_setting_of_every_section():
    """``strand run --help`` lists the settings from the settings classes, the same source as
    the settings reference: every key of every section, each set-up kind's own too, under its
    section and with its default."""
    from dataclasses import fields

    from strand.app.kinds import registered
    from strand.app.settings import KIND_SECTIONS, SECTIONS
    from strand.app.settings_reference import default_toml

    done = subprocess.run(
        [sys.executable, "-m", "strand.app", "run", "--help"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    text = done.stdout
    blocks = dict(re.findall(r"^\[(\w+)\]\n(.*?)(?=^\[|^\S|\Z)", text, re.M | re.S))
    assert list(blocks) == list(SECTIONS)
    for section, cls in SECTIONS.items():
        classes = [cls] + [
            getattr(k, KIND_SECTIONS[section]) for k in registered() if section in KIND_SECTIONS
        ]
        for f in (f for c in classes for f in fields(c) if f.name != "by_kind"):
            key = rf"^  {f.name} = {re.escape(default_toml(f))}(\s|$)"
            assert re.search(key, blocks[section], re.M), (section, f.name)
    assert re.search(r'^cable = "cardinal" ', text, re.M)
    assert re.search(r"^  fixed_lateral = 0 +\(kind = \"tension_cycle\"\)", blocks["load"], re.M)
    assert "minutes" not in text  # the main job's time is the README's to state


def test_a_case_that_fails_while_built_leaves_the_folder_as_it_was(
    tmp_path, seven, capsys, monkeypatch
):
    """A run writes into its folder only once its strand is built: a case refused while it is
    built (here the finite-element problem's own refusal) creates no folder and keeps an earlier
    run's files even under --overwrite, so the corrected run goes into the same folder."""
    import strand.app.build

    def refused(*args, **kwargs):
        raise CaseError("refused while built")

    monkeypatch.setattr(strand.app.build, "StrandProblem", refused)
    new, old = tmp_path / "new", earlier_run(tmp_path / "old")
    before = contents(old)
    assert main(["run", str(seven), "--out", str(new)]) == 2
    assert one_line_error(capsys) == "strand: error: refused while built"
    assert not new.exists()
    assert main(["run", str(seven), "--out", str(old), "--overwrite"]) == 2
    assert contents(old) == before
    monkeypatch.undo()
    capsys.readouterr()
    assert main(["run", str(seven), "--out", str(new), "--set", "load.cycle=[1.0]"]) == 0
    assert (new / "case.toml").is_file() and (new / "steps.csv").is_file()


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_results_folder_is_named(tmp_path, seven, capsys):
    out = tmp_path / "ro"
    out.mkdir()
    out.chmod(0o500)
    try:
        assert main(["run", str(seven), "--out", str(out)]) == 2
    finally:
        out.chmod(0o700)
    assert "is not writable" in one_line_error(capsys)


def test_set_overrides_the_case_file(seven):
    case = load_case(seven, ["mesh.length=0.25", "contact.friction=false", 'cable="cardinal"'])
    assert case.mesh.length == 0.25 and not case.contact.friction
    assert case.cable.name.startswith("Cardinal") and case.load.tension == 10e3
    assert load_case(None, ["load.lateral=1e3"]).load.lateral == 1e3
    with pytest.raises(CaseError, match="expected a number"):
        load_case(seven, ["mesh.length=short"])  # not TOML: read as a string, then refused


def test_set_reaches_into_the_cable(seven):
    """``--set cable.core.<key>``, ``cable.layer.<n>.<key>`` (or ``cable.layer[n].<key>``) and
    ``cable.name`` edit the case's cable, a table, a file or a built-in one, and nothing else."""
    plain = load_case(seven)
    case = load_case(
        seven,
        [
            "cable.core.nu=0.28",
            "cable.layer.1.E=200e9",
            "cable.layer[1].friction=0.4",
            'cable.name="stiffer"',
        ],
    )
    core, layer = case.cable.layers
    assert (core.wire.nu, layer.wire.E, layer.friction, case.cable.name) == (
        0.28,
        200e9,
        0.4,
        "stiffer",
    )
    assert (core.wire.E, layer.wire.nu, layer.lay_angle) == (
        plain.cable.layers[0].wire.E,
        0.3,
        plain.cable.layers[1].lay_angle,
    )
    assert case.mesh == plain.mesh and case.load == plain.load
    cardinal = load_case(None, ["cable.layer.4.E=60e9"])  # the built-in default's cable
    assert [lay.wire.E for lay in cardinal.cable.layers] == [210e9, 180e9, 65e9, 65e9, 60e9]
    assert cardinal.unset_loads == ()  # still Cardinal: its default loads are its own
    with pytest.raises(CaseError, match="give the whole cable .* or edit the case's, not both"):
        load_case(seven, ['cable="cardinal"', "cable.core.nu=0.28"])


def test_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0
    assert capsys.readouterr().out.strip() == f"strand {__version__}"


def test_the_command_line_keeps_one_run_per_folder(tmp_path, capsys):
    """The results-folder rules (tests/test_folder.py) as ``strand run`` applies them: a run into
    a folder holding an earlier run is refused and touches nothing; with --overwrite none of the
    earlier run's fields and figures is left (this run writes no VTX series, output.vtx = false,
    and no figures); a folder of other files is refused even then."""
    case = tmp_path / "seven.toml"
    case.write_text(SEVEN_WIRE)
    out = earlier_run(tmp_path / "out")
    first = contents(out)
    assert main(["run", str(case), "--out", str(out)]) == 2
    assert "holds the results of an earlier run" in one_line_error(capsys)
    assert contents(out) == first
    off = ["--set", "output.vtx=false", "--set", "output.plots=false", "--set", "load.cycle=[1.0]"]
    assert main(["run", str(case), "--out", str(out), "--overwrite", *off]) == 0
    second = {p.name for p in out.iterdir()}
    assert "fields.xdmf" in second and "fields.bp" not in second, second
    assert not any(n.endswith(".png") for n in second), second
    assert tomllib.loads((out / "case.toml").read_text())["output"]["vtx"] is False
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("not a run")
    capsys.readouterr()
    assert main(["run", str(case), "--out", str(tmp_path / "mine"), "--overwrite"]) == 2
    assert "not a strand run's" in one_line_error(capsys)
    assert (tmp_path / "mine" / "notes.txt").read_text() == "not a run"


def test_ctrl_c_stops_at_the_last_converged_step_and_keeps_everything(tmp_path):
    """Ctrl-C during the cycle: the run stops at a converged step, writes its summary (saying it
    was interrupted), keeps every step, exits with 130 and no traceback."""
    case = tmp_path / "seven.toml"
    case.write_text(
        SEVEN_WIRE.replace("lateral = 100.0", "lateral = 5.0").replace(  # many small steps
            "plots = false", "plots = true\nfields = false"
        )
    )
    out = tmp_path / "out"
    run = subprocess.Popen(
        [sys.executable, "-m", "strand.app", "run", str(case), "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
    )
    lines = []
    deadline = time.monotonic() + 120
    for line in run.stdout:
        lines.append(line)
        if "leg 1" in line or time.monotonic() > deadline:
            break
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=120)
    text = "".join(lines) + stdout
    assert run.returncode == 130, text + stderr
    assert "Traceback" not in stderr + text
    assert "interrupted" in text
    summary = (out / "summary.txt").read_text()
    assert summary.startswith("INTERRUPTED:") and "stopped: leg" in summary
    assert f"The steps up to the last converged one are written in {out}." in summary
    assert not list(out.glob("fields*"))  # output.fields = false: no field files
    with open(out / "steps.csv") as f:
        steps = list(csv.DictReader(f))
    assert any(s["stage"] == "leg 1" for s in steps)
    n = int(summary.split()[1])
    assert len(steps) == n  # every step reported was written
    # the figures say the run is incomplete: a line in red (tab:red) at the bottom
    import matplotlib.image

    image = matplotlib.image.imread(out / "load_deflection.png")[..., :3]
    bottom = image[int(0.95 * len(image)) :]
    red = np.all(np.abs(bottom - [0.839, 0.153, 0.157]) < 0.05, axis=-1)
    assert red.sum() > 50
