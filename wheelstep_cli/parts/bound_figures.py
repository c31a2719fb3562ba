"""The bounds a written gear pair must mesh within (issue 13, SPEC §10), and the remedies its
figures point to: pure functions of a meshing record (``MeshingReport.to_dict()``).

A pair meshes within bounds when no pose interferes and, on both flanks, the total
tangential composite deviation F'i, the tooth-to-tooth one f'i (both um along the wheel
pitch curve) and the hub speed ripple band-limited to 3 tooth harmonics (%) are at most
the bounds. Lengths in mm, figures in um and %.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MeshBounds:
    """Largest figures (um, um, %) a written pair may show on either flank; with a fit, its
    design before the inset (the inset is print compensation, judged over the band)."""

    total_um: float = 15.0
    """F'i, total tangential composite deviation, um."""
    tooth_um: float = 10.0
    """f'i, tooth-to-tooth tangential composite deviation, um."""
    ripple_pct: float = 1.0
    """Hub speed ripple, band-limited to 3 tooth harmonics, %."""


#: (record key, bound field, unit, name in the refusal) per figure of a flank.
_FIGURES = (("F_i_total_um", "total_um", "um", "F'i"), ("f_i_tooth_um", "tooth_um", "um", "f'i"),
            ("hub_speed_ripple_pct", "ripple_pct", "%", "band-limited ripple"))


def bound_violations(record: dict, bounds: MeshBounds = MeshBounds()) -> list[str]:
    """What in a meshing record (``MeshingReport.to_dict()``) breaks the bounds, one phrase
    each (empty: within bounds). A figure that could not be measured (None) breaks them."""
    found = []
    if record["interference"]:
        found.append(f"teeth interfere at {record['interfering_poses']} of {record['samples']} poses")
    if record.get("contact_lost"):
        found.append("contact lost at some poses")
    # the ripple bound is on what the teeth add: a law that is not the crank law (or is
    # blended) has an output-speed ripple of its own
    own = record.get("law_hub_speed_ripple_pct", 0.0)
    for side in ("drive", "coast"):
        for key, field_name, unit, name in _FIGURES:
            value, limit, beyond = record[side][key], getattr(bounds, field_name), ""
            if key == "hub_speed_ripple_pct" and value is not None and own > 0.01:
                value, beyond = max(0.0, value - own), f" beyond the law's own {own:.2f} %"
            if value is None:
                found.append(f"{side} flank {name} not measured (bound {limit:g} {unit})")
            elif value > limit:
                found.append(f"{side} flank {name} {_beyond_limit(value, limit)} {unit}{beyond} > {limit:g} {unit}")
    return found


def _beyond_limit(value: float, limit: float) -> str:
    """A figure over its bound with the decimals (2 at least) that show it over: 1.004 %, not 1.00 %."""
    for places in range(2, 7):
        shown = f"{value:.{places}f}"
        if float(shown) > limit:
            return shown
    return f"{value:.6g}"


def _side_offsets(record: dict) -> dict[str, float]:
    """Each flank's mean lag behind the law (rad of wheel angle), from its TE band (arcmin)."""
    arcmin = np.pi / (180.0 * 60.0)
    return {side: 0.5 * (record[side]["te_min_arcmin"] + record[side]["te_max_arcmin"]) * arcmin
            for side in ("drive", "coast") if record[side]["te_min_arcmin"] is not None}


def backlash_remedy(law, record: dict, backlash: float, bounds: MeshBounds = MeshBounds(),
                    margin: float = 0.9) -> float:
    """Largest normal backlash (mm) at which both flanks' ripple should fall within
    ``margin`` x the bound: each flank's ripple is split into what its play costs
    (gears.generation.play) and the rest (the tooth form), and the play scaled down with
    the backlash. 0 when the rest alone breaks the bound."""
    from wheelstep_cli.gears.generation.play import largest_play, play_ripple

    scale, own = 1.0, play_ripple(law, 0.0)
    for side, delta in _side_offsets(record).items():
        ripple = record[side]["hub_speed_ripple_pct"]
        if ripple is None or abs(delta) < 1e-9:
            continue
        base = ripple / 100.0 - play_ripple(law, delta)
        allowed = largest_play(law, margin * bounds.ripple_pct / 100.0 + own, base)
        scale = min(scale, allowed / abs(delta))
    return float(np.floor(1000.0 * scale * backlash) / 1000.0)


def teeth_remedy(record: dict, z: int, periods: int, bounds: MeshBounds = MeshBounds(),
                 squared: bool = False) -> int:
    """Pinion teeth at which F'i and f'i should meet the bounds: the composite deviations of
    the generated teeth fall at least as fast as 1/z (about 1/z^2 measured), so z is scaled
    by the worst ratio to its bound (or its square root with ``squared``: as 1/z^2), rounded
    up to whole law periods."""
    worst = 1.0
    for side in ("drive", "coast"):
        flank = record[side]
        for key, limit in (("F_i_total_um", bounds.total_um), ("f_i_tooth_um", bounds.tooth_um)):
            worst = max(worst, (flank[key] if flank[key] is not None else 2 * limit) / limit)
    return int(periods * np.ceil(z * (np.sqrt(worst) if squared else worst) / periods))


def ripple_teeth_remedy(record: dict, z: int, periods: int, bounds: MeshBounds = MeshBounds(),
                        margin: float = 0.9) -> int:
    """Pinion teeth at which the tooth form's ripple should fall within ``margin`` x the bound:
    generated flanks deviate by microns whatever the tooth size, and the smaller the pitch,
    the steeper the TE those microns make, so their ripple grows about as z. z is scaled down
    by the worst flank's ratio (beyond the law's own ripple), in whole law periods, by at least
    a period, to no fewer than 6 teeth; two periods more when the ripple was not measured."""
    beyond = worst_ripple(record)
    if beyond is None:
        return z + 2 * periods
    worst = beyond / (margin * bounds.ripple_pct)
    fewer = min(z - periods, int(periods * np.floor(z / max(worst, 1.0) / periods)))
    return max(fewer, periods * -(-6 // periods))


def worst_ripple(record: dict) -> float | None:
    """The worst flank's band-limited ripple beyond the law's own (%), None if unmeasured."""
    ripples = [record[side]["hub_speed_ripple_pct"] for side in ("drive", "coast")]
    if any(value is None for value in ripples):
        return None
    return max(ripples) - record.get("law_hub_speed_ripple_pct", 0.0)


def fit_design_record(record: dict, fit: dict) -> dict:
    """The meshing record the bounds judge a fitted pair by: its design's figures before the
    inset (``fit["design"]``, parts.fit; the inset is print compensation, judged over the
    band) with the law's own ripple and the poses of ``record``, the inset pair's."""
    design = fit["design"]
    return {"interference": bool(design["interference"]), "interfering_poses": "some",
            "samples": record["samples"], "contact_lost": False, "drive": design["drive"],
            "coast": design["coast"], "law_hub_speed_ripple_pct": record.get("law_hub_speed_ripple_pct", 0.0)}


def bounds_verdict(record: dict, fit: dict | None = None, bounds: MeshBounds = MeshBounds(),
                   inset: float = 0.0) -> dict:
    """What a report says of the bounds for a meshing ``record``: the bounds, whether the pair
    is within them (``within``) and each bound it breaks, judged on the meshes checked or, for
    a pair a fit inset (``fit``, parts.fit, with an inset), on its design before the inset.
    Meshes a fit drew ``inset`` mm smaller whose design figures are not at hand (a plate's) are
    not judged (``within`` None): their figures carry the print compensation; ``broken`` then
    lists what those figures break."""
    fitted = fit is not None and bool(fit.get("inset_mm"))
    broken = bound_violations(fit_design_record(record, fit) if fitted else record, bounds)
    within: bool | None = not broken
    if fitted:
        judged = ("the design before the fit's inset (tolerance.fit.design): the inset is print "
                  "compensation, judged over the printer's band")
    elif inset:
        judged, within = (f"not judged: the meshes were drawn {inset:.3f} mm smaller by a fit (print "
                          "compensation, in their figures); gears judged the design before the inset"), None
    else:
        judged = "the meshes checked"
    return {"F_i_total_um": bounds.total_um, "f_i_tooth_um": bounds.tooth_um,
            "hub_speed_ripple_pct": bounds.ripple_pct,
            "ripple_of": "each flank's band-limited ripple beyond the law's own (law_hub_speed_ripple_pct)",
            "judged_on": judged, "within": within, "broken": broken}


def bounds_line(verdict: dict) -> str:
    """One line of a report saying whether the pair meshes within the bounds (:func:`bounds_verdict`)."""
    limits = (f"F'i <= {verdict['F_i_total_um']:g} um, f'i <= {verdict['f_i_tooth_um']:g} um, ripple <= "
              f"{verdict['hub_speed_ripple_pct']:g} % beyond the law's own, both flanks, no interference")
    if verdict["within"] is None:
        return f"bounds ({limits}): {verdict['judged_on']}"
    found = "within" if verdict["within"] else f"OUTSIDE ({'; '.join(verdict['broken'])})"
    return f"bounds: {found} ({limits}; judged on {verdict['judged_on']})"
