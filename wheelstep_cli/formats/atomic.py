"""Atomic file output: a part is either fully written or not there at all."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Mapping


def write_bytes_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        _unlink_quietly(Path(tmp))
        raise


def write_files_atomic(files: Mapping[Path, bytes]) -> list[Path]:
    """Write several files so that either all of them land or none does.

    All contents are first written to temporary files; only when every one
    succeeded are they renamed into place. Returns the written paths.
    """
    staged: list[tuple[Path, Path]] = []
    try:
        for path, data in files.items():
            path = Path(path)
            path.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
            staged.append((Path(tmp), path))
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
        for tmp, path in staged:
            os.replace(tmp, path)
    except BaseException:
        for tmp, _ in staged:
            _unlink_quietly(tmp)
        raise
    return [path for _, path in staged]


def remove_files(paths) -> None:
    """Remove files that were written, ignoring those already gone."""
    for p in paths:
        _unlink_quietly(Path(p))


def _unlink_quietly(path: Path) -> None:
    try:
        path.unlink()
    except FileNotFoundError:
        pass
