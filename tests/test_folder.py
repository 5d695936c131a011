"""The results-folder rules (``strand.app.folder``): a folder never holds two runs' files, an
earlier run's are replaced only when asked, a folder of other files is never written into. The
command line applies them through ``prepare_results_folder`` (end to end: tests/test_cli.py)."""

from __future__ import annotations

import pytest

from strand.app.folder import (
    RUN_MARKER,
    FolderError,
    check_results_folder,
    prepare_results_folder,
)
from strand_cases import contents, earlier_run


def test_a_new_folder_is_created_and_an_empty_one_used(tmp_path):
    assert prepare_results_folder(tmp_path / "a" / "b") == tmp_path / "a" / "b"
    assert (tmp_path / "a" / "b").is_dir()
    (tmp_path / "empty" / "sub").mkdir(parents=True)
    (tmp_path / "empty" / ".hidden").write_text("")
    before = contents(tmp_path / "empty")
    for overwrite in (False, True):  # sub-folders and hidden files are no run's
        assert prepare_results_folder(tmp_path / "empty", overwrite) == tmp_path / "empty"
    assert contents(tmp_path / "empty") == before


def test_a_folder_holding_a_run_is_refused_untouched(tmp_path):
    out = earlier_run(tmp_path / "out")
    before = contents(out)
    with pytest.raises(FolderError, match="holds the results of an earlier run; give another"):
        prepare_results_folder(out)
    assert contents(out) == before


def test_overwrite_removes_the_earlier_runs_files_and_fields_only(tmp_path):
    out = earlier_run(tmp_path / "out")
    assert prepare_results_folder(out, overwrite=True) == out
    assert set(contents(out)) == {"small", f"small/{RUN_MARKER}", ".keep"}


@pytest.mark.parametrize("overwrite", [False, True])
def test_a_folder_of_other_files_is_never_written_into(tmp_path, overwrite):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("not a run")
    (mine / "fields.bp").mkdir()
    before = contents(mine)
    with pytest.raises(FolderError, match="holds files that are not a strand run's"):
        prepare_results_folder(mine, overwrite)
    assert contents(mine) == before and (mine / "notes.txt").read_text() == "not a run"


def test_a_file_is_not_a_results_folder(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text("")
    with pytest.raises(FolderError, match="is a file, not a folder"):
        prepare_results_folder(path)
    with pytest.raises(FolderError, match="cannot create the results folder"):
        prepare_results_folder(path / "sub")


def test_the_check_gives_the_verdict_and_writes_nothing(tmp_path):
    """``check_results_folder`` (what a run asks before it builds its strand) refuses what
    ``prepare_results_folder`` refuses, with the same line, and creates, removes and writes
    nothing, whether it refuses or not."""
    run = earlier_run(tmp_path / "run")
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("not a run")
    (tmp_path / "file").write_text("")
    refused = [
        (run, False),
        (tmp_path / "mine", True),
        (tmp_path / "file", False),
        (tmp_path / "file" / "sub", False),
    ]
    for folder, overwrite in refused:
        before = contents(tmp_path)
        with pytest.raises(FolderError) as checked:
            check_results_folder(folder, overwrite)
        assert contents(tmp_path) == before
        with pytest.raises(FolderError) as prepared:
            prepare_results_folder(folder, overwrite)
        assert str(checked.value).split(" (")[0] == str(prepared.value).split(" (")[0]
    before = contents(tmp_path)
    for folder in (run, tmp_path / "new" / "sub"):
        assert check_results_folder(folder, overwrite=True) == folder
    assert contents(tmp_path) == before and not (tmp_path / "new").exists()
