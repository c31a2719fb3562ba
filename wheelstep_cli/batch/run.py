"""Running a checked batch: build the entries, pack and render the plates, write everything
in one atomic step."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from wheelstep_cli.batch.build import EntryResult, build_entry, executor, map_items
from wheelstep_cli.batch.outputs import MANIFEST, entry_report_bytes, manifest_bytes, previous_record
from wheelstep_cli.batch.plan import BatchPlan, Entry
from wheelstep_cli.batch.plates import Plate, plan_plates, plate_picture, plate_threemf


@dataclass
class BatchOutcome:
    written: list[Path]
    plates: list[Plate]
    failed: list[tuple[Entry, str, str]]     # entry, where (file:line), reason
    built: list[Entry]
    results: dict = field(default_factory=dict)   # entry index -> EntryResult
    removed: list = field(default_factory=list)   # files of an earlier batch this one removed
    kept: list = field(default_factory=list)      # ... and those it kept, changed since


def run_batch(plan: BatchPlan, out: Path, jobs: int = 1,
              progress: Callable[[str, int], Any] | None = None, force: bool = False,
              scheduler: str | None = None, tolerance: bool = True) -> BatchOutcome:
    """Build, pack, render and write a checked batch; ``progress(stage, total)`` -> advance().

    Files of an earlier batch in ``out`` (per its manifest, verified by SHA-256) that this one
    does not write are removed; any other file in the way is refused unless ``force``
    (DesignError, before anything is written). When no entry builds, nothing is written or
    removed. With ``scheduler`` the parts are built on
    that Dask cluster instead of ``jobs`` local processes. With ``tolerance`` (the default,
    as ``batch`` runs) each gear pair is also checked over its printer's band (SPEC §11)."""
    from functools import partial

    from wheelstep_cli.formats.atomic import remove_files, write_files_atomic
    from wheelstep_cli.formats.owned import check_collisions, kept_files, stale_files

    record, ours = previous_record(out)
    # refused before the build (minutes for gear pairs), as after it: a user's file, or one
    # changed since, at a name this run writes whatever the layout — the manifest, the print
    # sheet, the first plate and the entries' reports (the other plates' names come with it)
    early = [out / MANIFEST, out / "print-sheet.md", out / "plate-1.3mf", out / "plate-1.png",
             *(out / "reports" / f"{entry.name}.json" for entry in plan.entries)]
    check_collisions(out, dict.fromkeys(early, b""), record, force, own=(MANIFEST,) if ours else ())
    advance = progress or (lambda stage, total: (lambda: None))
    with executor(jobs, scheduler) as pool:
        step = advance("building parts", len(plan.entries))
        results: dict[int, EntryResult] = {}
        build = partial(build_entry, tolerance=tolerance)
        for result in map_items(pool, build, plan.entries, step):
            results[result.index] = result
        plates, dropped = plan_plates(plan.entries, results)
        step = advance("writing plates", 2 * len(plates))
        # 3MF files in the workers; meanwhile this (otherwise idle) process draws the pictures,
        # so matplotlib is imported once, as with --jobs 1
        threemfs = map_items(pool, plate_threemf, plates, step, lazy=True)
        pictures = {}
        for plate in plates:
            pictures[plate.number] = plate_picture(plate)
            step()
        rendered = {number: (data, pictures[number]) for number, data in threemfs}
    failed, built = _sort_out(plan, results, dropped)
    if not built:
        # a batch with no part to print writes nothing (as a refused command does) and leaves
        # an earlier batch's files where they are
        return BatchOutcome([], plates, failed, built, results, [])
    files = _files(plan, out, plates, rendered, built, results, failed)
    check_folder(out, files, force)
    written = write_files_atomic(files)
    stale = stale_files(out, files, record)
    remove_files(stale)
    return BatchOutcome(written, plates, failed, built, results, stale, kept_files(out, files, record))


def stale_batch_files(out: Path, paths) -> tuple[list[Path], list[Path]]:
    """The files of an earlier batch in ``out`` that a run writing ``paths`` removes, and those
    it keeps, changed since (as :func:`run_batch` does; for a dry run, built elsewhere)."""
    from wheelstep_cli.formats.owned import kept_files, stale_files

    files, record = dict.fromkeys(paths, b""), previous_record(out)[0]
    return stale_files(out, files, record), kept_files(out, files, record)


def check_folder(out: Path, paths, force: bool) -> None:
    """Refuse (DesignError) writing ``paths`` into ``out`` over files an earlier batch there did
    not write, as :func:`run_batch` does (for a dry run, built elsewhere)."""
    from wheelstep_cli.formats.owned import check_collisions

    record, ours = previous_record(out)
    check_collisions(out, dict.fromkeys(paths, b""), record, force, own=(MANIFEST,) if ours else ())


def _sort_out(plan: BatchPlan, results: dict[int, EntryResult], dropped: dict[int, str]):
    """(failed entries with where and why, built entries), in the batch file's order."""
    failed, built = [], []
    for entry in plan.entries:
        result = results[entry.index]
        if result.error:
            failed.append((entry, entry.locate(result.param or ""), result.error))
        elif entry.index in dropped:
            failed.append((entry, entry.where, dropped[entry.index]))
        else:
            built.append(entry)
    return failed, built


def _files(plan, out: Path, plates, rendered, built, results, failed) -> dict[Path, bytes]:
    """Every output file: plates, reports, the print sheet and the manifest (listing the rest)."""
    from wheelstep_cli.batch.mass import masses
    from wheelstep_cli.render.print_sheet import print_sheet_bytes

    from wheelstep_cli.formats.slicer_config import slicer_ini_bytes

    files: dict[Path, bytes] = {}
    for plate in plates:
        threemf, png = rendered[plate.number]
        files[out / f"{plate.stem}.3mf"] = threemf
        files[out / f"{plate.stem}.png"] = png
        printer = plate.printer
        files[out / f"{_ini_stem(printer.name)}.ini"] = slicer_ini_bytes(
            printer.slicer_config(), f"wheelstep batch: PrusaSlicer settings of printer {printer.name} "
                                     "(also inside each of its plates)")
    for entry in built:
        files[out / "reports" / f"{entry.name}.json"] = entry_report_bytes(entry, results[entry.index])
    files[out / "print-sheet.md"] = print_sheet_bytes(plan, plates, built, results, failed,
                                                      masses(built, results))
    files[out / MANIFEST] = manifest_bytes(plan, out, files, plates, built, results, failed)
    return files


def _ini_stem(printer: str) -> str:
    """``fdm-0.4-pla`` -> itself; a profile given as ``my-printer.yaml`` -> ``my-printer``."""
    name = Path(printer).name
    for suffix in (".yaml", ".yml"):
        if name.endswith(suffix):
            return name[: -len(suffix)]
    return name
