"""Run folders that reproduce themselves (``case.toml``, ``README.txt``) and the input a run
refuses before computing: unknown cables, Cardinal's loads on a cable of one's own, no case."""

from __future__ import annotations

import csv
import re
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from strand import __version__
from strand.analytical.fibre import fibre_model
from strand.app.case import case_from_dict, load_case
from strand.app.case_toml import case_toml
from strand.app.cli import main
from strand.cable.description import judge120
from strand_cases import SEVEN_WIRE, one_line_error

ROOT = Path(__file__).resolve().parents[1]

QUICK = SEVEN_WIRE.replace("plots = false", "plots = false\nfields = false")
#: the 1+6 of SEVEN_WIRE with a yield stress on its core below the core's stress at 10 kN
#: (189 MPa by the model, 198 MPa by the fibre model)
YIELDING = QUICK.replace("friction = 0.3\n", "friction = 0.3\nyield_stress = 150e6\n", 1)


def same_case(a, b) -> bool:
    """Equal cases whatever their source (file name) and their record of defaulted loads."""
    return replace(a, source="", unset_loads=()) == replace(b, source="", unset_loads=())


@pytest.mark.parametrize(
    "data",
    [
        {},  # the default case: Cardinal, saddle
        tomllib.loads(YIELDING),
        tomllib.loads(
            QUICK.replace(
                'lay = "S"\n', 'lay = "S"\nshear_coefficient = 0.7\ntorsional_stiffness = 1.5\n'
            )
        ),
        {
            "load": {"kind": "bending", "sweep": [0.1, 0.2]},
            "contact": {"friction": False},
            "fatigue": {"sn_curve": "custom", "sn_A": 400.0, "sn_layers": [2, 3]},
            "steps": {"stall": False, "balance": 0.0},
            "mesh": {"length": 0.5, "h_max": 3e-3},
        },
    ],
)
def test_case_toml_reads_back_to_the_same_case(tmp_path, data):
    """Every section, the cable inline and the version, as TOML that reads back to an equal
    ``Case`` (floats bitwise: ``==`` on every setting)."""
    case = case_from_dict(data, source="test")
    text = case_toml(case, "results/x")
    assert text.startswith(f"# strand {__version__}")
    table = tomllib.loads(text)
    assert set(table) == {"cable", "mesh", "contact", "load", "steps", "output", "fatigue"}
    path = tmp_path / "case.toml"
    path.write_text(text)
    again = load_case(path)
    assert same_case(again, replace(case, output=replace(case.output, folder="results/x")))
    assert again.unset_loads == ()  # every load is written out


def steps(folder: Path) -> tuple[list[str], np.ndarray]:
    """steps.csv without its stage names and wall times."""
    with open(folder / "steps.csv") as f:
        rows = list(csv.reader(f))
    keep = [i for i, n in enumerate(rows[0]) if n not in ("stage", "seconds")]
    return [rows[0][i] for i in keep], np.array([[float(r[i]) for i in keep] for r in rows[1:]])


def test_a_run_folder_reproduces_its_run(tmp_path, capsys):
    """``strand run <folder>/case.toml`` repeats the run: the same steps.csv (wall times aside),
    bitwise; the folder's README.txt names every file in it. The core's yield stress (given with
    the cable, 150 MPa) is passed at 10 kN: the mean wire stresses are printed after tension (the
    fibre model's within 10 %) and the warning is printed and kept in the summary."""
    case = tmp_path / "seven.toml"
    case.write_text(YIELDING)
    first, second = tmp_path / "first", tmp_path / "second"
    assert main(["run", str(case), "--out", str(first)]) == 0
    out = capsys.readouterr().out
    line = next(s for s in out.splitlines() if s.startswith("mean wire stress"))
    stress = [float(part.split()[-1]) for part in line.split(":")[1].split(",")]
    cable = load_case(case).cable
    force = np.asarray(fibre_model(cable, 10e3)["wire_force"])
    ref = force / [lay.wire.area for lay in cable.layers] / 1e6
    np.testing.assert_allclose(stress, ref, rtol=0.1)
    assert "strand: warning: core: a wire's axial stress reaches" in out
    assert "above its yield stress 150 MPa" in (first / "summary.txt").read_text()

    assert main(["run", str(first / "case.toml"), "--out", str(second)]) == 0
    head, a = steps(first)
    head_b, b = steps(second)
    assert head == head_b and len(a) > 3
    np.testing.assert_array_equal(a, b)
    readme = (first / "README.txt").read_text()
    assert "docs/outputs.md" in readme
    listed = {line.split()[0] for line in readme.splitlines()[3:]}
    assert listed == {p.name for p in first.iterdir()}


def test_an_unknown_cable_name_lists_the_built_in_ones(tmp_path, capsys):
    path = tmp_path / "drake.toml"
    path.write_text('cable = "drake"\n')
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    line = one_line_error(capsys)
    assert "cable = 'drake' is neither a built-in cable nor a file" in line
    assert line.endswith("built-in cables: cardinal, judge120")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("drop", "cycle", "missing"),
    [
        (["tension", "lateral"], "[1.0, 0.0]", "tension, lateral"),
        (["lateral"], "[1.0, 0.0]", "lateral"),
        (["tension", "lateral"], "[0.0]", "tension"),  # no cycle: no amplitude needed
    ],
)
def test_a_cable_of_ones_own_needs_its_loads(tmp_path, capsys, drop, cycle, missing):
    """Cardinal's default loads are refused on another cable, in one line naming the [load]
    settings to give, before anything is written; a built-in cable keeps its defaults."""
    text = QUICK.replace("cycle = [1.0, 0.0]", f"cycle = {cycle}")
    for key in drop:
        text = text.replace(
            {"tension": "tension = 10e3\n", "lateral": "lateral = 300.0\n"}[key], ""
        )
    path = tmp_path / "own.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    line = one_line_error(capsys)
    assert f"give [load] {missing} for the cable '1+6'" in line
    assert "built-in Cardinal's" in line
    assert not (tmp_path / "out").exists()
    assert load_case(path, ['cable="cardinal"']).unset_loads == ()


def test_strand_run_without_a_case_prints_how_to_run_one(tmp_path, capsys, monkeypatch):
    """No case: the usage and the built-in case's name, exit 2, nothing computed or written;
    ``cardinal`` names the built-in case (here refused at once for a bad --set)."""
    monkeypatch.chdir(tmp_path)
    for command in ("run", "compare"):
        assert main([command]) == 2
        err = capsys.readouterr().err
        assert err.startswith("usage: strand") and f"strand {command} cardinal" in err
    assert main(["run", "cardinal", "--set", "mesh.h_max=2.0"]) == 2
    line = one_line_error(capsys)
    assert line.startswith("strand: error: built-in default with --set:") and "h_max" in line
    assert list(tmp_path.iterdir()) == []


def test_the_built_in_name_needs_its_own_loads():
    """``cable = "judge120"`` loads the built-in strand; Cardinal's default loads are not its
    own, so a case that leaves them out is told to give them (Cardinal keeps its defaults)."""
    case = case_from_dict({"cable": "judge120"})
    assert case.cable == judge120()
    assert case.unset_loads == ("tension", "lateral")
    assert case_from_dict({"cable": "cardinal"}).unset_loads == ()


def test_every_setting_is_declared_with_a_valid_default():
    """Every setting of every section and set-up kind is declared (``setting``: unit, sign,
    choices, meaning), its default passes its own declaration (a choice among its choices, a
    number of its sign), and a refused value's line gives its unit: a new setting without a
    declaration fails here."""
    from strand.app.settings import SECTIONS
    from strand.app.settings_schema import entries
    from strand.beam.setting import read_value

    for section in SECTIONS:
        for e in entries(section):
            assert e.meta.doc, (section, e.name)
            value = list(e.default) if isinstance(e.default, tuple) else e.default
            assert read_value(e.name, value, e.default, e.meta) == e.default, (section, e.name)
    line = "[fatigue] clamp_distance = -0.089 m: expected a positive number"
    with pytest.raises(Exception, match=re.escape(line)):
        case_from_dict({"fatigue": {"clamp_distance": -0.089}}, source="c")


@pytest.fixture(scope="module")
def validator():
    """The JSON Schema of a case file as shipped with strand."""
    import json

    import jsonschema

    from strand.app.settings_schema import SCHEMA_FILE

    schema = json.loads(SCHEMA_FILE.read_text())
    jsonschema.Draft7Validator.check_schema(schema)
    return jsonschema.Draft7Validator(schema)


def test_the_shipped_json_schema_is_the_generated_one():
    """``case.schema.json`` is what the declarations give (regenerate it with
    ``python -c "from strand.app.settings_schema import write_schema; write_schema()"``)."""
    from strand.app.settings_schema import SCHEMA_FILE, schema_text

    assert SCHEMA_FILE.read_text() == schema_text()


@pytest.mark.parametrize("path", sorted(ROOT.glob("cases/*.toml")), ids=lambda p: p.name)
def test_every_shipped_case_validates_against_the_schema(validator, path):
    data = tomllib.loads(path.read_text())
    assert [e.message for e in validator.iter_errors(data)] == []


def test_the_template_is_the_default_case_and_validates(validator):
    """``strand run --template`` is valid TOML that passes the schema and reads as the default
    case; a typo in a key, a choice or a sign fails the schema."""
    from strand.app.settings_schema import template

    data = tomllib.loads(template())
    assert [e.message for e in validator.iter_errors(data)] == []
    assert same_case(case_from_dict(data), case_from_dict({}))
    for bad in (
        {"mesh": {"lenght": 1.0}},
        {"meshes": {}},
        {"contact": {"model": "huge"}},
        {"steps": {"balance": -1.0}},
        {"steps": {"cuts": 2.5}},
        {"load": {"direction": [1.0, 0.0]}},
        {"fatigue": {"spectrum": {"class": []}}},
        {"cable": {"core": {"diameter": 1e-3}, "layer": [{"wire": 6}]}},
    ):
        assert not validator.is_valid(bad), bad


def test_a_default_case_imports_neither_the_kinds_nor_dolfinx():
    """The settings import nothing of the set-up kinds (they join in when a case is read), and
    their declarations nothing of dolfinx: a ``Case`` made in code is light."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from strand.app.settings import Case\n"
        "from strand.cable.description import cardinal\n"
        "Case(cardinal())\n"
        "print(sorted(m for m in sys.modules if m == 'dolfinx' or m.startswith('strand.app.k')))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"
