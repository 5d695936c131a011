"""A mesh of more than ``strand.app.build.LARGE_MESH`` elements is announced before it is built: one
line with its elements, unknowns and a rough memory estimate (the threshold lowered here so
that the quick 1+6 case passes it)."""

from __future__ import annotations

import io
import re

import pytest

import strand.app.build
from strand.app.build import BYTES_PER_UNKNOWN, build_problem
from strand.app.case import load_case
from strand.cable.geometry import build_geometry
from strand_cases import SEVEN_WIRE


class Built(Exception):
    """Raised in place of building the finite-element problem: nothing is built in this test."""


def announced(tmp_path, monkeypatch, threshold: int | None) -> tuple[str, object]:
    """What ``build_problem`` prints on the quick 1+6 case up to the point where it builds the
    finite-element mesh (with ``LARGE_MESH`` = ``threshold``, or the default), and the case."""
    path = tmp_path / "seven.toml"
    path.write_text(SEVEN_WIRE)
    case = load_case(path)
    if threshold is not None:
        monkeypatch.setattr(strand.app.build, "LARGE_MESH", threshold)

    def no_build(*args, **kwargs):
        raise Built

    monkeypatch.setattr(strand.app.build, "StrandProblem", no_build)
    stream = io.StringIO()
    with pytest.raises(Built):
        build_problem(case, stream)
    return stream.getvalue(), case


def test_a_large_mesh_is_announced_with_its_size_before_it_is_built(tmp_path, monkeypatch):
    text, case = announced(tmp_path, monkeypatch, threshold=10)
    geometry = build_geometry(case.cable, case.mesh.length, case.mesh.h_max)
    elements, unknowns = len(geometry.cells), 6 * len(geometry.points)
    assert elements > 10
    lines = text.splitlines()
    assert len(lines) == 1 and lines[0].startswith("strand: a large mesh:"), text
    numbers = re.match(
        r"strand: a large mesh: ([\d,]+) elements, ([\d,]+) unknowns; .*roughly "
        r"([\d.e+-]+) GB",
        lines[0],
    )
    assert numbers, lines[0]
    assert int(numbers[1].replace(",", "")) == elements
    assert int(numbers[2].replace(",", "")) == unknowns
    assert float(numbers[3]) == pytest.approx(unknowns * BYTES_PER_UNKNOWN / 1e9, rel=0.05)


def test_a_mesh_under_the_threshold_is_not_announced(tmp_path, monkeypatch):
    text, _ = announced(tmp_path, monkeypatch, threshold=None)
    assert text == ""
