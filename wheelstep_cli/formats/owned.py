"""Output folders a command owns: what it wrote is recorded (SHA-256 per file), so a later
run replaces or removes exactly its own files and never a file it did not write.

A record is a claim, not proof: a previous file is removed or overwritten only while its
content still has the recorded SHA-256. A file of the same name that is not in the record,
or was changed since, is the user's: the run is refused (unless forced) before anything is
written. Names in a record are relative paths inside the folder; any other is ignored.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Mapping

from wheelstep_cli.errors import DesignError


def sha256_of(path: Path) -> str | None:
    """SHA-256 (hex) of a file's content; None if it is not a readable file."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


def read_record(path: Path, key: str = "files") -> dict[str, str]:
    """Relative name -> SHA-256 listed under ``key`` of a JSON record file ({} if none or unreadable)."""
    try:
        listed = json.loads(Path(path).read_text(encoding="utf-8")).get(key)
    except (OSError, ValueError, AttributeError, UnicodeDecodeError):
        return {}
    if not isinstance(listed, dict):
        return {}
    return {name: sha for name, sha in listed.items()
            if isinstance(name, str) and isinstance(sha, str) and _inside(name)}


def _inside(name: str) -> bool:
    given = Path(name)
    return bool(name) and not given.is_absolute() and ".." not in given.parts


def record_bytes(tool: str, folder: Path, files: Mapping[Path, bytes]) -> bytes:
    """The record of ``files`` (inside ``folder``) written by ``tool``, as JSON."""
    from wheelstep_cli.formats.jsonio import json_bytes

    return json_bytes({"tool": tool, "files": {
        Path(p).relative_to(folder).as_posix(): hashlib.sha256(data).hexdigest()
        for p, data in sorted(files.items(), key=lambda kv: Path(kv[0]).as_posix())}})


def check_collisions(folder: Path, files: Mapping[Path, bytes], record: Mapping[str, str],
                     force: bool, own: tuple[str, ...] = (), param: str = "out") -> None:
    """Refuse (DesignError naming ``param``) to overwrite a file in ``folder`` that the record
    does not list with its present content; ``own`` names files that are ours by name."""
    if force:
        return
    for path in files:
        name = Path(path).relative_to(folder).as_posix()
        if name in own or not Path(path).is_file():
            continue
        if record.get(name) != sha256_of(path):
            # the record is the last run's: a file an earlier run wrote and a later one kept
            # (changed since) is not in it
            why = ("changed since this command wrote it" if name in record
                   else "not written by this command's last run here" if record else "not written by this command")
            # the folder as the user gave it, with the file in it; a file the user named, itself
            value, which = (str(folder), f"{name} there ") if param == "out" else (str(path), "")
            refused = DesignError(param, value, f"{which}exists and was {why}: it is kept; move it away "
                                  "or give --force to overwrite it")
            refused.remedy, refused.remedies = {"force": True}, [{"force": True}]
            raise refused


def _not_written_again(folder: Path, files: Mapping[Path, bytes], record: Mapping[str, str]):
    """(path, unchanged since) of each file of the previous run (per ``record``) still in
    ``folder`` that this run, writing ``files``, does not write again; each hashed once."""
    new = {Path(p).relative_to(folder).as_posix() for p in files}
    for name, sha in sorted(record.items()):
        if name not in new and (now := sha256_of(folder / name)) is not None:
            yield folder / name, now == sha


def stale_files(folder: Path, files: Mapping[Path, bytes], record: Mapping[str, str]) -> list[Path]:
    """Files of the previous run (per ``record``) this run does not write and whose content is
    unchanged since: the ones to remove."""
    return [path for path, unchanged in _not_written_again(folder, files, record) if unchanged]


def kept_files(folder: Path, files: Mapping[Path, bytes], record: Mapping[str, str]) -> list[Path]:
    """Files of the previous run (per ``record``) this run does not write that were changed
    since it wrote them: kept (an edit of the user's), and said so, not left unsaid."""
    return [path for path, unchanged in _not_written_again(folder, files, record) if not unchanged]


def merged_record_bytes(tool: str, folder: Path, files: Mapping[Path, bytes],
                        record: Mapping[str, str]) -> bytes:
    """The record of ``files`` (inside ``folder``) written by ``tool``, keeping the entries of
    ``record`` (an earlier run's) for the names this run does not write."""
    from wheelstep_cli.formats.jsonio import json_bytes

    listed = dict(record)
    listed.update({Path(p).relative_to(folder).as_posix(): hashlib.sha256(data).hexdigest()
                   for p, data in files.items()})
    return json_bytes({"tool": tool, "files": dict(sorted(listed.items()))})
