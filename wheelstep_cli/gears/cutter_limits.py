"""The ranges the basic rack's tooth form takes (SPEC §9): what a generated pair's cutter may be.

The pressure angle in degrees (it bounds what a user writes); addendum, dedendum, tip
fillet and tip clearance as multiples of the module. The configuration's fields and the
rack cutter itself state them from here.
"""

from __future__ import annotations

#: Pressure angle of the rack, deg (least, greatest).
PRESSURE_ANGLE_DEG = (5.0, 35.0)
#: Addendum, x module (least, greatest).
ADDENDUM = (0.3, 2.0)
#: Greatest dedendum, x module (it must also exceed the addendum: the tip clearance).
DEDENDUM_MAX = 2.5
#: Cutter tip fillet radius, x module (least, greatest).
FILLET = (0.0, 0.45)
#: Tip clearance of the wheel's spaces below the pinion's tips, x module (least, greatest).
CLEARANCE = (0.0, 1.0)


def range_text(bounds: tuple[float, float], unit: str) -> str:
    """A refusal's limit for a value between ``bounds`` (``must be 0..0.45 x module``)."""
    return f"must be {bounds[0]:g}..{bounds[1]:g} {unit}"
