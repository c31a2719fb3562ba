"""Building the entries of a batch: each in a worker process (one failure does not stop the
others), its parts laid on z = 0, compensated for the printer and checked."""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.batch.interrupts import interrupts_kept_from_children
from wheelstep_cli.batch.plan import Entry
from wheelstep_cli.config.names import remedy_in_yaml
from wheelstep_cli.errors import DesignError, offered_remedies
from wheelstep_cli.parts.interference_refusals import (interference_phrase, require_mounted_where_rolling,
                                                       require_play_that_clears, require_tips_clear_of_roots)
from wheelstep_cli.parts.bed_remedy import scaled_to_bed
from wheelstep_cli.parts.gear_pair import require_pair_on_bed
from wheelstep_cli.parts.kinds import KINDS, as_designed, build_for_printer, for_printer
from wheelstep_cli.parts.mesh_bounds import remedy_check, require_within_bounds, undercut_checked
from wheelstep_cli.parts.shoe_bed import shoe_scaled_to_bed
from wheelstep_cli.parts.tolerance import design_printer, keeps_no_play
from wheelstep_cli.parts.tolerance_cli import design_pair


@dataclass
class BuiltPart:
    """A checked, printer-compensated part lying on z = 0, with its footprint (mm)."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    volume: float
    expected_volume: float
    triangles: int
    footprint: list[list[np.ndarray]]
    checks: dict[str, bool]

    @property
    def bounds(self) -> np.ndarray:
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @property
    def perimeter(self) -> float:
        """Length (mm) of all footprint rings."""
        return float(sum(np.linalg.norm(np.diff(r, axis=0, append=r[:1]), axis=1).sum()
                         for polygon in self.footprint for r in polygon))


@dataclass
class EntryResult:
    index: int
    parts: list[BuiltPart] = field(default_factory=list)
    report: dict | None = None
    error: str | None = None
    param: str | None = None
    mating: dict | None = None   # a gear pair's meshing record (parts.mesh_check.meshing_record)
    band: dict | None = None     # its band record when the band is checked (parts.tolerance_cli)
    no_play: bool = False        # a gear pair whose backlash is all its printer's tooth clearance
    remedies: list = field(default_factory=list)   # a refusal's remedies, the entry's keys -> values


def refused_by(index: int, err: DesignError, **found) -> EntryResult:
    """Entry ``index`` refused by ``err``: its line with the remedies as the file's keys, and
    those remedies as data (for the batch's JSON report); ``found``: what was built before."""
    return EntryResult(index, error=remedy_in_yaml(err), param=err.param, remedies=offered_remedies(err),
                       **found)


def build_entry(entry: Entry, tolerance: bool = True) -> EntryResult:
    """Build one entry's parts for its printer and check them as written, alone and (a gear
    pair's meshing) together, with ``tolerance`` also over the printer's band (SPEC §11;
    worker-process entry point; never raises)."""
    try:
        kind = KINDS[entry.kind]
        # a band's fit is how the printer's pairs are drawn, not a check: it holds without
        # ``tolerance`` too (the print sheet and the plates say the parts are fitted)
        fit = _printer_fit(entry) if kind.mating_check is not None else None
        printer = entry.printer if fit is None else design_printer(entry.printer)
        if kind.mating_check is not None:
            # mounted closer than its teeth's tip clearance allows: refused before any tooth is cut
            require_tips_clear_of_roots(entry.spec, remedy_check(printer, bed=printer) if fit is None
                                        else _fit_check(entry, fit, printer))
        # an undercut entry is offered the remedies a build for its printer passed
        built = undercut_checked(lambda: (
            for_printer(kind, kind.build_part(entry.printed), printer, entry.spec) if fit is None
            else design_pair(entry.spec, entry.printer)), entry.spec, remedy_check(printer, bed=printer))
        if kind.mating_check is not None:
            # on its bed before the minutes of checks, as gears checks it: a pair that no plate
            # holds is refused for its size, not for figures its remedies could not cure
            # with the pair drawn smaller as the remedy when that one fits and meshes
            scaled_to_bed(lambda: require_pair_on_bed(built, entry.printer), entry.spec,
                          remedy_check(printer, bed=printer) if fit is None else _fit_check(entry, fit, printer))
        elif kind.name == "shoe":
            # too large for the bed: the shoe of the mechanism drawn smaller as the remedy
            built = shoe_scaled_to_bed(built, printer, lambda spec: build_for_printer(kind.name, spec, printer))
        mating = kind.mating_check(built) if kind.mating_check is not None else None
        result = EntryResult(entry.index, _parts(kind, built), _report(kind, built, mating), mating=mating)
        refused = _refused(entry, built, result, printer) or _out_of_bounds(entry, built, result, printer)
        if refused is not None:
            return refused
        if fit is not None:
            return _fitted(entry, kind, built, fit)
        band = _band(built, entry) if tolerance and mating is not None else None
        if band is not None:
            result.report["tolerance"] = band
        # unchecked over the band, a pair keeping no play of its own is warned of (gears warns too)
        return EntryResult(entry.index, result.parts, result.report, mating=mating, band=band,
                           no_play=band is None and mating is not None and keeps_no_play(built))
    except DesignError as err:
        # raised on the printer's compensated values: said of the override that shares the
        # blame (as the command line names the flag given), as the entry gives them
        err = as_designed(err.for_given(entry.overrides), entry.spec, entry.printed)
        return refused_by(entry.index, err)
    except Exception as err:  # an unexpected failure must not stop the other entries
        return EntryResult(entry.index, error=f"internal error: {type(err).__name__}: {err}")


def _parts(kind, built) -> list[BuiltPart]:
    from wheelstep_cli.geometry.solids import footprint

    return [BuiltPart(part.name, part.vertices, part.faces, check.volume, check.expected_volume,
                      check.triangles, footprint(part), _checks(check))
            for part, check in ((p, built.checks[p.name]) for p in kind.parts(built))]


def _report(kind, built, mating: dict | None, fit: dict | None = None) -> dict:
    """The entry's report: its kind's, with a gear pair's meshing record and what it says of
    the bounds (``fit``: the fit that inset the pair, judged on its design)."""
    from wheelstep_cli.parts.bound_figures import bounds_verdict

    report = kind.report_of(built)
    if mating is not None:
        report["meshing"] = {**mating, "bounds": bounds_verdict(mating, fit)}
    return report


def _fit_check(entry: Entry, fit: str, printer):
    """``verify(design)`` -> (design pair, its meshing record) for a remedy of an entry whose
    printer's band names a ``fit``: the design built for ``printer`` (without the tooth
    clearance) on the entry printer's bed, then fitted as :func:`_fitted` fits it, refused
    (DesignError) where that refuses it (the fit not met, teeth the inset left too thin)."""
    from wheelstep_cli.parts.fit import PROFILE_FIT_REMEDY, require_fit_met
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth
    from wheelstep_cli.parts.tolerance_cli import fitted_pair

    design_check = remedy_check(printer, bed=entry.printer)

    def verify(design):
        pair, record = design_check(design)
        fitted, band, _ = fitted_pair(design, entry.printer, fit, pair, None)
        require_fit_met(band, remedy=PROFILE_FIT_REMEDY)
        require_printable_teeth(fitted)
        return pair, record
    return verify


def _printer_fit(entry: Entry) -> str | None:
    """The fit (auto, tight, normal, loose) the entry's printer band names, else None."""
    return getattr(getattr(entry.printer, "band", None), "fit", None)


def _fitted(entry: Entry, kind, design, fit: str) -> EntryResult:
    """A gear pair entry drawn for its printer band's ``fit`` (parts.fit): ``design`` (drawn
    without the printer's tooth clearance, checked and within the bounds) inset until the
    band keeps the fit's margin; refused (naming ``fit``) when no inset does."""
    from wheelstep_cli.parts.fit import PROFILE_FIT_REMEDY, require_fit_met
    from wheelstep_cli.parts.mesh_check import meshing_record
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth
    from wheelstep_cli.parts.tolerance_cli import fitted_pair

    built, band, nominal = fitted_pair(entry.spec, entry.printer, fit, design, None)
    mating = meshing_record(nominal)
    band = {"checked": True, "tooth_clearance_mm": 0.0, **band}
    report = {**_report(kind, built, mating, band.get("fit")), "tolerance": band}
    try:
        require_fit_met(band, remedy=PROFILE_FIT_REMEDY)
        require_printable_teeth(built)    # on the printer it was drawn for: no tooth clearance
    except DesignError as err:   # its remedy as the entry's override keys, as without a fit
        return refused_by(entry.index, err, report=report, mating=mating)
    return EntryResult(entry.index, _parts(kind, built), report, mating=mating, band=band)


def _band(built, entry: Entry) -> dict:
    """The band record of a built gear pair on its entry's printer (a note to add a band
    when the printer has none)."""
    from wheelstep_cli.parts.tolerance_cli import printer_band_record

    return printer_band_record(built, entry.printer)


def _checks(check) -> dict[str, bool]:
    return {"manifold": True, "watertight": check.watertight,
            "winding_consistent": check.winding_consistent,
            "volume_matches_outline": check.volume_error < 1e-3}


def _refused(entry: Entry, built, result: EntryResult, printer) -> EntryResult | None:
    """The entry refused (no parts) when its gear teeth interfere, unless it allows it: named
    for its installed distance when the pair is mounted off its rolling distance, or for a
    backlash set too small for any play (each with its remedy, built for ``printer``), else
    for its teeth."""
    mating = result.mating
    if mating is None or not mating["interference"] or entry.allow_interference:
        return None
    interfere = interference_phrase(mating)
    try:
        verify = remedy_check(printer, bed=printer)
        require_mounted_where_rolling(built, interfere, verify)
        require_play_that_clears(built, mating, interfere, verify)
    except DesignError as err:
        err = err.for_given(entry.overrides)     # the override that moved the distance or the play
        return refused_by(entry.index, err, report=result.report, mating=mating)
    printed = entry.printed
    teeth = getattr(printed.teeth, "value", printed.teeth)
    reason = f"teeth = {teeth}: {interfere}; allow_interference: true builds it anyway"
    return EntryResult(entry.index, report=result.report, error=reason, param="teeth", mating=mating,
                       remedies=[{"allow_interference": True}])


def _out_of_bounds(entry: Entry, built, result: EntryResult, printer) -> EntryResult | None:
    """The entry refused (no parts) when its generated gear pair meshes outside the SPEC §10
    bounds or its teeth are too thin for the entry's printer, as ``wheelstep gears`` refuses
    it (the reason names the option and its remedy); ``printer``: as the pair was drawn for
    it (with a fit, without its tooth clearance), for the remedies' builds."""
    if result.mating is None or result.mating["interference"]:
        return None
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    try:
        require_within_bounds(built, result.mating, verify=remedy_check(printer, bed=printer))
        require_printable_teeth(built, printer)
    except DesignError as err:
        err = err.for_given(entry.overrides)     # the override that shares the blame, as gears names it
        return refused_by(entry.index, err, report=result.report, mating=result.mating)
    return None


class _Serial:
    """In-process stand-in for an executor (``--jobs 1``)."""

    def __enter__(self):
        return None

    def __exit__(self, *exc):
        return False


def executor(jobs: int, scheduler: str | None = None):
    """Where the entries are built: on the Dask cluster at ``scheduler`` when given, else
    ``jobs`` local processes (in this process for one)."""
    if scheduler:
        from wheelstep_cli.batch.cluster import dask_executor

        return dask_executor(scheduler)
    if jobs <= 1:
        return _Serial()
    return _local_pool(jobs)


@contextmanager
def _local_pool(jobs: int):
    """A pool of ``jobs`` worker processes, shut down waiting for them when the block ends
    normally; when it ends in an error or a Ctrl-C, its workers are killed and nothing waits
    for them (a worker cut off while it sent a result back would leave the pool's reader
    waiting on that message for ever)."""
    import multiprocessing

    before = set(multiprocessing.active_children())
    # spawn: safe with manifold3d's threads and the same on every platform
    pool = _QuietPool(max_workers=jobs, mp_context=multiprocessing.get_context("spawn"),
                     initializer=ends_at_interrupt)
    try:
        yield pool
    except BaseException:
        for worker in set(multiprocessing.active_children()) - before:
            worker.kill()
        # with the workers gone the pool's own end of their result pipe is its last writer:
        # closed, a result half sent ends the pool's reader (EOF) instead of keeping it waiting
        writer = getattr(getattr(pool, "_result_queue", None), "_writer", None)
        if writer is not None:
            writer.close()
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)


class _QuietPool(ProcessPoolExecutor):
    """A process pool whose workers never print a traceback at a Ctrl-C."""

    def submit(self, *args, **kwargs):
        # a submission may start a worker process: with SIGINT blocked until it is set up to
        # end quietly (ends_at_interrupt)
        with interrupts_kept_from_children():
            return super().submit(*args, **kwargs)


def ends_at_interrupt() -> None:
    """Set up a local pool worker (started with SIGINT blocked, see :func:`_local_pool`) to end
    at once and silently at a Ctrl-C: it holds no file (this process writes them all, and
    says that the run was stopped), and finishing its entry would keep the person waiting."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def map_items(pool, function, items, step, lazy: bool = False):
    """Results of ``function`` over ``items`` (any order), calling ``step()`` after each.

    With a pool the work is submitted at once; ``lazy`` (serial only) defers it until the
    results are read, so that the caller can do other work first either way.
    """
    if pool is None:
        results = (_call_and_step(function, item, step) for item in items)
        return results if lazy else list(results)
    futures = {pool.submit(function, item): item for item in items}
    return _collect(futures, step)


def _call_and_step(function, item, step):
    result = function(item)
    step()
    return result


def _collect(futures, step):
    from concurrent.futures import as_completed

    for future in as_completed(futures):
        try:
            result = future.result()
        except Exception as err:  # a worker died (e.g. killed): fail this item only
            item = futures[future]
            if isinstance(item, Entry):
                result = EntryResult(item.index, error=f"worker process failed: {type(err).__name__}: {err}")
            else:
                raise
        step()
        yield result


