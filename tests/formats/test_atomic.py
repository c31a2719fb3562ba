"""Atomic writes: all or nothing, with the permissions the user's umask gives."""

from __future__ import annotations

import os
import stat

import pytest

from wheelstep_cli.formats.atomic import write_bytes_atomic, write_files_atomic


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_written_files_follow_the_umask(tmp_path, umask, mode):
    old = os.umask(umask)
    try:
        write_files_atomic({tmp_path / "a.stl": b"a", tmp_path / "sub" / "b.json": b"{}"})
        write_bytes_atomic(tmp_path / "c.png", b"c")
    finally:
        os.umask(old)
    for name in ("a.stl", "sub/b.json", "c.png"):
        assert stat.S_IMODE((tmp_path / name).stat().st_mode) == mode, name
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == ["a.stl", "b.json", "c.png"]


def test_a_failed_write_leaves_no_file_and_no_temporary(tmp_path):
    (tmp_path / "taken").mkdir()                  # a folder where a file must go: the rename fails
    with pytest.raises(OSError):
        write_files_atomic({tmp_path / "ok.stl": b"x", tmp_path / "taken": b"y"})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken"]


def test_a_rename_failing_half_way_puts_the_folder_back(tmp_path, monkeypatch):
    (tmp_path / "a.stl").write_bytes(b"old a")
    real = os.replace
    calls = []

    def flaky(src, dst):
        calls.append(dst)
        if str(dst).endswith("b.stl"):
            raise PermissionError(13, "denied", str(dst))
        return real(src, dst)

    monkeypatch.setattr(os, "replace", flaky)
    with pytest.raises(PermissionError):
        write_files_atomic({tmp_path / "a.stl": b"new a", tmp_path / "b.stl": b"new b"})
    monkeypatch.setattr(os, "replace", real)
    assert (tmp_path / "a.stl").read_bytes() == b"old a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.stl"]
