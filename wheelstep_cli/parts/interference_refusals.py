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
            error.remedy = remedy
            raise error
