"""Refusals of generated pairs whose teeth interfere for a cause the user set (SPEC §10):
mounted off the distance their pitch curves roll at, or a backlash set below any play.
Each names the input and a remedy (built and checked, for the backlash). Lengths in mm."""

from __future__ import annotations

from typing import Callable

import numpy as np

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.mesh_bounds import (OPENING_TOLERANCE, MeshBounds, no_remedy, opening_phrase,
                                             verified_remedy)


def interference_phrase(record: dict) -> str:
    """What a meshing record's interference is, for a refusal: poses, distance (mm) and the
    largest overlap (mm^2; under a thousandth, as a zero-play pair's is, in um^2)."""
    area = float(record["max_overlap_area_mm2"])
    shown = f"{area:.3f} mm2" if area >= 5e-4 else f"{area * 1e6:.0f} um2"
    return (f"the teeth interfere at {record['interfering_poses']} of {record['samples']} poses at "
            f"{record['distance_mm']:g} mm (max overlap {shown})")


def require_mounted_where_rolling(pair, failure: str, verify: Callable | None = None) -> None:
    """Refuse (DesignError on the installed distance, with the remedy) a generated pair mounted
    off its rolling distance whose check found ``failure``; nothing for a pair mounted where
    its pitch curves roll. With ``verify(design)`` (pair, record) the remedy is built and
    followed up (mounted where they roll, the teeth may still mesh outside the bounds) before
    it is offered."""
    if pair.generated is None or abs(pair.opening) <= OPENING_TOLERANCE:
        return
    design = pair.as_asked
    remedy, tried = {"install_distance": pair.design_distance}, []
    if verify is not None:
        remedy, tried, _ = verified_remedy(design, remedy, verify, MeshBounds())
    advice = (f"use {as_flags(remedy)} (for more play, more backlash)" if remedy else
              no_remedy(tried))
    error = DesignError("install_distance", pair.mounted_distance,
                        f"{failure}; {opening_phrase(pair)}; nothing written; {advice}")
    error.remedy = remedy
    # the rolling distance comes from the centre distance or the module: named if given instead
    raise error.tied_to({"center_distance": design.center_distance, "module": design.module})


def require_play_that_clears(pair, record: dict, failure: str, verify: Callable,
                             bounds: MeshBounds = MeshBounds()) -> None:
    """Refuse (DesignError on the backlash, with a checked remedy) a generated pair whose teeth
    interfere (``failure``, from its meshing ``record``) at a backlash the user set below the
    design's own. Tried in turn, each built by ``verify(design)`` (pair, record) and followed
    as a bounds refusal's remedy is: the backlash rounded up to 0.01 mm past twice the
    interference depth (it takes play off both gears), at least 0.01 mm more than given;
    then the design's own backlash. Nothing when the backlash was not set or was not below
    the design's own, or when no try builds within the bounds."""
    from wheelstep_cli.parts.gear_laws import own_backlash

    if pair.generated is None:
        return
    design = pair.as_asked
    if design.backlash is None:
        return
    own = own_backlash(design)
    if design.backlash >= own:
        return
    depth = float(record["max_penetration_mm"])
    needed = design.backlash + 2.0 * depth
    least = max(float(np.ceil(100.0 * needed - 1e-9)) / 100.0, round(design.backlash + 0.01, 2))
    for candidate in dict.fromkeys([round(min(least, own), 3), round(own, 3)]):
        remedy, _, _ = verified_remedy(design, {"backlash": candidate}, verify, bounds)
        if remedy:
            error = DesignError("backlash", design.backlash,
                                f"{failure}, up to {1000.0 * depth:.1f} um deep: the backlash leaves "
                                f"rigid teeth no play; nothing written; use {as_flags(remedy)} "
                                "(--allow-interference writes them anyway)")
            # the line's other way out, after its remedy
            error.remedy, error.remedies = remedy, [remedy, {"allow_interference": True}]
            raise error


def require_tips_clear_of_roots(design, verify: Callable | None = None) -> None:
    """Refuse (DesignError on the installed distance, before any tooth is cut) generated teeth
    of ``design`` (config.specs.GearPairSpec) mounted closer than their pitch curves roll by
    more than the shallower tip clearance: where a tip of the gear with the taller teeth
    crosses the line of centres, mounting closer moves it straight into the other gear's
    space bottom, so the teeth interfere at every such tooth (a fit's inset deepens the
    spaces, but the design before it is checked first); the build and meshing check that
    would find it take a minute. The remedy (mounted where the pitch curves roll) is built by
    ``verify(design)`` (pair, record) when given."""
    from wheelstep_cli.gears.pitch_curves import center_distance_for_module
    from wheelstep_cli.parts.gear_laws import generation_law, rolling_distance

    if design.teeth != "generated" or design.install_distance is None:
        return
    law = generation_law(design)[1]
    if design.z % law.pinion_periods:
        return      # a tooth count the law's periods do not share is refused as such, later
    rolling = rolling_distance(design, law)
    closer = rolling - float(design.install_distance)
    if closer <= 0.0:
        return
    # the module the teeth are cut with at the rolling distance (SPEC §9: pitch / pi)
    module = rolling / center_distance_for_module(law, design.z // law.pinion_periods, 1.0)
    cutter = design.cutter()
    clearance = min(cutter.clearance, cutter.pinion_clearance) * module
    if closer <= clearance:
        return
    remedy, tried = {"install_distance": rolling}, []
    if verify is not None:
        remedy, tried, _ = verified_remedy(design, remedy, verify, MeshBounds())
    advice = f"use {as_flags(remedy)}" if remedy else no_remedy(tried)
    error = DesignError("install_distance", design.install_distance,
                        f"mounted {closer:.4g} mm closer than the pitch curves roll ({rolling:g} mm), more than "
                        f"the tip clearance {clearance:.3f} mm: tips run into the shallower spaces' bottoms "
                        f"where they cross the line of centres; nothing written; {advice}")
    error.remedy = remedy
    raise error.tied_to({"center_distance": design.center_distance, "module": design.module})
