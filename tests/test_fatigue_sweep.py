"""A sweep answers the fatigue question per amplitude (``strand.app.sweep.fatigue_columns``): the
largest surface stress range per layer and zone, the worst crossing's F₂ and slip amplitude, the
largest damage and Poffenberger–Swart's ratio, each column named with its unit."""

from __future__ import annotations

import csv
import io

import numpy as np

from strand.app.case import load_case
from strand.app.run import run_sweep
from strand_cases import SEVEN_WIRE

UNITS = ("_MPa", "_MPa_J_per_m2", "_um")


def test_a_sweep_gives_the_fatigue_figures_per_amplitude(tmp_path):
    """A 1+6 (0.1 m, clamp zones of 20 mm) at lateral amplitudes 150 and 300 N: every fatigue
    column is in sweep.csv and sweep.txt with its unit, the saddle's measure too (the midspan
    deflection, m); sweep.txt gives a line per column, its values side by side; the larger
    amplitude has the larger stress range in every layer and zone, and the larger worst F₂ (of a
    line contact: a 1+6 has no crossings) in the free span."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    case = load_case(
        path, ["load.sweep=[150.0, 300.0]", "fatigue.end_zone=0.02", "output.fields=false"]
    )
    run_sweep(case, tmp_path / "sweep", stream=io.StringIO())
    with open(tmp_path / "sweep" / "sweep.csv") as f:
        rows = list(csv.DictReader(f))
    assert [r["amplitude_N"] for r in rows] == ["150", "300"]
    names = [f"stress_range_{z}_layer_{i}_MPa" for z in ("free", "clamp") for i in (0, 1)]
    names += [
        f"worst_{k}{q}_{z}_{u}"
        for z in ("free", "clamp")
        for k in ("", "line_")
        for q, u in (("f2", "MPa_J_per_m2"), ("slip_amplitude", "um"))
    ]
    names += ["largest_damage_free", "largest_damage_clamp", "ps_ratio"]
    assert set(names) <= set(rows[0])
    assert list(rows[0])[5:7] == ["peak_deflection_m", "unloaded_deflection_m"]
    text = (tmp_path / "sweep" / "sweep.txt").read_text()
    lines = text.splitlines()
    for name, value in rows[1].items():  # a line per column: its name, then each amplitude's
        line = next(x for x in lines if x.split()[:1] == [name])
        assert line.split()[1:] == [rows[0][name], value], line
    assert max(map(len, lines)) < 100, text
    small, large = ({k: float(v) for k, v in r.items() if k in names} for r in rows)
    for name in names[:4]:
        assert 0 < small[name] < large[name], name
    # a 1+6 has no crossings, only the core | layer-1 line: NaN for the crossings' columns
    assert np.isnan(small["worst_f2_free_MPa_J_per_m2"])
    assert 0 < small["worst_line_f2_free_MPa_J_per_m2"] < large["worst_line_f2_free_MPa_J_per_m2"]
    assert small["largest_damage_free"] <= large["largest_damage_free"]
    assert np.isnan(small["ps_ratio"])  # 0.1 m: Poffenberger–Swart's long span does not hold
