"""``wheelstep batch``: build a YAML list of parts into plates, a manifest and a print sheet."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

import typer

from wheelstep_cli.cli.options import DryRun, Force, Json, Out, Quiet, Verbose, opt, require_workers

BatchTolerance = Annotated[Optional[bool], opt(
    "--tolerance/--no-tolerance", shown="--tolerance",
    help="Check every gear pair over its printer's dimensional band (SPEC §11), as drawn with "
         "the printer's tooth clearance: per case in its report and the manifest, a warning "
         "for a pair that jams. On by default; a printer profile without a band is told to add "
         "one. --no-tolerance skips the check (about four meshing checks per pair); a band "
         "that names a fit still has its pairs fitted to it.")]
from wheelstep_cli.cli.output import Output
from wheelstep_cli.errors import counted


def batch(
    file: Path = typer.Argument(..., help="Batch YAML: parts with kind, design, overrides, quantity, printer."),
    out: Out = Path("wheelstep-batch"),
    jobs: Annotated[int, opt("--jobs", "-j", help="Worker processes; 0 = one per CPU core.")] = 0,
    scheduler: Annotated[Optional[str], opt(
        "--scheduler", help="Build on the Dask cluster of this scheduler (tcp://HOST:8786) "
                            "instead of --jobs local processes.")] = None,
    force: Force = False, tolerance: BatchTolerance = None,
    json: Json = False, dry_run: DryRun = False, quiet: Quiet = False, verbose: Verbose = False,
) -> None:
    """Build every part of a batch file into packed 3MF plates with PNG previews,
    manifest.json and print-sheet.md. Exit 1 if some parts failed, 2 if the file is invalid."""
    from wheelstep_cli.batch import load_batch
    from wheelstep_cli.errors import DesignError

    show = Output(json, quiet, verbose)
    require_workers("jobs", jobs, "one per CPU core; a cluster goes in --scheduler")
    if scheduler and jobs:
        raise DesignError("jobs", jobs, "must not be given with --scheduler (the cluster's workers build)")
    if out.exists() and not out.is_dir():
        raise DesignError("out", str(out), "is a file; give a folder")
    # a file's problems (InvalidInput) are said by the CLI's runner, with --json's object too
    plan = load_batch(file, str(file))
    if tolerance is not None and not any(entry.kind == "gear-pair" for entry in plan.entries):
        # said as the switch typed, given (on), as a switch given twice is
        raise DesignError("tolerance", True, "the band check is of gear pairs, and the batch has none")
    tolerance = True if tolerance is None else tolerance
    for entry in plan.entries:      # -v: what each entry resolved to, before any build
        values = ", ".join(f"{k} = {v}" for k, v in entry.spec.model_dump().items() if v is not None)
        show.detail(f"  {entry.name}: {entry.kind} x {entry.quantity} from {entry.design_label} for printer "
                    f"{entry.printer.name}: {values}")
    outcome, written = _run(plan, out, jobs, show, dry_run, force, scheduler, tolerance)
    show.report({**_summary(file, out, plan, outcome), **show.written_record(written, dry_run)},
                lambda: _lines(out, plan, outcome, dry_run))
    _band_warnings(show, outcome)
    # a real run's files are said by its summary lines (each one with -v); a dry run's, and what
    # either removes, here
    if show.verbose and not dry_run:
        for path in written:
            show.detail(f"  wrote {path}")
    show.files(written if dry_run else [], dry_run=dry_run)
    if outcome.failed:
        show.error(f"{counted(len(outcome.failed), 'entry', 'entries')} failed:")
        for entry, where, reason in outcome.failed:
            show.error(f"  {entry.name} ({where}): {reason}")
        raise typer.Exit(1)


def _run(plan, out: Path, jobs: int, show: Output, dry_run: bool, force: bool, scheduler=None,
         tolerance: bool = False):
    """Build the batch into ``out`` (a dry run: into a scratch folder, then discarded);
    returns the outcome and the files written (or that would be, named inside ``out``)."""
    import os
    import tempfile

    from wheelstep_cli.batch import run_batch
    from wheelstep_cli.batch.run import check_folder, stale_batch_files
    from wheelstep_cli.cli.progress import Progress
    from wheelstep_cli.errors import DesignError

    workers = max(1, min(jobs or os.cpu_count() or 1, len(plan.entries)))
    show.detail(f"  {len(plan.entries)} entries, " + (f"on {scheduler}" if scheduler else f"{workers} worker(s)"))
    try:
        with Progress(not show.quiet, transient=False) as bars:
            if not dry_run:
                outcome = run_batch(plan, out, workers, bars, force, scheduler, tolerance)
                show.removed.extend(outcome.removed)
                show.kept.extend(outcome.kept)
                return outcome, outcome.written
            with tempfile.TemporaryDirectory(prefix="wheelstep-dry-run-") as scratch:
                outcome = run_batch(plan, Path(scratch), workers, bars, scheduler=scheduler,
                                    tolerance=tolerance)
                written = [out / p.relative_to(scratch) for p in outcome.written]
                if outcome.built:       # a run that builds nothing writes and removes nothing
                    check_folder(out, written, force)   # what the real run would refuse
                    removes, keeps = stale_batch_files(out, written)
                    show.would_remove.extend(removes)
                    show.kept.extend(keeps)
                return outcome, written
    except OSError as err:
        raise DesignError("out", str(out), f"cannot be written ({err.strerror or err})") from None


def _summary(file: Path, out: Path, plan, outcome) -> dict:
    """The batch run as plain data: what was built, on which plates, what failed and why (the
    files it writes are the output's :meth:`Output.written_record`)."""
    return {
        "batch": str(file), "out": str(out), "entries": len(plan.entries),
        "built": [entry.name for entry in outcome.built],
        "parts": sum(len(p.items) for p in outcome.plates),
        "plates": [{"file": f"{p.stem}.3mf", "printer_profile": p.printer.name,
                    "parts": len(p.items)} for p in outcome.plates],
        # each with the remedies its reason offers, as the entry's keys (none: [])
        "failed": [{"entry": entry.name, "where": where, "reason": reason,
                    "remedies": outcome.results[entry.index].remedies if entry.index in outcome.results else []}
                   for entry, where, reason in outcome.failed],
        **({"tolerance": bands} if (bands := _bands(outcome)) else {}),
    }


def _bands(outcome) -> list[dict]:
    """Per built gear pair checked over its printer's band: jams or not, least backlash."""
    from wheelstep_cli.batch.outputs import fit_brief

    return [{"entry": e.name, "printer": b["printer"], "checked": b["checked"], "jams": b["jams"],
             "least_backlash_mm": b.get("least_backlash_mm"), **({"note": b["note"]} if "note" in b else {}),
             **fit_brief(b)}
            for e in outcome.built if (b := outcome.results[e.index].band) is not None]


def _band_warnings(show: Output, outcome) -> None:
    """One stderr line per gear pair that jams over its band or whose printer has none, and
    (not checked over its band) per pair that keeps no play of its own once printed."""
    # PrusaSlicer's read-back is of FDM G-code: a resin printer's pair is not offered it
    resin = {e.name for e in outcome.built if getattr(e.printer, "technology", None) == "resin"}
    for entry in outcome.built:
        if outcome.results[entry.index].no_play:
            show.warning(f"WARNING: {entry.name}: printed on '{entry.printer.name}' the teeth keep no play of "
                         "their own (the backlash is all the printer's tooth clearance): teeth printed larger "
                         "than the clearance allows for jam; the batch without --no-tolerance checks it over "
                         "the printer's band, `fit: auto` in the profile's band section fits the teeth to it")
    for band in _bands(outcome):
        slice_words = "" if band["entry"] in resin else "`gears --slice` checks the pair as PrusaSlicer prints it, and "
        if not band["checked"]:
            show.warning(f"{band['entry']}: {band['note']}")
        elif band["jams"]:
            least = band["least_backlash_mm"]
            # a jammed case's backlash is an estimate where rigid teeth cannot go
            shown = "" if least is None or least <= 0.0 else f" (least backlash {least:.3f} mm)"
            show.warning(f"WARNING: {band['entry']} jams over the band of {band['printer']}{shown}: "
                         f"its report's tolerance section says in which case and how deep; {slice_words}"
                         "`fit: auto` in the printer profile's band section insets the tooth "
                         "outlines until the band clears (it says so when none within its limits does)")


def _lines(out: Path, plan, outcome, dry_run: bool = False) -> list[str]:
    """What the batch built (with ``dry_run``: would build) into ``out``, per plate, and each fit."""
    from wheelstep_cli.parts.fit import inset_words

    parts = sum(len(p.items) for p in outcome.plates)
    plates = len(outcome.plates)
    if not outcome.built:
        from wheelstep_cli.batch.outputs import MANIFEST

        kept = " (the earlier batch's files there are kept)" if (out / MANIFEST).is_file() else ""
        return [f"built none of {counted(len(plan.entries), 'entry', 'entries')}: nothing written to {out}{kept}"]
    built = "would build" if dry_run else "built"
    return [f"{built} {len(outcome.built)} of {counted(len(plan.entries), 'entry', 'entries')}: "
            f"{counted(parts, 'part', 'parts')} on {counted(plates, 'plate', 'plates')} in {out}",
            *(f"  {p.stem}.3mf ({p.printer.name}): {counted(len(p.items), 'part', 'parts')}"
              for p in outcome.plates),
            *(f"  {b['entry']}: fit {b['fit']} to the band of {b['printer']}: both tooth outlines drawn "
              f"{inset_words(b['inset_mm'])} along their normals, least backlash over the band "
              f"{b['least_backlash_mm']:.3f} mm" for b in _bands(outcome) if "fit" in b and not b["jams"])]


def register(app: typer.Typer) -> None:
    app.command("batch")(batch)
