"""Walls a shaft hole and a hub must leave in a gear plate (mm): the rules the plate's solid
is built to, checked before manifold3d sees the shapes."""

from __future__ import annotations

import numpy as np

from wheelstep_cli.errors import DesignError, rounded_down, rounded_up
from wheelstep_cli.geometry.planar import min_radius

#: Least wall (mm) from a shaft hole (bore, key, flat corner, hex corner) to the root.
MIN_HOLE_WALL = 1.5


def require_wall(name: str, outline: np.ndarray, hole: np.ndarray, hole_param: str,
                  hole_value: object, bore: tuple[float, float] | None = None) -> None:
    """DesignError naming ``hole_param`` when the hole leaves under MIN_HOLE_WALL mm to the
    root; for a keyway (``hole_param`` key_depth, ``bore`` = (diameter, key width) mm) it
    names the bore when no key depth would leave the wall."""
    root = min_radius(outline)
    reach = hole_reach(hole)
    if root - reach < MIN_HOLE_WALL:
        # the largest value that leaves the wall: the hole's reach grows in proportion to
        # the bore (round, flat, hex), one for one with a key's depth
        value = float(hole_value or 0.0)
        limit = (value - (MIN_HOLE_WALL - (root - reach)) if hole_param == "key_depth"
                 else (root - MIN_HOLE_WALL) * value / reach)
        wall = f"(leave {MIN_HOLE_WALL:g} mm of wall inside the {name}'s root)"
        by_bore = None
        if hole_param == "key_depth" and bore is not None:
            allowed = root - MIN_HOLE_WALL

            def half_chord(radius: float, width: float) -> float:
                """How far from the axis a key ``width`` mm wide reaches a circle of ``radius``."""
                return float(np.sqrt(max(radius ** 2 - (width / 2.0) ** 2, 0.0)))

            def largest_bore(width: float, depth: float = value) -> float:
                return 2.0 * (half_chord(allowed, width) - depth)

            # the key's outer corner at (width/2, bore/2 + depth): not one for one with the depth
            # off the axis, so a far depth's limit is solved on that corner, less what the
            # hole's drawn reach adds to it (a printer's compensation)
            added = reach - np.hypot(bore[0] / 2.0 + value, bore[1] / 2.0)
            limit = min(limit, half_chord(allowed - added, bore[1]) - bore[0] / 2.0)
            largest = largest_bore(bore[1])
            if bore[1] >= largest:
                # no bore both holds the key (wider than it) and leaves the wall: the key is too
                # wide; the widest that leaves a bore between them, by bisection
                low, high = 0.0, float(bore[1])
                for _ in range(50):
                    middle = 0.5 * (low + high)
                    low, high = (middle, high) if middle < largest_bore(middle) else (low, middle)
                if float(rounded_down(low)) > 0.0:
                    raise DesignError("key_width", bore[1], f"must be < {rounded_down(low)} mm: wider, no bore "
                                                            f"both holds the key and leaves the wall {wall}")
                # a key this deep leaves no bore at any width: its depth is what to change (below)
            by_bore = (bore[0], f"must be < {rounded_down(max(largest, 0.0))} mm with the keyway's "
                                f"{value:g} mm depth {wall}")
            if largest <= 0.0:
                # a key this deep leaves no bore: the bore's limit is the one that leaves room
                # for a keyway half as deep as it is wide, the depth then said in turn
                depth = bore[1] / 2.0
                shallow = largest_bore(bore[1], depth)
                by_bore = (bore[0], f"must be < {rounded_down(max(shallow, 0.0))} mm for a keyway up to "
                                    f"{depth:g} mm deep (the {value:g} mm depth leaves no bore) {wall}")
            if limit <= 0.0:    # no key depth helps: the bore itself is too large for this gear
                raise DesignError("bore", *by_bore)
        elif limit <= 0.0:      # a root too near the axis for any hole ("must be < -1.36 mm" said nothing)
            raise DesignError(hole_param, hole_value, f"must be 0 (no hole): the {name}'s root is "
                              f"{rounded_down(root)} mm from the axis, under the {MIN_HOLE_WALL:g} mm of wall "
                              "a hole must leave")
        # a key depth the user left to its DIN default is said of the bore they gave
        raise DesignError(hole_param, hole_value, f"must be < {rounded_down(limit)} mm {wall}",
                          {"bore": by_bore} if by_bore else None)


def hole_reach(hole: np.ndarray | None) -> float:
    """How far (mm) a shaft ``hole`` ring reaches from the axis (0 without one)."""
    return float(np.max(np.hypot(hole[:, 0], hole[:, 1]))) if hole is not None else 0.0


def require_hub_fits(outline: np.ndarray, hole: np.ndarray | None, diameter: float) -> None:
    """DesignError naming hub_d when a hub of ``diameter`` mm leaves under MIN_HOLE_WALL mm
    to the root of ``outline`` or round the shaft ``hole`` (rings in mm)."""
    root, reach = min_radius(outline), hole_reach(hole)
    if reach + MIN_HOLE_WALL > root - MIN_HOLE_WALL:
        # no hub diameter fits: its two limits (round the hole, to the root) cross
        raise DesignError("hub_d", diameter, f"has no size that fits: a hub needs {MIN_HOLE_WALL:g} mm of wall "
                          f"round the shaft hole (reaching {reach:.2f} mm from the axis) and to the root "
                          f"({root:.2f} mm): make the hole smaller (--bore, a key's or flat's depth) or "
                          "leave out --hub-d")
    if diameter / 2.0 > root - MIN_HOLE_WALL:
        raise DesignError("hub_d", diameter, f"must be <= {rounded_down(2 * (root - MIN_HOLE_WALL))} mm (leave "
                          f"{MIN_HOLE_WALL:g} mm to the root)")
    require_hub_clears_hole(hole_reach(hole), diameter)


def require_hub_clears_hole(reach: float, diameter: float) -> None:
    """DesignError naming hub_d when a hub of ``diameter`` mm leaves under MIN_HOLE_WALL mm
    round a shaft hole reaching ``reach`` mm from the axis."""
    if diameter / 2.0 < reach + MIN_HOLE_WALL:
        raise DesignError("hub_d", diameter, f"must be >= {rounded_up(2 * (reach + MIN_HOLE_WALL))} mm (leave "
                          f"{MIN_HOLE_WALL:g} mm of wall round the shaft hole)")


#: Least plastic (mm) between a set screw's hole and the plate's top face: the hole runs out
#: through the hub's side above the plate, where a screwdriver reaches it.
SCREW_CLEAR_OF_PLATE = 0.5


def require_screw_fits(name: str, reach: float, hub: tuple[float, float], thickness: float,
                       flats: float, height: float, drop: np.ndarray) -> None:
    """DesignError naming set_screw ``name`` (its hole's teardrop section ``drop``, mm) when its
    captive nut (``flats`` across, ``height`` mm, between MIN_HOLE_WALL of wall round a hole
    reaching ``reach`` mm and the hub's wall) does not fit the hub = (diameter, length) mm on a
    plate ``thickness`` mm thick, or its hole (on the hub's mid-height) would run into the
    plate below the hub's side. The limits are rounded up: applied as printed, they fit."""
    diameter = float(np.ptp(np.asarray(drop)[:, 0]))     # the teardrop's round part
    # each also stated for the hub's diameter: the rule is shared with it
    if hub[0] <= 0:
        raise DesignError("set_screw", name, "needs --hub-d (the screw goes through the hub)",
                          {"hub_d": (None, f"must be given: the {name} set screw goes through the hub")})
    nut_out = reach + MIN_HOLE_WALL + height
    if nut_out > hub[0] / 2.0 - MIN_HOLE_WALL:
        least = rounded_up(2 * (nut_out + MIN_HOLE_WALL))
        raise DesignError("set_screw", name, f"does not fit the hub: needs --hub-d >= {least} mm",
                          {"hub_d": (hub[0], f"must be >= {least} mm (room for the {name} set screw's nut)")})
    length = max(2.0 * (flats / np.sqrt(3.0) - thickness + 1.0), diameter + 2.0 * SCREW_CLEAR_OF_PLATE)
    if hub[1] < length - 1e-9:
        raise DesignError("set_screw", name, f"does not fit the hub: needs --hub-length >= {rounded_up(length)} "
                          "mm (for its nut, and for its hole to leave through the hub's side, above the plate)",
                          {"hub_length": (hub[1], f"must be >= {rounded_up(length)} mm for the {name} set screw "
                                                  "(its hole leaves through the hub's side, above the plate)")})


def corner_clear_of(direction: float, segments: int) -> float:
    """Where (polar angle, rad) a regular polygon of ``segments`` sides puts its first corner
    so that none lies on the line at ``direction`` (rad): a set screw's hole cut along that
    line would meet a corner edge-on and leave slivers float32 cannot hold."""
    return direction + np.pi / segments
