"""Load spectra: a load history reduced by rainflow to cycle counts per
amplitude (``strand spectrum``, ``strand.fatigue.spectrum.reduce_history``), Miner's sum over a
spectrum, and a ``[fatigue] spectrum`` case whose damage is the sum of its members' runs."""

from __future__ import annotations

import csv
import io
import re
import shlex
import tomllib
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from strand.app.case import CaseError, case_from_dict, load_case
from strand.app.cli import main
from strand.app.fatigue.load_history import history_spectrum, spectrum_block
from strand.app.fatigue.spectrum import spectrum_report, write_spectrum
from strand.app.history import read_history
from strand.app.run import run_sweep
from strand.fatigue.cycles import rainflow_cycles, repeating_cycles
from strand.fatigue.sn import SN_CURVES, miner_damage
from strand.fatigue.spectrum import reduce_history, spectrum_damage
from strand.fatigue.stress import surface_stress
from strand_cases import SEVEN_WIRE, one_line_error

ROOT = Path(__file__).parents[1]


def two_blocks() -> tuple[np.ndarray, np.ndarray]:
    """Time (s) and load: 10 periods of 2 sin(2πt), then 3 of 5 sin(2πt), 20 samples a period
    (every peak and trough sampled exactly)."""
    t1 = np.arange(200) / 20
    t2 = np.arange(61) / 20
    load = np.concatenate([2 * np.sin(2 * np.pi * t1), 5 * np.sin(2 * np.pi * t2)])
    return np.concatenate([t1, 10 + t2]), load


def test_rainflow_reduction_of_two_sine_blocks_counts_by_hand():
    """Turning points 0, (2, −2) × 10, (5, −5) × 3, 0. ASTM E1049 counts, each as a half cycle
    (every range it meets contains the start of what is left): 0 → 2 (amplitude 1, mean 1), the
    19 ranges of block one (amplitude 2, mean 0), −2 → 5 (3.5, mean 1.5), the 5 ranges of block
    two (5, mean 0) and −5 → 0 (2.5, mean −2.5): 13.5 cycles. In 3 classes of width 5/3: 0.5
    cycle at 5/3; 9.5 + 0.5 at 10/3 (mean −0.125); 0.5 + 2.5 at 5 (mean 0.25)."""
    _, load = two_blocks()
    s = reduce_history(load, 3)
    assert s.turning_points == 28 and s.cycles == 13.5
    np.testing.assert_allclose(s.amplitude, [5 / 3, 10 / 3, 5], rtol=1e-14)
    np.testing.assert_array_equal(s.count, [0.5, 10.0, 3.0])
    np.testing.assert_allclose(s.mean, [1.0, -0.125, 0.25], atol=1e-12)
    one = reduce_history(load, 1)
    assert one.amplitude.tolist() == [5.0] and one.count.tolist() == [13.5]
    many = reduce_history(load, 10)  # width 0.5: amplitudes 1, 2, 2.5, 3.5, 5 on their own
    np.testing.assert_allclose(many.amplitude, [1, 2, 2.5, 3.5, 5], rtol=1e-14)
    np.testing.assert_array_equal(many.count, [0.5, 9.5, 0.5, 0.5, 2.5])


def test_a_binned_spectrum_damages_at_least_as_much_as_its_history():
    """Each class runs at its upper edge: Miner's damage of the binned spectrum bounds the
    history's own from above, and tends to it as the classes narrow."""
    rng = np.random.default_rng(29)
    stress = 150e6 * np.cumsum(rng.normal(size=2000)) / 40 + 300e6  # Pa, a random walk
    curve = SN_CURVES["en1992-prestressing-steel"]
    c = rainflow_cycles(stress)
    exact = miner_damage(c.range, c.count, curve)
    binned = []
    for bins in (3, 10, 100):
        s = reduce_history(stress, bins)
        binned.append(miner_damage(2 * s.amplitude, s.count, curve))
    assert exact > 0 and binned[0] > binned[1] > binned[2] >= exact
    assert binned[2] < 1.3 * exact


def test_miner_sum_of_a_spectrum_is_the_hand_sum_of_n_over_N():
    """Ranges of 300, 150 and 100 MPa on EN 1992-1-1's prestressing steel curve (185 MPa at
    10⁶, slope 5 above, 9 below): N = 10⁶ (185/Δσ)^k; D = Σ nᵢ/Nᵢ, shares nᵢ/(Nᵢ D). A layer
    without a curve (NaN) stays NaN."""
    ranges = np.array([300.0, 150.0, 100.0])
    counts = np.array([1e3, 1e5, 1e6])
    N = 1e6 * (185 / ranges) ** np.where(ranges >= 185, 5, 9)
    curve = SN_CURVES["en1992-prestressing-steel"]
    per_cycle = [miner_damage([1e6 * r], [1.0], curve) for r in ranges]
    total, shares = spectrum_damage(counts, per_cycle)
    hand = np.sum(counts / N)
    assert total == pytest.approx(hand, rel=1e-12)
    np.testing.assert_allclose(shares, counts / N / hand, rtol=1e-12)
    both, both_shares = spectrum_damage(counts, np.column_stack([per_cycle, [np.nan] * 3]))
    assert both[0] == pytest.approx(hand, rel=1e-12) and np.isnan(both[1])
    assert np.all(np.isnan(both_shares[:, 1]))


@pytest.mark.parametrize(("delta", "k"), [(50e6, 9), (200e6, 5)])
def test_a_members_damage_is_that_of_a_steady_cycle(delta, k):
    """Why a spectrum's D is the damage of as many steady cycles (docs/fatigue.md): a point's
    stress s₀ → s₀+Δ → s₀ → s₀−Δ → s₀ (the cycle [1, 0, −1, 0] once from the tensioned state),
    counted as the fatigue report counts it (repeating), damages 1/N(2Δ): what each further
    repetition adds to a once-through count. Counted once through it would damage (½ + 2^−k)/
    N(2Δ) (ASTM's ½ cycle of 2Δ and two ½ cycles of Δ): 1.99 times less for k = 9, 1.88 for
    k = 5."""
    curve = SN_CURVES["en1992-prestressing-steel"]  # slope 9 below 185 MPa, 5 above
    once = 300e6 + delta * np.array([0.0, 1.0, 0.0, -1.0, 0.0])

    def damage(history, count=rainflow_cycles):
        c = count(history)
        return miner_damage(c.range, c.count, curve)

    life = curve.life(delta)  # N of the range 2Δ (amplitude Δ)
    assert damage(once, repeating_cycles) == pytest.approx(1 / life, rel=1e-12)
    repeated = [np.concatenate([once, *[once[1:]] * (n - 1)]) for n in (10, 11)]
    steady = damage(repeated[1]) - damage(repeated[0])
    assert steady == pytest.approx(1 / life, rel=1e-9)
    assert damage(once) == pytest.approx((0.5 + 2.0**-k) / life, rel=1e-12)
    assert steady / damage(once) == pytest.approx({9: 1.992, 5: 1.882}[k], abs=1e-3)


@pytest.mark.parametrize(
    ("spectrum", "message"),
    [
        ([[1000.0, -2.0]], r"-2.0 cycles at amplitude 1000.0: expected a positive count"),
        ([[0.0, 10.0]], r"amplitude 0.0: expected a positive amplitude"),
        ([[-5.0, 10.0]], r"amplitude -5.0: expected a positive amplitude"),
        ([[100.0, 1.0], [100.0, 2.0]], r"amplitude 100 is listed twice"),
        ([100.0, 2.0], r"expected \[\[amplitude, cycles\], ...\], pairs of numbers; got 100.0"),
        ([[100.0, "many"]], r"pairs of numbers"),
    ],
)
def test_a_bad_spectrum_is_refused_in_one_line(spectrum, message):
    with pytest.raises(CaseError, match=message) as e:
        case_from_dict({"fatigue": {"spectrum": spectrum}}, source="c.toml")
    assert str(e.value).startswith("c.toml: [fatigue] spectrum") and "\n" not in str(e.value)


def test_the_spectrum_supplies_the_sweep():
    """Its amplitudes become [load] sweep; a sweep of the same amplitudes is accepted, other
    amplitudes, no fatigue outputs or a cycle at zero load are refused in one line."""
    spectrum = [[1000.0, 2e6], [2000.0, 3e5], [4300.0, 1e4]]
    case = case_from_dict({"fatigue": {"spectrum": spectrum}})
    assert case.load.sweep == (1000.0, 2000.0, 4300.0)
    assert case.fatigue.spectrum == ((1000.0, 2e6), (2000.0, 3e5), (4300.0, 1e4))
    same = case_from_dict(
        {"fatigue": {"spectrum": spectrum}, "load": {"sweep": [4300.0, 1000.0, 2000.0]}}
    )
    assert same.load.sweep == (4300.0, 1000.0, 2000.0)
    for data, message in (
        (
            {"load": {"sweep": [1000.0]}},
            r"spectrum amplitudes \[1000.0, 2000.0, 4300.0\] "
            r"differ from \[load\] sweep = \[1000.0\]",
        ),
        ({"fatigue": {"outputs": False}}, r"needs \[fatigue\] outputs = true"),
        ({"load": {"cycle": [0.0]}}, r"needs a cycle with a target other than 0"),
    ):
        data = {**data, "fatigue": {"spectrum": spectrum, **data.get("fatigue", {})}}
        with pytest.raises(CaseError, match=message) as e:
            case_from_dict(data)
        assert "\n" not in str(e.value)


def test_a_spectrum_table_of_its_own_is_the_same_spectrum():
    """[fatigue.spectrum] with classes = [[amplitude, cycles], ...] (a sub-table: it may stand
    beside a case's [fatigue]) gives the case the list form gives; other keys are refused, and
    its classes are checked as the list's."""
    spectrum = [[1000.0, 2e6], [2000.0, 3e5]]
    table = tomllib.loads(
        "[fatigue]\nend_zone = 0.05\n[output]\nplots = false\n"
        "[fatigue.spectrum]\nclasses = [[1000.0, 2e6], [2000.0, 3e5]]\n"
    )
    listed = {"fatigue": {"end_zone": 0.05, "spectrum": spectrum}, "output": {"plots": False}}
    assert case_from_dict(table) == case_from_dict(listed)
    for value, message in (
        (
            {"classes": spectrum, "period": 1.0},
            r"expected the one key classes = .* got \['classes'",
        ),
        ({"cycles": spectrum}, r"\[fatigue.spectrum\]: expected the one key classes"),
        ({"classes": [[1000.0, -2.0]]}, r"\[fatigue\] spectrum: -2.0 cycles at amplitude 1000.0"),
    ):
        with pytest.raises(CaseError, match=message) as e:
            case_from_dict({"fatigue": {"spectrum": value}}, source="c.toml")
        assert str(e.value).startswith("c.toml: [fatigue") and "\n" not in str(e.value)


def test_a_spectrum_case_reads_back_from_its_case_toml(tmp_path):
    """The case.toml a run writes holds the spectrum and the sweep it supplies, and reads back
    to the same case (floats bitwise)."""
    from strand.app.case_toml import case_toml

    case = case_from_dict(
        {"fatigue": {"spectrum": [[0.1, 3.0e6], [0.3, 1.5]]}, "load": {"kind": "bending"}},
        source="test",
    )
    path = tmp_path / "case.toml"
    path.write_text(case_toml(case, "results/x"))
    again = load_case(path)
    assert again.fatigue == case.fatigue and again.load == case.load
    assert again.load.sweep == (0.1, 0.3)


def test_the_spectrum_case_file_reads_as_its_comments_say():
    case = load_case(ROOT / "cases" / "quick_1x6_spectrum.toml")
    assert case.fatigue.spectrum == ((100.0, 2e6), (200.0, 3e5), (300.0, 1e4))
    assert case.load.sweep == (100.0, 200.0, 300.0) and case.unset_loads == ()
    assert (case.mesh.length, case.fatigue.end_zone, case.load.kind) == (0.2, 0.05, "saddle")


def _history(tmp_path: Path, tension=None) -> Path:
    t, load = two_blocks()
    tension = 10e3 + 100 * load if tension is None else tension
    path = tmp_path / "history.csv"
    rows = [
        f"{a!r},{b!r},{c!r}"
        for a, b, c in zip(t.tolist(), load.tolist(), tension.tolist(), strict=True)
    ]
    path.write_text("# a global analysis' output\ntime_s,lateral_N,tension_N\n" + "\n".join(rows))
    return path


def test_strand_spectrum_prints_the_block_a_case_file_takes(tmp_path, capsys):
    """The printed lines are TOML; their spectrum, in a case, is the hand-made one (amplitudes
    rounded up to six digits), the same case as a hand-made spectrum gives, so the same run.
    The tension's mean is given for [load] tension, and --output writes the same lines."""
    path = _history(tmp_path)
    out = tmp_path / "spectrum.toml"
    args = [
        "spectrum",
        str(path),
        "--column",
        "lateral_N",
        "--time-column",
        "time_s",
        "--tension-column",
        "tension_N",
        "--output",
        str(out),
    ]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert out.read_text() == text
    assert "13.5 cycles in 13" in text and "28 turning points" in text
    assert "set [load] tension = 10000 in N" in text and "WARNING" not in text
    table = tomllib.loads(text)
    assert table["fatigue"]["spectrum"]["classes"] == [[1.66667, 0.5], [3.33334, 10], [5, 3]]
    from_history = case_from_dict(table)
    by_hand = case_from_dict(
        {"fatigue": {"spectrum": [[1.66667, 0.5], [3.33334, 10.0], [5.0, 3.0]]}}
    )
    assert from_history == by_hand
    assert main([*args[:4], "--scale", "2", "--bins", "1"]) == 0
    assert tomllib.loads(capsys.readouterr().out)["fatigue"]["spectrum"]["classes"] == [[5, 27]]


def _block(tmp_path: Path, capsys, *args: str) -> str:
    """What ``strand spectrum`` prints for the two-block history (``_history``) with ``args``."""
    assert main(["spectrum", str(_history(tmp_path)), "--column", "lateral_N", *args]) == 0
    return capsys.readouterr().out


def _classes(text: str) -> list[list[float]]:
    return tomllib.loads(text)["fatigue"]["spectrum"]["classes"]


@pytest.mark.parametrize(
    ("period", "seconds"),
    [("1y", 365.25 * 86400), ("30d", 30 * 86400), ("3h", 10800), ("13", 13), ("2.5min", 150)],
)
def test_period_scales_the_counts_from_the_records_duration(tmp_path, capsys, period, seconds):
    """The record lasts 13 s (its time column, time_s): --period P multiplies the hand counts
    0.5, 10, 3 by P / 13 s; a year is 365.25 d; --period 13 leaves them as counted."""
    text = _block(tmp_path, capsys, "--time-column", "time_s", "--period", period)
    scale = seconds / 13
    counts = [c for _, c in _classes(text)]
    np.testing.assert_allclose(counts, [0.5 * scale, 10 * scale, 3 * scale], rtol=1e-9)
    assert "13.5 cycles in 13 s" in text
    if period != "13":
        assert f"counts × {scale:.6g}: the record's 13 s scaled to the period {seconds:g} s" in text


def test_period_reads_the_time_columns_unit(tmp_path):
    """A time column in hours (its units line) lasts 3600 times as many seconds; one without a
    unit is taken in s and the block says so."""
    rows = "\n".join(f"{t},{x}" for t, x in zip([0, 0.5, 1, 1.5, 2], [0, 1, -1, 1, 0], strict=True))
    hours = tmp_path / "hours.csv"
    hours.write_text(f"time,x\n(h),(N)\n{rows}\n")
    h = history_spectrum(hours, "x", 1, time_column="time", period=86400.0)
    assert h.duration == 7200 and h.scale == pytest.approx(12, rel=1e-12)
    assert h.spectrum.count.tolist() == [2.0] and "(the time column has no unit" not in (
        spectrum_block(h)
    )
    bare = tmp_path / "bare.csv"
    bare.write_text(f"t,x\n{rows}\n")
    h = history_spectrum(bare, "x", 1, time_column="t", period=86400.0)
    assert h.duration == 2 and h.scale == 43200
    assert "in 2 s (the time column has no unit: taken in s)" in spectrum_block(h)


def test_a_force_column_in_kn_is_read_in_newtons_and_says_so(tmp_path, capsys):
    """The two-block history with its lateral load and tension in kN: the amplitudes and the
    tension's mean are those of the same history in N, 1000 times the numbers in the file,
    each conversion said in one line; a column in te is refused."""
    t, load = two_blocks()
    path = tmp_path / "kn.csv"
    rows = [
        f"{a!r},{b / 1e3!r},{10 + b / 10:.12g}"
        for a, b in zip(t.tolist(), load.tolist(), strict=True)
    ]
    path.write_text("time_s,lateral_kN,tension_kN\n" + "\n".join(rows) + "\n")
    assert (
        main(["spectrum", str(path), "--column", "lateral_kN", "--tension-column", "tension_kN"])
        == 0
    )
    text = capsys.readouterr().out
    np.testing.assert_allclose(
        np.array(_classes(text)), [[1.66667, 0.5], [3.33334, 10], [5, 3]], rtol=1e-6
    )
    assert "# column 'lateral_kN' is in kN: read × 1000, in N\n" in text
    assert "# column 'tension_kN' is in kN: read × 1000, in N\n" in text
    assert "set [load] tension = 10000 in N" in text
    moordyn = tmp_path / "line.out"
    moordyn.write_text("Time Ten\n(s) (te)\n0 100\n1 140\n2 60\n")
    assert main(["spectrum", str(moordyn), "--column", "Ten"]) == 2
    line = one_line_error(capsys)
    assert "column 'Ten' is in te, outside SI: give it in N" in line


def test_the_printed_block_pasted_into_a_case_with_a_fatigue_table_is_read(tmp_path, capsys):
    """The block goes at the end of a case file that has its own [fatigue] table (the mooring
    case, where it is the last table; a 1+6 case where [output] follows it): the case reads,
    its [fatigue] settings kept and its spectrum the block's."""
    text = _block(tmp_path, capsys, "--time-column", "time_s")
    mooring = (ROOT / "cases" / "mooring_judge120.toml").read_text()
    seven = SEVEN_WIRE.replace("[output]", "[fatigue]\nend_zone = 0.02\n\n[output]")
    expected = ((1.66667, 0.5), (3.33334, 10.0), (5.0, 3.0))
    for name, before in (("mooring", mooring), ("seven", seven)):
        path = tmp_path / f"{name}.toml"
        path.write_text(before + "\n" + text)
        case = load_case(path.with_name(f"{name}.toml"))
        assert case.fatigue.spectrum == expected and case.load.sweep == (1.66667, 3.33334, 5.0)
    assert case.fatigue.end_zone == 0.02
    assert load_case(tmp_path / "mooring.toml").fatigue.breaking_strength == 3.606e6


def test_the_docs_example_prints_what_the_docs_show(tmp_path, capsys, monkeypatch):
    """docs/fatigue.md's load history example, run as written (its Python writes the history,
    its command counts it for a year): it prints the block the page shows, line for line, and
    writes the same to its --output."""
    page = (ROOT / "docs" / "fatigue.md").read_text()
    script, command = re.search(
        r'```bash\n\.venv/bin/python -c "\n(.*?)"\n\.venv/bin/strand (spectrum .*?)\n```',
        page,
        re.S,
    ).groups()
    shown = re.search(r"```toml\n(# rainflow .*?)```", page, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    exec(script, {})
    args = shlex.split(command.replace("\\\n", " "))
    assert "--period" in args and main(args) == 0
    assert capsys.readouterr().out == shown
    assert (tmp_path / "spectrum.toml").read_text() == shown


def test_a_tension_that_varies_more_than_its_mean_is_flagged(tmp_path, capsys):
    _, load = two_blocks()
    path = _history(tmp_path, tension=1e3 + 300 * load)  # 1 kN ± 1.5 kN
    h = history_spectrum(path, "lateral_N", tension_column="tension_N")
    assert h.tension is not None and h.tension.mean() == pytest.approx(1e3, rel=1e-3)
    assert (
        main(["spectrum", str(path), "--column", "lateral_N", "--tension-column", "tension_N"]) == 0
    )
    flagged = [line for line in capsys.readouterr().out.splitlines() if "WARNING" in line]
    assert len(flagged) == 1 and "varies by 3000, more than its mean" in flagged[0]


@pytest.mark.parametrize(
    ("content", "args", "message"),
    [
        (None, ["--column", "x"], r"missing.csv: no such file"),
        ("t,x\n0,1\n1,2\n", ["--column", "y"], r"no column 'y'; its columns: \['t', 'x'\]"),
        ("t,x\n0,1\n1,abc\n", ["--column", "x"], r"line 3: column 'x' holds 'abc', not a finite"),
        ("t,x\n0,1\n1,\n", ["--column", "x"], r"line 3: column 'x' holds '', not a finite"),
        ("t,x\n0,1\n1,1\n2,1\n", ["--column", "x"], r"1 turning point\(s\) in 3 value\(s\)"),
        ("t,x\n0,1\n", ["--column", "x"], r"1 turning point\(s\) in 1 value\(s\)"),
        ("", ["--column", "x"], r"empty; expected a header line"),
        ("t,x\n0,1\n1,2\n1,0\n", ["--column", "x", "--time-column", "t"], r"does not increase"),
        ("t,x\n0,1\n1,2\n", ["--column", "x", "--bins", "0"], r"--bins 0: expected a positive"),
        ("t,x\n0,1\n1,2\n", ["--column", "x", "--scale", "-1"], r"scale -1.0: expected a posi"),
        (
            "t,x\n0,1\n1,2\n",
            ["--column", "x", "--time-column", "t", "--period", "1y", "--scale", "2"],
            r"--period and --scale: give one",
        ),
        ("t,x\n0,1\n1,2\n", ["--column", "x", "--period", "1y"], r"--period needs --time-column"),
        (
            "t,x\n0,1\n1,2\n",
            ["--column", "x", "--time-column", "t", "--period", "1w"],
            r"--period 1w: expected a positive number of seconds, or a number with s, min, h, d, y",
        ),
        (
            "t,x\n0,1\n1,2\n",
            ["--column", "x", "--time-column", "t", "--period", "0d"],
            "--period 0d: expected a positive",
        ),
        (
            "t,x\n(-),(N)\n0,1\n1,2\n",
            ["--column", "x", "--time-column", "t"],
            r"time column 't' is in '-': expected a time in s, min, h, d, y",
        ),
        ("t,x_lbf\n0,1\n1,2\n", ["--column", "x_lbf"], r"'x_lbf' is in lbf, outside SI"),
    ],
)
def test_bad_history_input_gets_one_line(tmp_path, capsys, content, args, message):
    """One line, exit code 2, and nothing written: not even the --output file."""
    path = tmp_path / ("missing.csv" if content is None else "h.csv")
    if content is not None:
        path.write_text(content)
    output = tmp_path / "spectrum.toml"
    assert main(["spectrum", str(path), *args, "--output", str(output)]) == 2
    line = one_line_error(capsys)
    assert line.startswith("strand: error: ") and re.search(message, line), line
    assert not output.exists()


def test_a_history_in_moordyn_layout_is_read(tmp_path):
    """Blanks between the values and a units line in parentheses under the header."""
    path = tmp_path / "line1.out"
    path.write_text("Time FairTen1\n(s) (N)\n0.0 100.0\n0.5 140.0\n1.0 60.0\n1.5 100.0\n")
    s = history_spectrum(path, "FairTen1", bins=2, time_column="Time").spectrum
    # turning points 100, 140, 60, 100: half cycles of amplitude 20, 40, 20
    np.testing.assert_array_equal(s.amplitude, [20.0, 40.0])
    np.testing.assert_array_equal(s.count, [1.0, 0.5])


# --- the spectrum of a run --------------------------------------------------------------------


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path) as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def spectrum_run(tmp_path_factory):
    """The 1+6 (0.1 m, clamp zones of 20 mm) at 10 kN with the saddle cycle 0 → A → 0 → −A → 0
    at A = 150 and 300 N, 10⁶ and 10⁴ cycles."""
    folder = tmp_path_factory.mktemp("spectrum")
    path = folder / "seven.toml"
    path.write_text(SEVEN_WIRE)
    case = load_case(
        path,
        [
            "fatigue.spectrum=[[150.0, 1e6], [300.0, 1e4]]",
            "load.cycle=[1.0, 0.0, -1.0, 0.0]",
            "fatigue.end_zone=0.02",
            "output.fields=false",
        ],
    )
    results = run_sweep(case, folder / "sweep", stream=io.StringIO())
    return case, folder / "sweep", results


def test_the_spectrum_damage_is_the_sum_of_its_members_runs(spectrum_run):
    """spectrum.csv: per wire and zone, D is the largest over its elements of Σ nᵢ dᵢ, dᵢ read
    back from each member's wire_stresses.csv, at the element it names, the shares summing to 1;
    spectrum_crossings.csv: per pair Σ nᵢ dᵢ of the members' crossings.csv."""
    _, folder, _ = spectrum_run
    counts = {"lateral_150": 1e6, "lateral_300": 1e4}
    members = {name: _rows(folder / name / "wire_stresses.csv") for name in counts}
    total = sum(n * np.array([float(r["damage"]) for r in members[m]]) for m, n in counts.items())
    first = members["lateral_150"]
    rows = _rows(folder / "spectrum.csv")
    assert len(rows) == 14  # 7 wires, free span and clamp zone
    for row in rows:
        mine = [
            k for k, r in enumerate(first) if r["wire"] == row["wire"] and r["zone"] == row["zone"]
        ]
        assert float(row["damage"]) == pytest.approx(total[mine].max(), rel=2e-5)
        k = int(row["element"])
        assert k in mine and total[k] == pytest.approx(float(row["damage"]), rel=2e-5)
        shares = [float(row[f"share_{m}"]) for m in counts]
        assert sum(shares) == pytest.approx(1, abs=2e-6)
        d = float(members["lateral_300"][k]["damage"])
        assert shares[1] == pytest.approx(1e4 * d / total[k], rel=1e-4)
    pairs = {m: _rows(folder / m / "crossings.csv") for m in counts}
    by_pair = sum(n * np.array([float(r["damage"]) for r in pairs[m]]) for m, n in counts.items())
    got = np.array([float(r["damage"]) for r in _rows(folder / "spectrum_crossings.csv")])
    np.testing.assert_allclose(got, by_pair, rtol=2e-5)


def test_the_spectrum_is_as_many_steady_cycles_of_each_members_history(spectrum_run):
    """At the element of largest D in spectrum.csv, D = Σ nᵢ dᵢ with dᵢ what a third repetition
    adds to a once-through count of member i's own surface-stress histories repeated twice
    (wire_sections.h5, σ = N/A + (r/I)(M₁ sin ψ − M₂ cos ψ) at the report's surface points, the
    worst point per member as the report takes it): the damage of nᵢ steady cycles, no ½."""
    case, folder, _ = spectrum_run
    rows = [r for r in _rows(folder / "spectrum.csv") if r["damage"] != "nan"]
    worst = max(rows, key=lambda r: float(r["damage"]))
    e, curve = int(worst["element"]), case.fatigue.curves(case.cable)[int(worst["layer"])]
    psi = 2 * np.pi * np.arange(case.fatigue.surface_points) / case.fatigue.surface_points

    def damage(series):
        c = rainflow_cycles(series)
        return miner_damage(c.range, c.count, curve)

    total = 0.0
    for amplitude, n in case.fatigue.spectrum:
        h = read_history(folder / f"lateral_{amplitude:g}" / "wire_sections.h5")
        sigma = surface_stress(
            h["axial"][:, e, None],
            h["m1"][:, e, None],
            h["m2"][:, e, None],
            h.static["diameter"][e],
            psi,
        )
        total += n * max(damage(np.tile(s, 3)) - damage(np.tile(s, 2)) for s in sigma.T)
    assert total > 0 and float(worst["damage"]) == pytest.approx(total, rel=1e-4)


def test_the_spectrum_text_gives_each_layer_and_the_tension_check(spectrum_run):
    """spectrum.txt: every amplitude with its count, each layer's worst wire per zone, the worst
    pairs, and the T–N sum Σ nᵢ D_T,i of the members' own DNV damage beside the wires'."""
    case, folder, results = spectrum_run
    text = (folder / "spectrum.txt").read_text()
    for line in (r"\n +150 +1e\+06 +lateral_150\n", r"\n +300 +1e\+04 +lateral_300\n"):
        assert re.search(line, text), line
    assert text.count("layer 0: wire 0, D = ") == 2 and text.count("layer 1: wire ") == 2
    assert "five worst contact pairs" in text and "not checked ([fatigue] breaking_strength" in text
    dnv = sum(
        n * r.fatigue.tension_check.dnv
        for (_, n), r in zip(case.fatigue.spectrum, results[1:], strict=True)
    )
    assert f"DNV-OS-E301 spiral rope: D = {dnv:.3g}" in text


def test_the_spectrum_figure_shows_the_runs_classes_at_its_worst_wire(spectrum_run):
    """spectrum.png's data (``spectrum_figure_data``) of the run: its two classes and counts,
    the worst place spectrum.csv names first, its classes' damages summing to its D, each its
    member's range there (wire_stresses.csv), and DNV-OS-E301's per class summing to the
    spectrum's."""
    from strand.app.fatigue.spectrum_figure import spectrum_figure_data

    case, folder, results = spectrum_run
    report = spectrum_report(case, results[1:], "lateral", "N")
    data = spectrum_figure_data(report, [r.fatigue for r in results[1:]])
    assert data.amplitudes.tolist() == [150.0, 300.0] and data.counts.tolist() == [1e6, 1e4]
    worst = max(
        (r for r in _rows(folder / "spectrum.csv") if r["damage"] != "nan"),
        key=lambda r: float(r["damage"]),
    )
    place = data.places[0]
    assert (place.element, place.wire) == (int(worst["element"]), int(worst["wire"]))
    assert place.damage.sum() == pytest.approx(float(worst["damage"]), rel=2e-5)
    for amplitude, delta in zip((150, 300), place.range, strict=True):
        row = _rows(folder / f"lateral_{amplitude}" / "wire_stresses.csv")[place.element]
        assert 1e-6 * delta == pytest.approx(float(row["range_MPa"]), rel=1e-5)
    assert data.dnv.sum() == pytest.approx(report.tension.dnv, rel=1e-12) and data.api is None


def _fake_member(damage: float, curve: str | None):
    """A member's fatigue report as the spectrum reads it: one wire of two elements (free, clamp)
    and one pair, ``damage`` per cycle (NaN: no curve)."""
    d = np.nan if curve is None else damage
    report = SimpleNamespace(
        elements=SimpleNamespace(
            wire=np.array([0, 0]),
            layer=np.array([0, 0]),
            z=np.array([0.5, 0.0]),
            clamp=np.array([False, True]),
            damage=np.array([d, 2 * d]),
        ),
        crossings=SimpleNamespace(
            interface=np.array([0]),
            wire_a=np.array([0]),
            wire_b=np.array([1]),
            z=np.array([0.5]),
            clamp=np.array([False]),
            line=np.array([True]),
            damage=np.array([d]),
        ),
        wires=SimpleNamespace(curve=np.array([curve or "not assessed"])),
        end_zone=0.1,
        length=1.0,
        tension_check=SimpleNamespace(dnv=1e-9, api=None, range=5.0, mean=1e4, cycle=False),
    )
    return SimpleNamespace(fatigue=report, failure="", interrupted=False)


def test_a_layer_without_a_curve_is_not_assessed_and_a_failed_member_gives_no_spectrum(tmp_path):
    case = case_from_dict({"fatigue": {"spectrum": [[1.0, 10.0], [2.0, 5.0]]}})
    r = spectrum_report(case, [_fake_member(1e-6, None), _fake_member(1e-5, None)], "lateral", "N")
    assert np.all(np.isnan(r.wires.damage)) and np.isnan(r.crossings.damage[0])
    assert "layer 0: not assessed" in r.text and r.tension.dnv == pytest.approx(15e-9)
    ok = spectrum_report(case, [_fake_member(1e-6, "x"), _fake_member(1e-5, "x")], "lateral", "N")
    assert ok.wires.damage.tolist() == pytest.approx([10e-6 + 5e-5, 20e-6 + 10e-5])
    failed = _fake_member(1e-5, "x")
    failed.failure = "step 3 did not converge"
    text = write_spectrum(tmp_path, case, [_fake_member(1e-6, "x"), failed], "lateral", "N")
    assert text.count("\n") == 1 and "the member lateral_2 failed (step 3" in text
    assert sorted(p.name for p in tmp_path.iterdir()) == ["spectrum.txt"]
