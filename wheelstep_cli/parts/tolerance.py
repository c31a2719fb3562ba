"""Will the pair mesh when printed? The meshing check over a printer's band (SPEC §11).

A printer lays outlines down offset along their normals by -d..+d and holds the centre
distance to +-e (:class:`~wheelstep_cli.config.printers.Band`). The pair is checked at the
band's extremes: both gears grown at the smallest distance (least backlash: does it jam?),
both shrunk at the largest (most backlash), and the two mixed cases at the smallest
distance (one gear's grown tips in the other's shrunk spaces: tip and root interference
that the symmetric cases hide). The nominal case is the check ``gears`` already ran.
Lengths in mm, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from wheelstep_cli.errors import DesignError
from wheelstep_cli.gears.cycle import WholeCycle
from wheelstep_cli.gears.meshing import MeshingReport, MeshingSettings, check_meshing
from wheelstep_cli.gears.meshing.check import default_pose_count
from wheelstep_cli.geometry.planar import offset_outline


@dataclass(frozen=True)
class BandCase:
    """One corner of the band: outline offsets (mm, + grows) and the distance shift (mm)."""

    name: str
    pinion_offset: float
    wheel_offset: float
    distance_shift: float


@dataclass(frozen=True)
class SectionedPair:
    """A pair's mid-thickness outlines (mm, own frames), law, installed distance and teeth.
    ``whole_cycle``: outlines that do not repeat every period of the law (printed ones), so
    checked over its whole cycle (gears.cycle.WholeCycle); else over one period."""

    pinion: np.ndarray
    wheel: np.ndarray
    law: object
    distance: float
    teeth: int
    shift: tuple | None = None   # (theta, wheel angle rad): start poses moved into the play
    whole_cycle: bool = False


def mid_play(sections: SectionedPair, nominal: MeshingReport) -> SectionedPair:
    """``sections`` starting their cases in the middle of the nominal pair's play, pose by
    pose: generated teeth may keep their play on one side, so the law's own pose touches a
    flank and any growth would overlap there although the wheel is free to turn away."""
    middle = 0.5 * (nominal.phi_drive + nominal.phi_coast) - nominal.phi_law
    good = np.isfinite(middle)
    fill = float(np.mean(middle[good])) if good.any() else 0.0
    return replace(sections, shift=(np.asarray(nominal.theta, float), np.where(good, middle, fill)))


def band_cases(band) -> tuple[BandCase, ...]:
    """The band's cases that decide jam and play (SPEC §11), tightest first."""
    d, e = float(band.outline), float(band.center_distance)
    return (BandCase("tight", d, d, -e),
            BandCase("pinion grown, wheel shrunk", d, -d, -e),
            BandCase("pinion shrunk, wheel grown", -d, d, -e),
            BandCase("loose", -d, -d, e))


def require_band(printer, option: str = "printer"):
    """The printer's band; DesignError telling the user to add one when it has none (a
    printer without a band is never taken as perfect)."""
    if printer.band is None:
        raise DesignError(option, printer.given or printer.name, "has no dimensional band: add a `band:` "
                                                "section (outline, hole_shrink, center_distance, mm) "
                                                "to its profile")
    return printer.band


def sectioned_pair(pair) -> SectionedPair:
    """The mid-thickness sections of a built gear pair's written meshes (SPEC §10)."""
    from wheelstep_cli.geometry.solids import section_outline

    generated = getattr(pair, "generated", None)
    law = generated.law if generated is not None else pair.law
    return SectionedPair(section_outline(pair.pinion.vertices, pair.pinion.faces, "pinion"),
                         section_outline(pair.wheel.vertices, pair.wheel.faces, "wheel"),
                         law, float(pair.mounted_distance), int(pair.spec.z))


NOMINAL = BandCase("nominal", 0.0, 0.0, 0.0)


#: Thinning (mm) of a band case's offset outlines: the round joins put an arc on every convex
#: vertex of the dense sections; kept to 0.1 um they add 10-20 % vertices and as much to the
#: meshing check's time. 0.5 um leaves about the sections' own count, far below the band's
#: +-50..100 um and the figures' micrometre. Fixed in mm at every module, as the band is (a
#: printer's deviation does not shrink with the teeth), for the fit's insets too.
OFFSET_THIN = 5e-4


def case_settings(settings: MeshingSettings) -> MeshingSettings:
    """``settings`` for a band case: its record gives jam, poses and depth, not the area, and
    no contacts where the teeth overlap."""
    return replace(settings, overlap_area=False, contacts_where_jammed=False)


def check_case(sections: SectionedPair, case: BandCase,
               settings: MeshingSettings = MeshingSettings()) -> MeshingReport:
    """The meshing check of ``sections`` offset and moved as ``case`` says: over one period of
    the law, or its whole cycle (:func:`checked_law`)."""
    pinion = offset_outline(sections.pinion, case.pinion_offset, "pinion", thin=OFFSET_THIN)
    wheel = offset_outline(sections.wheel, case.wheel_offset, "wheel", thin=OFFSET_THIN)
    law, settings = checked_law(sections, settings)
    return check_meshing(pinion, wheel, law, sections.distance + case.distance_shift,
                         settings, teeth=sections.teeth, start_offset=_start_offset(sections))


def checked_law(sections: SectionedPair, settings: MeshingSettings) -> tuple[object, MeshingSettings]:
    """The law ``sections`` are checked over and the settings for it: ``sections.law`` for
    outlines that repeat every period; for ``whole_cycle`` ones its whole cycle, in each of
    whose periods ``settings.samples`` poses (None: the default count of one period), so a
    tooth is sampled as densely as in the designed pair's check of one period."""
    if not sections.whole_cycle:
        return sections.law, settings
    cycle = WholeCycle(sections.law)
    per_period = (default_pose_count(sections.law, sections.teeth) if settings.samples is None
                  else settings.samples)
    return cycle, replace(settings, samples=cycle.periods * per_period)


def _start_offset(sections: SectionedPair):
    """Where each pose's contact search starts (rad of wheel angle from the law's) for
    ``sections``: its ``shift`` (found over one period of the designed pair, which repeats)
    interpolated over the law's period (None: at the law's angle)."""
    if sections.shift is None:
        return None
    theta, shift = sections.shift
    period = float(sections.law.theta_period)
    return lambda at: np.interp(at, theta, shift, period=period)


#: Pinion tooth pitches either side of a pitch-curve corner that are the corner's own poses.
#: There the pinion's corner space, cut by the rack pivoting about the corner point (an arc
#: about it), meets the wheel's notch tooth with no radial clearance, and more tooth
#: clearance was not seen to clear a jam (benchmarks/results.md, the corner socket).
CORNER_ZONE_PITCHES = 1.5


def jammed_poses(report: MeshingReport) -> np.ndarray:
    """Per pose: True where the teeth overlap or leave no backlash (as :func:`jams` counts:
    a pose whose contact was not found is not counted)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(report.interference, bool) | (np.asarray(report.backlash) <= 0.0)


def corner_poses(report: MeshingReport, law) -> np.ndarray:
    """Per pose of ``report``: True within :data:`CORNER_ZONE_PITCHES` pinion tooth pitches
    of a pitch-curve corner of ``law`` (all False for a law without corners)."""
    theta = np.asarray(report.theta, dtype=float)
    corners = np.asarray(law.corners, dtype=float)
    if corners.size == 0:
        return np.zeros(theta.shape, dtype=bool)
    period = float(law.theta_period)
    at = np.asarray(law.pinion_angle(corners), dtype=float)
    off = np.abs(np.mod(theta[:, None] - at[None, :] + 0.5 * period, period) - 0.5 * period)
    return off.min(axis=1) <= CORNER_ZONE_PITCHES * 2.0 * np.pi / int(report.teeth)


def jam_record(report: MeshingReport, law) -> dict:
    """How many poses of ``report`` jam, and how many of them at the corners of ``law``, of its
    ``poses``."""
    jammed = jammed_poses(report)
    return {"poses": int(jammed.size), "jammed_poses": int(jammed.sum()),
            "jammed_at_corners": int((jammed & corner_poses(report, law)).sum())}


def jams(summary: dict) -> bool:
    """True when a case's teeth overlap or leave no backlash somewhere."""
    least = summary["backlash_min_mm"]
    return bool(summary["interference"]) or (least is not None and least <= 0.0)


def case_record(case: BandCase, report: MeshingReport) -> dict:
    """What the band report says of one case (mm, um, %)."""
    summary = report.to_dict()
    flank = ("F_i_total_um", "f_i_tooth_um", "hub_speed_ripple_pct")
    if summary["interference"]:
        # searched only where the teeth clear (case_settings): a backlash over those poses
        # alone would read as the play of a pair that does not turn
        summary.update(backlash_min_mm=None, backlash_max_mm=None)
    return {"case": case.name, "pinion_offset_mm": case.pinion_offset,
            "wheel_offset_mm": case.wheel_offset, "distance_mm": summary["distance_mm"],
            "jams": jams(summary), "interference": summary["interference"],
            "interfering_poses": summary["interfering_poses"],
            "max_penetration_mm": summary["max_penetration_mm"],
            "backlash_min_mm": summary["backlash_min_mm"], "backlash_max_mm": summary["backlash_max_mm"],
            **{side: {key: summary[side][key] for key in flank} for side in ("drive", "coast")}}


def band_record(sections: SectionedPair, band, printer_name: str, nominal: MeshingReport,
                settings: MeshingSettings = MeshingSettings(), cases=None, known: dict | None = None) -> dict:
    """The meshing check on every case of ``band`` (or the ``cases`` given), started in the
    middle of the ``nominal`` check's play: per case and the band's least and largest
    backlash (mm on the wheel pitch curve). ``known``: reports of cases already checked so,
    by case name."""
    cases = band_cases(band) if cases is None else cases
    sections = mid_play(sections, nominal)
    records = []
    for case in cases:
        report = (known or {}).get(case.name) or check_case(sections, case, case_settings(settings))
        records.append({**case_record(case, report), **jam_record(report, sections.law)})
    # a case that jams has no backlash somewhere: the band's least is then none (0)
    least = [0.0 if r["jams"] else r["backlash_min_mm"] for r in records
             if r["jams"] or r["backlash_min_mm"] is not None]
    largest = [r["backlash_max_mm"] for r in records if r["backlash_max_mm"] is not None]
    return {"printer": printer_name,
            "band": {"outline_mm": band.outline, "hole_shrink_mm": band.hole_shrink,
                     "center_distance_mm": band.center_distance},
            "source": "exact offsets of the mid-thickness sections of the written meshes (SPEC §11)",
            "start_shift_arcmin": float(np.degrees(np.mean(sections.shift[1])) * 60.0),
            "cases": records, "jams": any(r["jams"] for r in records),
            "least_backlash_mm": min(least) if least else None,
            "largest_backlash_mm": max(largest) if largest else None}


def band_lines(record: dict) -> list[str]:
    """The band report as text, one line per case."""
    band = record["band"]
    lines = [f"tolerance band of {record['printer']}: outline +-{band['outline_mm']:g} mm, "
             f"centre distance +-{band['center_distance_mm']:g} mm -> "
             + ("JAMS" if record["jams"] else "meshes in every case")]
    for case in record["cases"]:
        def num(value, fmt=".3f"):
            return "n/a" if value is None else format(value, fmt)
        lines.append(
            f"  {case['case']:<28} {case['pinion_offset_mm']:+.3f}/{case['wheel_offset_mm']:+.3f} mm "
            f"at {case['distance_mm']:g} mm: "
            + (f"JAMS ({case.get('jammed_poses', case['interfering_poses'])} poses, "
               f"{1000 * case['max_penetration_mm']:.0f} um deep" + at_corners(case)
               # where the teeth overlap the contact angles are estimates, not a motion
               + ("; no backlash or TE where rigid teeth cannot go)" if case['interfering_poses'] else ")")
               if case['jams'] else "ok")
            + ("" if case['interfering_poses'] else
               f", backlash {num(case['backlash_min_mm'])}..{num(case['backlash_max_mm'])} mm, drive F'i "
               f"{num(case['drive']['F_i_total_um'], '.1f')} um f'i {num(case['drive']['f_i_tooth_um'], '.1f')}"
               f" um ripple {num(case['drive']['hub_speed_ripple_pct'], '.2f')} %"))
    return lines


def at_corners(case: dict) -> str:
    """What a jammed case's line says of its jam at the pitch-curve corners (nothing when it
    jams at every pose: the share would only measure the corner zone)."""
    jammed, corner = case.get("jammed_poses", 0), case.get("jammed_at_corners", 0)
    if not corner or jammed == case.get("poses"):
        return ""
    return ", all at the pitch-curve corners" if corner == jammed else f", {corner} at the pitch-curve corners"


def design_printer(printer):
    """``printer`` as a fit's design is drawn for it: without its tooth clearance (the
    fit's outline inset replaces it); every other compensation kept."""
    return replace(printer, tooth_clearance=0.0)


def printed_play(pair) -> float | None:
    """Play (mm) generated teeth keep of their own once printed: the backlash they were cut
    with less the printer's tooth clearance held in it; None when no clearance is held there
    (paper teeth, no printer, a clearance of 0, or a fit's inset in its place)."""
    printing = getattr(pair, "printing", None)
    if pair.generated is None or printing is None or float(getattr(pair, "inset", 0.0)) != 0.0:
        return None
    clearance = float(printing.printer.tooth_clearance)
    return None if clearance <= 0.0 else float(pair.generated.cutter.backlash) - clearance


def keeps_no_play(pair) -> bool:
    """Whether generated teeth drawn for a printer keep no play of their own once printed
    (:func:`printed_play` none within rounding: the default backlash is max(design's,
    clearance), so equal to the clearance within it)."""
    play = printed_play(pair)
    return play is not None and play < 1e-9
