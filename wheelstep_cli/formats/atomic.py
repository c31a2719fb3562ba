"""Atomic file output: a part is either fully written or not there at all.

Files are staged as hidden temporary files in the target folder and renamed into place,
so a reader never sees half a file. They get the permissions an ordinary ``open`` would
give them under the user's umask (0644 under the usual 022), not the owner-only mode of
a temporary file.
"""

from __future__ import annotations

import errno
import os
import tempfile
from pathlib import Path
from typing import Mapping


def _file_mode() -> int:
    """Mode a newly created file gets under the process umask (read without changing it for long)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_bytes_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename."""
    write_files_atomic({Path(path): data})


def write_files_atomic(files: Mapping[Path, bytes]) -> list[Path]:
    """Write several files so that either all of them land or none does.

    Every target is checked first (a folder in a file's place is refused before anything
    is written); all contents are staged as temporary files; only then are they renamed
    into place, each file it replaces kept aside until all renames succeeded, so a
    failure half-way puts the folder back as it was. Returns the written paths.
    """
    targets = [Path(p) for p in files]
    for path in targets:
        if path.is_dir():
            raise IsADirectoryError(21, "is a folder, not a file", str(path))
    mode = _file_mode()
    staged: list[tuple[Path, Path]] = []
    made: list[Path] = []
    try:
        for path, data in zip(targets, files.values()):
            _make_folders(path.parent, made)
            staged.append((_staged(path, data, mode, ".part"), path))
        _rename_all(staged)
    except BaseException:
        for tmp, _ in staged:
            _unlink_quietly(tmp)
        for folder in reversed(made):       # all-or-nothing: the folders made for them too
            try:
                folder.rmdir()
            except OSError:
                pass
        raise
    return targets


def _make_folders(folder: Path, made: list[Path]) -> None:
    """Create ``folder`` and its missing parents, outermost first, each added to ``made``
    as it is created (so a failure half-way leaves the list of those to remove)."""
    for missing in [f for f in [folder, *folder.parents] if not f.is_dir()][::-1]:
        if missing.exists():
            raise NotADirectoryError(errno.ENOTDIR, "is a file, not a folder", str(missing))
        missing.mkdir()
        made.append(missing)


def _staged(path: Path, data: bytes | None, mode: int, suffix: str) -> Path:
    """A hidden temporary file beside ``path`` holding ``data`` (None: an empty placeholder)."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    except OSError as err:     # said of the file asked for, not of the hidden temporary one
        raise type(err)(err.errno, err.strerror, str(path)) from None
    os.fchmod(fd, mode)
    with os.fdopen(fd, "wb") as fh:
        if data:
            fh.write(data)
    return Path(tmp)


def _rename_all(staged: list[tuple[Path, Path]]) -> None:
    """Rename every staged file onto its target; on any failure undo the renames done."""
    done: list[tuple[Path, Path | None]] = []
    try:
        for tmp, path in staged:
            backup = None
            if path.exists():
                backup = _staged(path, None, 0o600, ".old")
                os.replace(path, backup)
            done.append((path, backup))
            os.replace(tmp, path)
    except BaseException:
        for path, backup in reversed(done):
            if backup is not None:
                os.replace(backup, path)
            else:
                _unlink_quietly(path)
        raise
    for _, backup in done:
        if backup is not None:
            _unlink_quietly(backup)


def remove_files(paths) -> None:
    """Remove files that were written, ignoring those already gone."""
    for p in paths:
        _unlink_quietly(Path(p))


def _unlink_quietly(path: Path) -> None:
    try:
        path.unlink()
    except FileNotFoundError:
        pass
