"""The fit of a printed pair (SPEC §11): the tooth clearance that keeps the least backlash
over the printer's band at the fit's margin, with no more play than that.

The least backlash of the band is that of its tight corner (both gears grown at the
smallest distance); it grows about linearly with the clearance cut into the teeth, so a
secant search on the tight corner finds the clearance in two or three builds, and the
whole band is checked once on the pair found. Lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from wheelstep_cli.config.printers import FIT_MARGINS, Fit
from wheelstep_cli.gears.meshing import MeshingSettings
from wheelstep_cli.parts.tolerance import (NOMINAL, band_cases, band_record, case_record, case_settings,
                                           check_case, jam_record, mid_play, printer_with_clearance, sectioned_pair)

#: The search stops when the tight corner's least backlash is this close (mm) above the margin.
FIT_TOLERANCE = 0.005
FIT_ROUNDS = 4
#: The most clearance (mm) the search tries: the printer profile's own limit.
FIT_MAX_CLEARANCE = 1.0
#: ... and at most this many modules: the backlash thins each tooth by half of it, and a
#: band that still jams there jams radially, which no clearance cures.
FIT_MAX_MODULES = 0.4


@dataclass(frozen=True)
class FitResult:
    """The fitted pair, the printer's clearance it was drawn with (mm) and its band record."""

    pair: object
    nominal: object     # the fitted pair's meshing report as written
    clearance: float
    margin: float
    band: dict
    rounds: list
    stopped: str = "margin"   # why the search ended: margin, corners, cap, repeat or rounds


def fit_pair(spec, printer, fit: str, build: Callable, settings: MeshingSettings = MeshingSettings()
             ) -> FitResult:
    """Search the tooth clearance (mm, added to ``spec``'s backlash) for ``fit`` (auto, tight,
    normal, loose: :data:`FIT_MARGINS`) on ``printer``'s band; ``build(spec, printer)``
    builds the pair as written. The clearance never takes the backlash below zero."""
    margin = FIT_MARGINS[Fit(fit)]
    tight = band_cases(printer.band)[0]
    cos_a = float(np.cos(np.radians(spec.pressure_angle)))
    lowest = -float(spec.backlash_mm)
    clearance, tried = float(printer.tooth_clearance), []
    pair = sections = nominal = None
    stopped = "rounds"
    for _ in range(FIT_ROUNDS):
        pair = build(spec, printer_with_clearance(printer, clearance))
        sections = sectioned_pair(pair)
        nominal = check_case(sections, NOMINAL, settings)
        report = check_case(mid_play(sections, nominal), tight, case_settings(settings))
        case = case_record(tight, report)
        least = -1.0 if case["backlash_min_mm"] is None else float(case["backlash_min_mm"])
        tried.append({"clearance_mm": clearance, "tight_least_backlash_mm": least,
                      "tight_depth_mm": case["max_penetration_mm"], **jam_record(report, sections.law)})
        if margin <= least <= margin + FIT_TOLERANCE:
            stopped = "margin"
            break
        if _corners_resist(tried):
            stopped = "corners"
            break
        cap = fit_cap(pair)
        clearance = min(cap, max(lowest, _next_clearance(tried, margin, cos_a)))
        if any(abs(t["clearance_mm"] - clearance) < 1e-6 for t in tried):
            stopped = "cap" if clearance >= cap - 1e-9 else "repeat"
            break
    record = band_record(sections, printer.band, printer.name, nominal, settings)
    return FitResult(pair, nominal, tried[-1]["clearance_mm"], margin, record, tried, stopped)


def _corners_resist(tried: list) -> bool:
    """True when the last two tries jam only at the pitch-curve corners and the larger
    clearance did not make that jam shallower (by a tenth): the corner jam is radial, more
    tooth clearance will not clear it."""
    if len(tried) < 2:
        return False
    prev, last = tried[-2], tried[-1]
    only = all(t["jammed_poses"] and t["jammed_at_corners"] == t["jammed_poses"] for t in (prev, last))
    return (only and last["clearance_mm"] > prev["clearance_mm"]
            and last["tight_depth_mm"] >= 0.9 * prev["tight_depth_mm"])


def fit_cap(pair) -> float:
    """The most tooth clearance (mm) the search gives ``pair``'s design: FIT_MAX_CLEARANCE,
    and at most FIT_MAX_MODULES of its module (generated teeth: the module they were cut
    with; paper teeth: the spec's)."""
    generated = getattr(pair, "generated", None)
    module = getattr(generated, "module", None)
    if module is None:
        module = getattr(getattr(pair, "spec", None), "module", None)
    return FIT_MAX_CLEARANCE if module is None else min(FIT_MAX_CLEARANCE, FIT_MAX_MODULES * float(module))


def _next_clearance(tried: list, margin: float, cos_a: float) -> float:
    """The next clearance (mm): a secant through the last two tries, or (first try, or a
    flat secant) the normal backlash's share cos(alpha) of the missing play."""
    last = tried[-1]
    aim = last["clearance_mm"] + (margin + FIT_TOLERANCE / 2 - last["tight_least_backlash_mm"]) * cos_a
    if len(tried) < 2:
        return aim
    prev = tried[-2]
    slope = ((last["tight_least_backlash_mm"] - prev["tight_least_backlash_mm"])
             / (last["clearance_mm"] - prev["clearance_mm"]))
    if not np.isfinite(slope) or slope <= 0.1:
        return aim
    return last["clearance_mm"] + (margin + FIT_TOLERANCE / 2 - last["tight_least_backlash_mm"]) / slope


def fit_record(result: FitResult, fit: str, design_backlash: float) -> dict:
    """What the report says of the fit (mm)."""
    return {"fit": fit, "margin_mm": result.margin, "tooth_clearance_mm": result.clearance,
            "backlash_mm": design_backlash + result.clearance, "search": result.rounds,
            "stopped": result.stopped}


def fit_line(record: dict) -> str:
    return (f"fit {record['fit']}: tooth clearance {record['tooth_clearance_mm']:.3f} mm (backlash "
            f"j_n {record['backlash_mm']:.3f} mm) keeps the band's least backlash >= "
            f"{record['margin_mm']:g} mm, found in {len(record['search'])} builds")


#: What a refused fit suggests instead: the pair drawn with the printer's own clearance is
#: within the design bounds; the band is the printer's worst case, and --slice checks the
#: pair as the slicer will really lay it down.
FIT_REMEDY = ("print without --fit (the printer's own tooth clearance): --slice checks the pair as "
              "PrusaSlicer will print it, --tolerance shows which cases of the band jam")


def require_fit_met(record: dict) -> None:
    """Refuse (DesignError on ``fit``) a fit whose search ended short of its margin: at the
    last clearance tried (mm) the band still jams, or keeps less least backlash than the
    margin (``record``: a band record with its ``fit``, see :func:`fit_record`)."""
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
    largest = max([t["clearance_mm"] for t in fit.get("search", [])] + [fit["tooth_clearance_mm"]])
    raise DesignError("fit", fit["fit"],
                      f"no tooth clearance up to {largest:.3f} mm keeps the least backlash >= "
                      f"{fit['margin_mm']:g} mm over the band of {record['printer']} (at "
                      f"{fit['tooth_clearance_mm']:.3f} mm {found}); nothing written; {FIT_REMEDY}")


def _corner_cause(case: dict, fit: dict) -> str:
    """What the refusal says of a jam at the pitch-curve corners: where, and when the search
    stopped on it, that more clearance did not shrink it."""
    jammed, corner = case.get("jammed_poses", 0), case.get("jammed_at_corners", 0)
    if not corner:
        return ""
    if fit.get("stopped") != "corners":
        return ", all at the pitch-curve corners" if corner == jammed else f", {corner} of them at the pitch-curve corners"
    return (", all at the pitch-curve corners, and more tooth clearance did not make that jam "
            "shallower: there the pinion's corner space meets the wheel's notch tooth with no "
            "radial clearance")


def require_fit_within_bounds(record: dict, band: dict) -> None:
    """Refuse (DesignError on ``fit``) a fitted pair whose meshing ``record`` breaks the design
    bounds (parts.mesh_bounds): the play the band needs costs each flank hub speed ripple
    at the handovers, which no remedy on the backlash can give back without losing the fit
    (``band``: its band record with the ``fit``)."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.parts.mesh_bounds import bound_violations

    broken = [text for text in bound_violations(record) if "interfere" not in text]
    if not broken:
        return
    fit = band["fit"]
    raise DesignError("fit", fit["fit"],
                      f"the tooth clearance the band of {band['printer']} needs "
                      f"({fit['tooth_clearance_mm']:.3f} mm, backlash j_n {fit['backlash_mm']:.3f} mm) "
                      f"puts the pair outside the bounds ({'; '.join(broken)}); nothing written; "
                      f"{FIT_REMEDY}")
