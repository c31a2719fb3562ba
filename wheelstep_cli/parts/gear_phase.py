"""How a printed pair is put together in phase: the assembly phase and what the bore and the
timing marks let the person assembling it do (angles in degrees, as reported)."""

from __future__ import annotations

from wheelstep_cli.config.specs import BoreShape


def phase_report(pair) -> dict:
    """The assembly phase (deg) and how the shaft holes sit on it."""
    from wheelstep_cli.gears.phase import assembly_phase, phase_record
    from wheelstep_cli.parts.gear_faces import pair_law

    law = pair_law(pair)
    record = phase_record(assembly_phase(law))
    if pair.spec.mark_depth <= 0:
        # nothing engraved: the directions are the assembly phase's, not marks on the gears
        record["carrier_zero"]["note"] = ("a shoe in mid-stance; no timing marks are engraved (mark depth 0): "
                                          "these directions set the pair in phase, the wheel's also the "
                                          "carrier's reference")
    record["shaft"] = shaft_record(pair.spec, law)
    return record


def shaft_record(spec, law) -> dict:
    """How the shaft holes of gears drawn to ``spec`` (config.specs.GearPairSpec) sit on the
    phase of ``law`` (its pinion_periods and wheel_periods): how many ways a shaft fits, how
    many of them are in phase, and how to assemble the pair in phase."""
    shape = BoreShape(spec.bore_shape) if spec.bore > 0 else None
    fits = shaft_positions(shape)
    in_phase = {"pinion": in_phase_positions(fits, law.pinion_periods),
                "wheel": in_phase_positions(fits, law.wheel_periods)}
    mark = "mark" if spec.mark_depth > 0 else "mark direction (no mark engraved)"
    every_way = fits not in (None, 1) and in_phase["pinion"] == in_phase["wheel"] == fits
    if spec.mark_depth <= 0 and fits != 1 and not every_way:
        how = ("the gears carry no timing marks (mark depth 0) and the bore does not set the phase: "
               "set the pair in phase by the assembly phase with your own reference, or print with marks")
    elif spec.mark_depth <= 0 and every_way:
        how = f"a hex shaft fits {fits} ways, every one in phase: no mark is needed"
    elif fits is None:
        how = "a round bore carries no phase: turn each gear until the marks face each other, then clamp"
    elif fits == 1:
        how = "a keyed shaft fits one way: shaft keys at the two mark angles plus key_angle put the pair in phase"
    else:
        how = (f"a hex shaft fits {fits} ways, of which {in_phase['pinion']} (pinion) and "
               f"{in_phase['wheel']} (wheel) are in phase: slide each gear on with its mark where "
               "the assembly phase says")
    return {"bore_shape": spec.bore_shape, "key_angle_deg": spec.key_angle,
            "shaft_fits_ways": fits, "in_phase_ways": in_phase if fits is not None else None,
            "note": f"the key, flat or a hex flat faces key_angle from each gear's {mark} (counter-"
                    f"clockwise seen from the top); {how}"}


def shaft_positions(shape: BoreShape | None) -> int | None:
    """How many ways a shaft fits its hole (None: any way, a round bore or none)."""
    return {BoreShape.d_flat: 1, BoreShape.keyway: 1, BoreShape.hex: 6}.get(shape)


def in_phase_positions(fits: int | None, periods: int) -> int | None:
    """Of the ``fits`` ways a shaft fits (equally spaced round the turn), how many put a gear
    whose teeth repeat ``periods`` times a turn in phase: those turned by a whole number of
    its periods (None for a round bore)."""
    if fits is None:
        return None
    return sum(1 for k in range(fits) if (k * periods) % fits == 0)
