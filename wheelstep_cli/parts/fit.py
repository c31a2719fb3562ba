"""The fit of a printed pair (SPEC §11): how much smaller along their normals both tooth
outlines are drawn so that the least backlash over the printer's band keeps the fit's
margin, with no more play than that.

A printer lays outlines down offset along their normals by -d..+d, so the fit takes its
clearance there too: both written outlines are the design's, inset (an exact polygon
offset). An angular backlash alone thins the teeth only along the motion, and at the
pitch-curve corners the pinion's corner space meets the wheel's notch tooth radially (an
arc about the corner point), which only a normal inset opens (benchmarks/results.md, the
corner socket). The least backlash of the band is that of its tight corner (both gears
grown at the smallest distance); it grows with the inset, so a secant search on the tight
corner's check of the inset sections finds it without rebuilding the teeth, and the whole
band is checked once on the pair as written. The design before the inset is what the
design bounds judge (parts.mesh_bounds); the inset pair's own figures are the print
compensation's, reported with the band. Lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from wheelstep_cli.config.printers import FIT_MARGINS, Fit
from wheelstep_cli.gears.meshing import MeshingSettings
from wheelstep_cli.geometry.planar import offset_outline
from wheelstep_cli.parts.tolerance import (NOMINAL, OFFSET_THIN, at_corners, band_cases, band_record,
                                           case_record, case_settings, check_case, design_printer,
                                           jam_record, mid_play, sectioned_pair)

#: The search stops when the tight corner's least backlash is this close (mm) above the margin.
FIT_TOLERANCE = 0.005
#: ... or when the smallest inset that keeps the margin is bracketed this close (mm): where
#: the last jam clears, the least backlash may jump past the margin's window.
INSET_TOLERANCE = 0.002
FIT_ROUNDS = 8
#: Builds of the written pair: the search checks exact offsets of the design's sections
#: with the design's play centring; at the corners a jam of a few um can hang on that
#: centring, so the written pair's tight corner is checked again, and the inset grown by
#: half the jam's depth while it jams.
FIT_CONFIRM_ROUNDS = 3
#: The most inset (mm) the search tries on each gear ...
FIT_MAX_INSET = 0.5
#: ... and at most this many modules: it thins every tooth by twice the inset, and a band
#: that still jams there jams for a reason the outlines' size does not touch.
FIT_MAX_MODULES = 0.15


@dataclass(frozen=True)
class FitResult:
    """The fitted pair as written, its meshing report, the design's (before the inset), the
    inset found (mm, each gear), the margin (mm), its band record and the search's tries."""

    pair: object
    nominal: object     # the fitted pair's meshing report as written
    design: object      # the design's meshing report (the pair before the inset)
    inset: float
    margin: float
    band: dict
    rounds: list
    stopped: str              # why the search ended: margin, corners, cap, repeat or rounds
    design_pair: object       # the design as drawn for the printer, before the inset


def inset_sections(sections, inset: float):
    """``sections`` (a tolerance.SectionedPair) with both outlines ``inset`` mm smaller."""
    if inset == 0.0:
        return sections
    return replace(sections, pinion=offset_outline(sections.pinion, -inset, "pinion", thin=OFFSET_THIN),
                   wheel=offset_outline(sections.wheel, -inset, "wheel", thin=OFFSET_THIN))


def inset_for_printer(pair, inset: float):
    """``pair`` (built for a printer or not) drawn ``inset`` mm smaller along its tooth
    outlines' normals, with the printer's bed-side compensation applied again."""
    from wheelstep_cli.parts.gear_pair import inset_gear_pair
    from wheelstep_cli.parts.kinds import KINDS, for_printer

    built = inset_gear_pair(pair, inset)
    if pair.printing is None:
        return built
    return for_printer(KINDS["gear-pair"], built, pair.printing.printer, pair.printing.design)


#: Meshing checks a fit runs at most: the search, the written pair's (nominal and tight
#: case) and the band's other three cases.
FIT_CHECKS = FIT_ROUNDS + 2 * FIT_CONFIRM_ROUNDS + 3


def fit_pair(spec, printer, fit: str, build: Callable, settings: MeshingSettings = MeshingSettings(),
             inset: Callable = inset_for_printer, design_report=None,
             progress: Callable[[int, int], None] | None = None) -> FitResult:
    """Search the outline inset (mm, each gear, along the normals) for ``fit`` (auto, tight,
    normal, loose: :data:`FIT_MARGINS`) on ``printer``'s band. ``build(spec, printer)``
    builds the design as written for the printer (drawn without the printer's tooth
    clearance: the inset replaces it); ``inset(pair, mm)`` draws it smaller;
    ``design_report``: the design's nominal meshing report when already checked;
    ``progress(done, FIT_CHECKS)`` after each meshing check. The inset never takes the
    design's normal backlash below zero (a negative inset grows the teeth)."""
    margin = FIT_MARGINS[Fit(fit)]
    tight = band_cases(printer.band)[0]
    cos_a = float(np.cos(np.radians(spec.pressure_angle)))
    design_pair = build(spec, design_printer(printer))
    # an inset e on both gears adds 4e to the normal backlash (each flank of the pinion's
    # tooth and of the wheel's space moves e): a negative one takes it off
    lowest = -0.25 * _normal_backlash(spec, design_pair)
    sections = sectioned_pair(design_pair)
    design = check_case(sections, NOMINAL, settings) if design_report is None else design_report
    done = [0]

    def checked(report):
        done[0] += 1
        if progress is not None:
            progress(min(done[0], FIT_CHECKS), FIT_CHECKS)
        return report
    # every try starts in the middle of the design's play: an inset only widens it
    start = mid_play(sections, design)
    cap = fit_cap(design_pair)
    tried, value, stopped = [], 0.0, "rounds"
    for _ in range(FIT_ROUNDS):
        report = checked(check_case(inset_sections(start, value), tight, case_settings(settings)))
        tried.append(_try_record(value, tight, report, sections.law))
        least = tried[-1]["tight_least_backlash_mm"]
        if (least is not None and margin <= least <= margin + FIT_TOLERANCE) or _bracketed(tried, margin):
            stopped = "margin"
            break
        if _corners_resist(tried):
            stopped = "corners"
            break
        value = min(cap, max(lowest, _next_inset(tried, margin, cos_a)))
        if any(abs(t["inset_mm"] - value) < 1e-6 for t in tried):
            stopped = "cap" if value >= cap - 1e-9 else "repeat"
            break
    chosen = _least_play(tried, margin)
    found = any(_good(t, margin) for t in tried)
    for round_ in range(FIT_CONFIRM_ROUNDS):
        # the pair as written, its play centred on its own nominal check as the band's is
        pair = inset(design_pair, chosen) if chosen != 0.0 else design_pair
        fitted = sectioned_pair(pair)
        nominal = checked(check_case(fitted, NOMINAL, settings))
        report = checked(check_case(mid_play(fitted, nominal), tight, case_settings(settings)))
        tried.append(_try_record(chosen, tight, report, fitted.law, on=FITTED_PAIR))
        if (not found or not tried[-1]["jams"] or chosen >= cap - 1e-9
                or round_ == FIT_CONFIRM_ROUNDS - 1):
            break
        chosen = min(cap, chosen + 0.5 * tried[-1]["tight_depth_mm"] + INSET_TOLERANCE)
    record = band_record(fitted, printer.band, printer.name, nominal, settings, known={tight.name: report})
    return FitResult(pair, nominal, design, chosen, margin, record, tried, stopped, design_pair)


def _normal_backlash(spec, design_pair) -> float:
    """The normal backlash j_n (mm) the design's teeth were cut with: generated teeth's
    cutter's, else the spec's."""
    cutter = getattr(getattr(design_pair, "generated", None), "cutter", None)
    return float(cutter.backlash) if cutter is not None else float(spec.backlash_mm)


#: What a try of the search was checked on (its record's ``checked_on``): offsets of the
#: design's sections, or the fitted pair built as it is written.
DESIGN_SECTIONS, FITTED_PAIR = "design sections", "fitted pair"


def _try_record(inset: float, tight, report, law, on: str = DESIGN_SECTIONS) -> dict:
    """One try of the search: the inset (mm), what it was checked on (``on``) and its tight
    corner's least backlash, jam depth (mm) and jammed poses."""
    case = case_record(tight, report)
    # where the teeth jam the least backlash is an overlap estimate, not a play
    least = None if case["jams"] or case["backlash_min_mm"] is None else float(case["backlash_min_mm"])
    return {"inset_mm": inset, "checked_on": on, "tight_least_backlash_mm": least,
            "tight_depth_mm": case["max_penetration_mm"], "jams": case["jams"], **jam_record(report, law)}


def _good(tried: dict, margin: float) -> bool:
    """Whether a try's tight corner keeps the margin (mm) without a jam."""
    least = tried["tight_least_backlash_mm"]
    return not tried["jams"] and least is not None and least >= margin


def _bracket(tried: list, margin: float) -> tuple[float, float]:
    """(largest inset that fell short, smallest that kept the margin), mm; -inf / inf if none."""
    short = [t["inset_mm"] for t in tried if not _good(t, margin)]
    good = [t["inset_mm"] for t in tried if _good(t, margin)]
    return max(short, default=-np.inf), min(good, default=np.inf)


def _bracketed(tried: list, margin: float) -> bool:
    low, high = _bracket(tried, margin)
    return high - low <= INSET_TOLERANCE


def _least_play(tried: list, margin: float) -> float:
    """The inset (mm) to write: the smallest tried whose tight corner keeps the margin without
    a jam, else the last tried (the fit is then refused on the band it gives)."""
    good = [t["inset_mm"] for t in tried if _good(t, margin)]
    return float(min(good)) if good else tried[-1]["inset_mm"]


def _corners_resist(tried: list) -> bool:
    """True when the last two tries jam only at the pitch-curve corners and the larger inset
    did not make that jam shallower (by a tenth): more inset will not clear it."""
    if len(tried) < 2:
        return False
    prev, last = tried[-2], tried[-1]
    only = all(t["jammed_poses"] and t["jammed_at_corners"] == t["jammed_poses"] for t in (prev, last))
    return (only and last["inset_mm"] > prev["inset_mm"]
            and last["tight_depth_mm"] >= 0.9 * prev["tight_depth_mm"])


def fit_cap(pair) -> float:
    """The most inset (mm, each gear) the search gives ``pair``'s design: FIT_MAX_INSET, and
    at most FIT_MAX_MODULES of its module (generated teeth: the module they were cut with;
    paper teeth: the spec's)."""
    generated = getattr(pair, "generated", None)
    module = getattr(generated, "module", None)
    if module is None:
        module = getattr(getattr(pair, "spec", None), "module", None)
    return FIT_MAX_INSET if module is None else min(FIT_MAX_INSET, FIT_MAX_MODULES * float(module))


def _next_inset(tried: list, margin: float, cos_a: float) -> float:
    """The next inset (mm). After a jam: the last plus half the jam's depth (an inset e on
    both gears takes 2e off a penetration along the normals) and the margin's share. Else a
    secant through the last two tries that did not jam, or (one such try, or a flat secant)
    the missing play's share: an inset e adds 4e of normal backlash, about 4e / cos(alpha)
    along the pitch curve. A step that leaves the bracket of short and good tries bisects it
    instead."""
    last = tried[-1]
    aim_margin = margin + FIT_TOLERANCE / 2
    if last["jams"] or last["tight_least_backlash_mm"] is None:
        aim = last["inset_mm"] + 0.5 * last["tight_depth_mm"] + 0.25 * aim_margin * cos_a
    else:
        missing = aim_margin - last["tight_least_backlash_mm"]
        aim = last["inset_mm"] + 0.25 * missing * cos_a
        free = [t for t in tried if not t["jams"] and t["tight_least_backlash_mm"] is not None]
        if len(free) >= 2:
            prev, last = free[-2], free[-1]
            slope = ((last["tight_least_backlash_mm"] - prev["tight_least_backlash_mm"])
                     / (last["inset_mm"] - prev["inset_mm"]))
            if np.isfinite(slope) and slope > 0.4:
                aim = last["inset_mm"] + (aim_margin - last["tight_least_backlash_mm"]) / slope
    low, high = _bracket(tried, margin)
    if low < aim < high:
        return aim
    if np.isfinite(low) and np.isfinite(high):
        return 0.5 * (low + high)
    return aim


def fit_record(result: FitResult, fit: str) -> dict:
    """What the report says of the fit (mm, um): the inset, what it adds to the normal
    backlash, the design's own figures before it and the search's tries."""
    return {"fit": fit, "margin_mm": result.margin, "inset_mm": result.inset,
            "normal_backlash_added_mm": 4.0 * result.inset,
            "how": "print compensation: both tooth outlines drawn this much smaller along their "
                   "normals (an exact polygon offset), as the printer's band moves them (SPEC §11)",
            "design": _figures(result.design), "search": result.rounds, "stopped": result.stopped}


def _figures(report) -> dict:
    """Backlash (mm) and each flank's figures (um, %) of a meshing report."""
    summary = report.to_dict()
    keep = ("F_i_total_um", "f_i_tooth_um", "hub_speed_ripple_pct")
    return {"interference": summary["interference"],
            "backlash_mm": [summary["backlash_min_mm"], summary["backlash_max_mm"]],
            **{side: {k: summary[side][k] for k in keep} for side in ("drive", "coast")}}


def fit_line(record: dict) -> str:
    def num(value, fmt):
        return "n/a" if value is None else format(value, fmt)

    design = record["design"]
    flanks = ", ".join(f"{side} F'i {num(design[side]['F_i_total_um'], '.1f')} um f'i "
                       f"{num(design[side]['f_i_tooth_um'], '.1f')} um ripple "
                       f"{num(design[side]['hub_speed_ripple_pct'], '.2f')} %" for side in ("drive", "coast"))
    inset = record["inset_mm"]
    drawn = inset_words(inset)
    source = f" ({record['from']})" if record.get("from") else ""
    replaced = record.get("replaces_tooth_clearance_mm")
    instead = f", instead of the printer's tooth clearance {replaced:g} mm" if replaced else ""
    return (f"fit {record['fit']}{source}: both tooth outlines drawn {drawn} along their normals "
            f"(print compensation{instead}; normal backlash {record['normal_backlash_added_mm']:+.3f} mm) "
            f"keep the band's least backlash >= {record['margin_mm']:g} mm ({_tries(record['search'])}); "
            f"the design before it: {flanks}")


def inset_words(inset: float) -> str:
    """How much smaller (or, < 0, larger) an inset of ``inset`` mm draws the outlines."""
    return f"{inset:.3f} mm smaller" if inset >= 0 else f"{-inset:.3f} mm larger"


def _tries(search: list) -> str:
    built = sum(1 for t in search if t["checked_on"] == FITTED_PAIR)
    return f"{len(search) - built} tries on the design's sections, {built} on the pair as written"


#: What a refused fit suggests instead: the pair drawn with the printer's own clearance; the
#: band is the printer's worst case, and --slice checks the pair as the slicer will really
#: lay it down.
FIT_REMEDY = ("print without --fit (the printer's own tooth clearance): --slice checks the pair as "
              "PrusaSlicer will print it, --tolerance shows which cases of the band jam")


#: ... and what a fit a printer profile's band names suggests (``batch``, or ``gears`` given
#: no --fit): the fit is the profile's, so it is taken out there.
PROFILE_FIT_REMEDY = ("remove `fit:` from the printer profile's band to print with its tooth_clearance "
                      "(with it removed, `wheelstep gears --tolerance --slice` with that --printer shows "
                      "which cases of the band jam and how PrusaSlicer prints the pair)")


def require_fit_met(record: dict, remedy: str = FIT_REMEDY) -> None:
    """Refuse (DesignError on ``fit``) a fit whose search ended short of its margin: at the
    last inset tried (mm) the band still jams, or keeps less least backlash than the margin
    (``record``: a band record with its ``fit``, see :func:`fit_record`)."""
    from wheelstep_cli.errors import DesignError

    fit, tight = record["fit"], record["cases"][0]
    least = record["least_backlash_mm"]
    if not record["jams"] and least is not None and least >= fit["margin_mm"] - FIT_TOLERANCE:
        return
    if record["jams"]:
        case = next(c for c in record["cases"] if c["jams"])
        found = (f"the {case['case']} case jams at {case.get('jammed_poses', case['interfering_poses'])} "
                 f"poses, {1000.0 * case['max_penetration_mm']:.0f} um deep{_corner_cause(case, fit)}")
    else:
        found = f"the {tight['case']} case keeps {least:.3f} mm"
    largest = max([t["inset_mm"] for t in fit.get("search", [])] + [fit["inset_mm"]])
    raise DesignError("fit", fit["fit"],
                      f"no outline inset up to {largest:.3f} mm per gear keeps the least backlash >= "
                      f"{fit['margin_mm']:g} mm over the band of {record['printer']} (at "
                      f"{fit['inset_mm']:.3f} mm {found}); nothing written; {remedy}")


def _corner_cause(case: dict, fit: dict) -> str:
    """What the refusal says of a jam at the pitch-curve corners: where (as the band's line
    says it), and when the search stopped on it, that a larger inset did not shrink it."""
    where = at_corners(case)
    if case.get("jammed_at_corners") and fit.get("stopped") == "corners":
        return where + ", and a larger inset did not make that jam shallower"
    return where
