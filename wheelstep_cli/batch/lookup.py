"""The profiles a batch file names (printers and designs), each found, read and checked once."""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Callable

from wheelstep_cli.config.located_yaml import LocatedYaml, YamlSyntaxError, read_located_yaml
from wheelstep_cli.config.printers import Printer, is_printer_profile, printer_from_profile
from wheelstep_cli.config.profiles import (
    design_from_file,
    find_profile,
    profile_label as file_label,
    wrong_kind,
)
from wheelstep_cli.config.schema import InvalidInput, Issue, dotted, show, yaml_issues
from wheelstep_cli.errors import DesignError


def profile_label(name: str) -> str:
    """A profile's name as recorded in outputs: bare names as they are, paths by file name only
    (so no folder, e.g. a temporary one, ends up in the manifest or the 3MF metadata)."""
    given = Path(name)
    return given.name if given.suffix in (".yaml", ".yml") or len(given.parts) > 1 else name


def _load_printer(name: str, file: Path, located: LocatedYaml) -> Printer:
    if not is_printer_profile(located.data):
        raise DesignError("printer", name, wrong_kind(located.data, "printer", name))
    return printer_from_profile(profile_label(name), file, file_label(file), located, given=name)


def _load_design(name: str, file: Path, located: LocatedYaml):
    return design_from_file(name, file, located), hashlib.sha256(file.read_bytes()).hexdigest()


class Profiles:
    """Printer and design profiles named by one batch file; relative ``.yaml`` paths are
    looked up next to the batch file first."""

    def __init__(self, batch_file: Path):
        self.folder = Path(batch_file).parent
        self.printers: dict[str, Printer | None] = {}
        self.designs: dict[str, tuple | None] = {}   # name -> (DesignProfile, file, sha256)
        # the outputs name a profile by its file's stem (no folder): one stem, one file
        self._stems: dict[tuple[bool, str], tuple[str, Path]] = {}

    def find(self, name: str, printer: bool | None = None) -> Path:
        """The file of profile ``name``; ``printer`` (True: a printer's, False: a design's)
        says which kind a refusal lists as known."""
        given = Path(name)
        nearby = self.folder / given
        if given.suffix in (".yaml", ".yml") and not given.is_absolute() and nearby.is_file():
            return nearby
        return find_profile(name, printer)

    def _lookup(self, doc: LocatedYaml, path: tuple, name: str, cache: dict, issues: list[Issue],
                load: Callable):
        """The profile ``name`` (named at ``path`` of the batch) as ``load`` makes it, read once;
        its problems become issues (and None is cached)."""
        if name not in cache:
            cache[name] = None
            try:
                file = self.find(name, printer=cache is self.printers)
                self._one_file_a_stem(name, file, cache is self.printers)
                cache[name] = (load(name, file, read_located_yaml(file, file_label(file))), file)
            except InvalidInput as err:
                issues.extend(err.issues)
            except DesignError as err:
                if isinstance(err, YamlSyntaxError):    # every repeated key at once, as for the batch file
                    issues.extend(yaml_issues(err))
                else:
                    issues.append(Issue(doc.where(path), dotted(path), f"= {show(name)}: {err.limit}"))
        return cache[name]

    def _one_file_a_stem(self, name: str, file: Path, printer: bool) -> None:
        """Refuse (DesignError) a profile whose file stem another file of its kind already has:
        its slicer settings, manifest and print-sheet entries would be written over."""
        key = (printer, Path(file).stem)
        seen = self._stems.setdefault(key, (name, Path(file).resolve()))
        if seen[1] != Path(file).resolve():
            raise DesignError("profile", name, f"names another file than {show(seen[0])} of the same "
                                               f"name ({Path(file).stem}), and the outputs name profiles "
                                               "by file name: rename one of the two files")

    def printer(self, doc: LocatedYaml, path: tuple, name: str, issues: list[Issue]) -> Printer | None:
        found = self._lookup(doc, path, name, self.printers, issues, _load_printer)
        if found is None and not any(i.where == doc.where(path) for i in issues):
            issues.append(Issue(doc.where(path), dotted(path),
                                f"= {show(name)}: the printer profile has errors (above)"))
        return None if found is None else found[0]

    def design(self, doc: LocatedYaml, path: tuple, name: str, issues: list[Issue]):
        """(DesignProfile, file name, sha256) of the design profile ``name``, or None."""
        found = self._lookup(doc, path, name, self.designs, issues, _load_design)
        if found is None:
            return None
        (profile, sha), file = found
        return profile, Path(file).name, sha
