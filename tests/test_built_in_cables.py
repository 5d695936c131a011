"""The built-in cables are the data files ``strand/cable/data/<name>.toml``: each is found by its
name alone, builds, and is the cable its named function gives; a case file finds every one."""

from __future__ import annotations

import pytest

from strand.cable.description import (
    CableError,
    built_in_cable,
    built_in_cables,
    cardinal,
    judge120,
)


def test_every_data_file_is_a_built_in_cable():
    assert built_in_cables() == ("cardinal", "judge120")
    for name in built_in_cables():
        assert built_in_cable(name).layers


def test_the_named_functions_give_the_files_cables():
    assert built_in_cable("cardinal") == cardinal()
    assert built_in_cable("Judge120") == judge120()


def test_an_unknown_name_lists_the_built_in_cables():
    with pytest.raises(CableError, match="built-in cables: cardinal, judge120"):
        built_in_cable("drake")


def test_a_case_file_finds_every_built_in_cable():
    # a case file names a built-in cable by its data file's name, in any case
    from strand.app.case import case_from_dict

    for name in built_in_cables():
        assert case_from_dict({"cable": name.upper()}).cable == built_in_cable(name)
