"""What a command prints: its report as a table or, with ``--json``, as one JSON document.

stdout carries the report only (with ``--json``, nothing but the document); warnings,
details (``-v``) and errors go to stderr. ``-q`` leaves errors and the requested JSON.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Mapping

import typer

from wheelstep_cli.formats.jsonio import json_text


@dataclass(frozen=True)
class Output:
    """How a command prints, from its ``--json``, ``-q`` and ``-v`` flags."""

    json: bool = False
    quiet: bool = False
    verbose: bool = False
    #: Files of an earlier run that a dry run's real run would remove (said by :meth:`files`).
    would_remove: list = field(default_factory=list, compare=False, repr=False)
    #: Files of an earlier run a run removed (said by :meth:`files`).
    removed: list = field(default_factory=list, compare=False, repr=False)
    #: Files of an earlier run changed since, which a run leaves where they are (said by :meth:`files`).
    kept: list = field(default_factory=list, compare=False, repr=False)
    #: Files the user named (:meth:`write_named`) that a run wrote: a --json report without
    #: a ``written`` list of its own gets them as one.
    named_written: list = field(default_factory=list, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.quiet and self.verbose:
            from wheelstep_cli.errors import DesignError

            # one asks for detail, the other for silence: neither may be dropped unsaid
            raise DesignError("verbose", "on", "cannot be combined with -q/--quiet")

    def report(self, report: Mapping, table: Callable[[], Iterable[str]]) -> None:
        """Print ``report`` as JSON (``--json``) or the lines of ``table()`` (none with -q). A
        command that wrote files the user named lists them as the report's ``written`` (unless
        it has its own), as the commands writing an output folder do."""
        if self.json:
            if self.named_written and "written" not in report:
                report = {**report, "written": [str(p) for p in self.named_written]}
            typer.echo(json_text(report), nl=False)
        elif not self.quiet:
            for line in table():
                typer.echo(line)

    def line(self, text: str) -> None:
        """One line of the table report (not with --json or -q)."""
        if not (self.json or self.quiet):
            typer.echo(text)

    def detail(self, text: str) -> None:
        """A line of detail on stderr, with -v only."""
        if self.verbose and not self.quiet:
            typer.echo(text, err=True)

    def warning(self, text: str) -> None:
        """A warning on stderr (not with -q)."""
        if not self.quiet:
            typer.echo(text, err=True)

    def error(self, text: str) -> None:
        """An error on stderr, always."""
        typer.echo(text, err=True)

    def parameters(self, values: Mapping, profile: str | None = None) -> None:
        """The parameters as resolved so far, one ``name = value`` per line (with -v); a nested
        mapping's entries as ``name.key``. Those still None are left to the design or preset
        (a command passes the values it has resolved by then) or do not apply: they are
        named on one last line, never printed as ``None``. ``profile``: the --profile given,
        said first with the file it was read from (a profiles/ folder in the working folder
        comes before the shipped presets)."""
        if profile:
            from wheelstep_cli.config.profiles import find_profile, profile_label, shadowed_preset

            found = find_profile(profile)
            if shadowed_preset(profile) is not None:
                # the same command elsewhere reads the preset: say which file this one read
                self.warning(f"wheelstep: warning: --profile {profile} is read from {profile_label(found)}, "
                             "a profiles/ folder in the working folder, not the shipped preset of that name")
            if self.verbose and not self.quiet:
                self.detail(f"  profile = {profile} ({found})")
        left = []
        for name, value in _flat(values):
            if value is None:
                left.append(name)
            else:
                self.detail(f"  {name} = {value}")
        if left:
            self.detail(f"  not given (set by the design or preset, or not used): {', '.join(left)}")

    def write(self, files: Mapping[Path, bytes], dry_run: bool) -> list[Path]:
        """Write ``files`` atomically, or nothing with ``dry_run``; the paths written."""
        from wheelstep_cli.formats.atomic import write_files_atomic

        if dry_run or not files:
            return []
        written = write_files_atomic(files)
        for path in written:
            self.detail(f"  {path}: {len(files[path])} bytes")
        return written

    def write_owned(self, folder: Path, command: str, files: Mapping[Path, bytes], dry_run: bool,
                    force: bool, check_only: bool = False) -> list[Path]:
        """Write ``files`` into ``folder`` as ``command``'s output (see formats.owned): a file
        there that this command did not write is refused unless ``force``; the record
        ``.wheelstep-COMMAND.json`` is written with them and the files of the previous run
        that this one does not write (and that are unchanged) are removed. Nothing with
        ``dry_run`` (the check still runs; the files it would remove are said with the
        files, unless ``check_only``: ``files`` are not all of the run's). Returns the paths
        written (would be, with ``dry_run``), the record last."""
        from wheelstep_cli.formats.atomic import remove_files
        from wheelstep_cli.formats.owned import check_collisions, kept_files, read_record, record_bytes, stale_files

        record_path = folder / f".wheelstep-{command}.json"
        record = read_record(record_path)
        check_collisions(folder, files, record, force)
        if not check_only:
            self.kept.extend(kept_files(folder, files, record))
        if dry_run:
            if not check_only:
                self.would_remove.extend(stale_files(folder, files, record))
            return [*files, record_path]
        written = self.write({**files, record_path: record_bytes(f"wheelstep {command}", folder, files)},
                             dry_run)
        stale = stale_files(folder, files, record)
        remove_files(stale)
        self.removed.extend(stale)
        return written

    def write_named(self, command: str, files: Mapping[Path, bytes], dry_run: bool,
                    force: bool, **named: Path | None) -> list[Path]:
        """Write files the user named (``named``: option -> path, e.g. plot=...) as ``command``'s
        outputs: a file of the same name that this command did not write (per the record
        ``.wheelstep-COMMAND.json`` in its folder) is refused naming its option unless
        ``force``, every path checked before any is written; each folder's record is updated
        with them and nothing else is removed."""
        from wheelstep_cli.formats.owned import check_collisions, merged_record_bytes, read_record

        groups: dict[Path, dict[Path, bytes]] = {}
        for path, data in files.items():
            groups.setdefault(Path(path).parent, {})[Path(path)] = data
        records = {folder: read_record(folder / f".wheelstep-{command}.json") for folder in groups}
        options = {Path(path): option for option, path in named.items() if path is not None}
        for folder, group in groups.items():
            for path, data in group.items():
                check_collisions(folder, {path: data}, records[folder], force, param=options.get(path, "out"))
        recorded = {folder / f".wheelstep-{command}.json":
                    merged_record_bytes(f"wheelstep {command}", folder, group, records[folder])
                    for folder, group in groups.items()}
        if dry_run or not files:
            return [*files, *recorded]
        written = self.write({**files, **recorded}, dry_run)
        self.named_written.extend(written)
        return written

    def written_record(self, paths: Iterable[Path], dry_run: bool) -> dict[str, list[str]]:
        """A report's ``written`` and ``removed`` files (none with ``dry_run``, whose report
        says them as ``would_write`` and ``would_remove``), and ``kept`` (``would_keep``) when
        an earlier run's file changed since is left in place."""
        kept = {"would_keep" if dry_run else "kept": [str(p) for p in self.kept]} if self.kept else {}
        names = [str(p) for p in paths]
        if dry_run:
            return {"written": [], "removed": [], "would_write": names,
                    "would_remove": [str(p) for p in self.would_remove], **kept}
        return {"written": names, "removed": [str(p) for p in self.removed], **kept}

    def files(self, paths: Iterable[Path], dry_run: bool, joined: bool = False) -> None:
        """Say which files were written (or would be, with ``dry_run``): one line each, or
        one ``joined`` line, and those of an earlier run removed (would be). In table mode on
        stdout; with --json on stderr for a dry run (the report lists them otherwise)."""
        verb = "would write" if dry_run else "wrote"
        names = [str(p) for p in paths]
        lines = ([f"{verb} " + ", ".join(names)] if joined else [f"{verb} {n}" for n in names]) if names else []
        # all the run does (would do) to the folder: the files it removes too
        lines += [f"{'would remove' if dry_run else 'removed'} {p} (written by an earlier run)"
                  for p in (self.would_remove if dry_run else self.removed)]
        lines += [f"{'would keep' if dry_run else 'kept'} {p} (an earlier run wrote it; changed since, so it "
                  "is not removed)" for p in self.kept]
        for text in lines:
            if not self.json:
                self.line(text)
            elif dry_run:
                self.warning(text)


def _flat(values: Mapping, prefix: str = "") -> list[tuple[str, object]]:
    """(name, value) of every entry, a nested mapping's entries named ``name.key``; an empty
    nested mapping stays one entry."""
    rows = []
    for name, value in values.items():
        if isinstance(value, Mapping) and value:
            rows += _flat(value, f"{prefix}{name}.")
        else:
            rows.append((f"{prefix}{name}", value))
    return rows
