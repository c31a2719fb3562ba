"""Owned output folders: a record is a claim, checked by SHA-256 before a file is replaced
or removed; a file the command did not write is refused unless forced."""

from __future__ import annotations

import hashlib

import pytest

from wheelstep_cli.errors import DesignError
from wheelstep_cli.formats.owned import check_collisions, kept_files, read_record, record_bytes, stale_files


def sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def test_record_round_trip_lists_relative_names_with_their_sha256(tmp_path):
    files = {tmp_path / "a.stl": b"a", tmp_path / "sub" / "b.json": b"b"}
    (tmp_path / ".rec.json").write_bytes(record_bytes("wheelstep test", tmp_path, files))
    assert read_record(tmp_path / ".rec.json") == {"a.stl": sha(b"a"), "sub/b.json": sha(b"b")}


@pytest.mark.parametrize("text", ['{"files": {"../x": "0", "/etc/passwd": "0", "": "0", "ok": 3}}',
                                  "not json", '["files"]', '{"files": ["a"]}'])
def test_a_record_never_names_a_file_outside_the_folder_and_bad_ones_are_empty(tmp_path, text):
    (tmp_path / "rec.json").write_text(text)
    assert read_record(tmp_path / "rec.json") == {}


def test_only_unchanged_files_of_the_previous_run_are_stale(tmp_path):
    (tmp_path / "old.3mf").write_bytes(b"old")
    (tmp_path / "edited.3mf").write_bytes(b"edited by the user")
    record = {"old.3mf": sha(b"old"), "edited.3mf": sha(b"as written"), "gone.stl": sha(b"x"),
              "kept.stl": sha(b"k")}
    assert stale_files(tmp_path, {tmp_path / "kept.stl": b"k2"}, record) == [tmp_path / "old.3mf"]
    # the changed one is kept, and named as kept (a gone file or one written again is neither)
    assert kept_files(tmp_path, {tmp_path / "kept.stl": b"k2"}, record) == [tmp_path / "edited.3mf"]


def test_a_file_not_in_the_record_or_changed_is_refused_unless_forced(tmp_path):
    (tmp_path / "mine.stl").write_bytes(b"mine")
    (tmp_path / "ours.stl").write_bytes(b"ours")
    files = {tmp_path / "mine.stl": b"new", tmp_path / "ours.stl": b"new"}
    with pytest.raises(DesignError, match="not written by this command"):
        check_collisions(tmp_path, files, {"ours.stl": sha(b"ours")}, force=False)
    with pytest.raises(DesignError, match="changed since"):
        check_collisions(tmp_path, files, {"ours.stl": sha(b"before"), "mine.stl": sha(b"mine")}, force=False)
    check_collisions(tmp_path, files, {"ours.stl": sha(b"ours"), "mine.stl": sha(b"mine")}, force=False)
    check_collisions(tmp_path, files, {}, force=True)
    check_collisions(tmp_path, {tmp_path / "mine.stl": b"x"}, {}, force=False, own=("mine.stl",))
