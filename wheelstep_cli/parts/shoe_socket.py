"""The shoe's sole and strut socket, sized before any solid is made (mm): what the shoe
pipeline (:mod:`wheelstep_cli.parts.shoe`) builds on, and what a batch plan checks up front."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.config.specs import MIN_BORE, MIN_SHOE_WALL, ShoeSpec
from wheelstep_cli.errors import DesignError, rounded_down, rounded_up
from wheelstep_cli.geometry.planar import polyline_box_distance
from wheelstep_cli.mechanism.sole import contact_angles, sole_profile

#: Hub angles sampled along the sole (JSON, CSV, DXF and the mesh all use these).
PROFILE_POINTS = 401


def check_socket(spec: ShoeSpec, sole_part: np.ndarray, top: float) -> float:
    """Check the socket fits in the body; return the wall between it and the sole (mm)."""
    d = spec.strut_diameter
    length = sole_part[-1, 0] - sole_part[0, 0]
    limit = min(spec.width, length) - 2.0 * MIN_SHOE_WALL
    if d > limit:
        across = "width" if spec.width <= length else f"sole length {length:.1f} mm"
        why = f"(socket wider than the body: {across} less {MIN_SHOE_WALL:g} mm wall each side)"
        # the width is the other side of the rule when it is the narrower; the mechanism
        # draws the sole, so a user who gave its sizes rather than the diameter is named
        alternatives = {"width": (spec.width, f"must be >= {rounded_up(d + 2.0 * MIN_SHOE_WALL)} mm {why}")
                        } if spec.width <= length else {}
        # a body narrower than its two walls has no socket to offer: most likely sizes typed
        # in metres (a = 0.06 for 60 mm) drew a sole a fraction of a millimetre long
        rule = (f"must be <= {rounded_down(limit)} mm {why}" if limit > 0 else
                f"fits no socket: the body is {min(spec.width, length):.2g} mm across (its "
                f"{'sole' if spec.width > length else 'width'}), less than its {MIN_SHOE_WALL:g} mm walls "
                "either side; lengths are in millimetres")
        error = DesignError("strut_diameter", d, rule, alternatives)
        if limit < MIN_BORE and alternatives:
            # no strut the shoe takes fits: the width is the input to change, said first
            width_rule = alternatives["width"][1]
            error = DesignError("width", spec.width, width_rule, {"strut_diameter": (d, rule)})
        raise error.tied_to({"a": spec.a, "b": spec.b, "c": spec.c, "r_min": spec.r_min})
    floor = polyline_box_distance(sole_part, (-d / 2.0, top - spec.socket_depth, d / 2.0, top))
    if floor < MIN_SHOE_WALL:
        # deepest socket that keeps the wall (the wall shrinks as the socket deepens): bisection
        lo, hi = 0.0, spec.socket_depth
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            wall = polyline_box_distance(sole_part, (-d / 2.0, top - mid, d / 2.0, top))
            lo, hi = (mid, hi) if wall >= MIN_SHOE_WALL else (lo, mid)
        # the body's height comes from the rim and the sole the mechanism draws: a user who
        # gave those rather than the depth is told which of theirs leaves the default too deep
        raise DesignError("socket_depth", spec.socket_depth,
                          f"must be <= {rounded_down(lo)} mm (socket deeper than the body: keep "
                          f"{MIN_SHOE_WALL:g} mm of plastic between it and the sole)"
                          ).tied_to({"rim": spec.rim, "a": spec.a, "b": spec.b, "c": spec.c, "r_min": spec.r_min})
    return floor


def sole_and_top(spec: ShoeSpec):
    """(mechanism, contact angles rad, sole profile, sole in the part frame, top y) in mm."""
    design = spec.design()
    phi = contact_angles(PROFILE_POINTS)
    profile = sole_profile(design, phi)
    sole_part = np.column_stack([profile[:, 0], design.c - profile[:, 1]])
    return design, phi, profile, sole_part, float(sole_part[[0, -1], 1].max() + spec.rim)


def socket_fits(spec: ShoeSpec) -> None:
    """The mechanism's and the socket's checks of :func:`~wheelstep_cli.parts.shoe.build_shoe`
    alone, before any solid is made (DesignError when the mechanism cannot be sized or the
    strut socket does not fit the body): a batch plan refuses such an entry up front."""
    _, _, _, sole_part, top = sole_and_top(spec)
    check_socket(spec, sole_part, top)
