"""The rules of a gear's shaft fittings (bore shape, key, flat, hub, set screw) and of its faces
(timing marks, chamfer) against its thickness: every rule stated for each input it reads,
so a refusal names the one the user gave, and a profile's search for its further problems
(config.resolve) never blames a rule on a default standing in for a key found at fault.
Lengths in mm.
"""

from __future__ import annotations

from enum import Enum

from wheelstep_cli.errors import DesignError


def _rule(ok: bool, param: str, value: object, limit: str, **reads: tuple[object, str]) -> None:
    """DesignError(param, value, limit) unless ``ok``; ``reads``: the other inputs the rule
    reads, each with the rule said of it (name=(value, limit))."""
    if not ok:
        raise DesignError(param, value, limit, reads)


def shaft_rules(spec) -> None:
    """Key narrower than the bore, flat shallower than its radius, a hub with its diameter, a
    set screw with a hub and a bore, marks and chamfer thinner than half the face width, a key
    angle with something to orient (a GearPairSpec)."""
    from wheelstep_cli.gears.bore_shapes import SET_SCREWS

    shape, bore, thickness = spec.bore_shape, spec.bore, spec.thickness
    shape_name = getattr(shape, "value", shape)
    _rule(spec.hub_length is None or spec.hub_d is not None, "hub_length", spec.hub_length, "needs --hub-d",
          hub_d=(None, "must be given: --hub-length is the hub's length"))
    _rule(spec.set_screw is None or spec.set_screw in SET_SCREWS, "set_screw", spec.set_screw,
          f"must be one of {', '.join(SET_SCREWS)}")
    _rule(spec.set_screw is None or spec.hub_d is not None, "set_screw", spec.set_screw,
          "needs --hub-d (the screw goes through the hub)",
          hub_d=(None, f"must be given: the {spec.set_screw} set screw goes through the hub"))
    if shape_name == "keyway":
        _rule(bore > 0, "bore", bore, "must be > 0 mm for a keyway", bore_shape=(shape_name, "needs --bore > 0 mm"))
        # the key width defaults from the bore (DIN 6885): name the bore when that was given
        _rule(spec.key_width < bore, "key_width", spec.key_width, f"must be < the bore {bore:g} mm",
              bore=(bore, f"must be > the key width {spec.key_width:g} mm"))
    # the timing marks are engraved into the faces: at most half the face width, so the
    # arrow never cuts through the gear
    _rule(spec.mark_depth <= 0.5 * thickness, "mark_depth", spec.mark_depth,
          f"must be <= half the thickness, {0.5 * thickness:g} mm",
          thickness=(thickness, f"must be >= twice the mark depth, {2.0 * spec.mark_depth:g} mm; or "
                                f"--mark-depth <= {0.5 * thickness:g} mm (0 for no marks)"))
    # a 45 deg chamfer on both faces: the two leave an edge between them
    _rule(spec.chamfer is None or 2.0 * spec.chamfer < thickness, "chamfer", spec.chamfer,
          f"must be < half the thickness {0.5 * thickness:g} mm",
          thickness=(thickness, f"must be > twice the chamfer, {2.0 * (spec.chamfer or 0.0):g} mm"))
    if shape_name == "hex":
        _rule(bore > 0, "bore", bore, "must be > 0 mm for a hex (across flats)",
              bore_shape=(shape_name, "needs --bore > 0 mm"))
    _rule(spec.set_screw is None or bore > 0, "set_screw", spec.set_screw,
          "needs a bore (--bore > 0 mm): the screw clamps the shaft",
          bore=(bore, f"must be > 0 mm: the {spec.set_screw} set screw clamps the shaft"))
    if shape_name == "d-flat":
        _rule(bore > 0, "bore", bore, "must be > 0 mm for a D-flat", bore_shape=(shape_name, "needs --bore > 0 mm"))
        _rule(spec.flat_depth < bore / 2.0, "flat_depth", spec.flat_depth, f"must be < half the bore {bore / 2.0:g} mm",
              bore=(bore, f"must be > twice the flat depth, {2.0 * spec.flat_depth:g} mm"))
    # a round hole looks the same at every angle: the angle orients a key, flat, hex or
    # screw (checked after the shapes' own rules, which name a missing bore first)
    why = "orients a keyed bore or a set screw: needs --bore-shape d-flat, keyway or hex, or --set-screw"
    _rule(spec.key_angle == 0 or spec.set_screw is not None or (bore > 0 and shape_name != "round"),
          "key_angle", spec.key_angle, why, bore_shape=(shape_name, f"is needed for --key-angle: {why}"),
          bore=(bore, f"is needed for --key-angle: {why}"))


def bore_defaults(values: dict) -> dict:
    """``values`` (a GearPairSpec's raw fields) with the bore shape's missing dimensions
    filled (mm) and the ones it does not use refused."""
    from wheelstep_cli.gears.bore_shapes import din_6885_key

    shape = values.get("bore_shape", "round")
    shape = shape.value if isinstance(shape, Enum) else shape
    bore = values.get("bore", 8.0)
    uses = {"d-flat": ("flat_depth",), "keyway": ("key_width", "key_depth")}.get(shape, ())
    for name in ("flat_depth", "key_width", "key_depth"):
        if values.get(name) is not None and name not in uses:
            wanted = "d-flat" if name == "flat_depth" else "keyway"
            raise DesignError(name, values[name], f"needs --bore-shape {wanted}",
                              {"bore_shape": (shape, f"must be {wanted} for --{name.replace('_', '-')}")})
    if not isinstance(bore, (int, float)) or isinstance(bore, bool) or bore <= 0:
        return values
    values = dict(values)
    if shape == "d-flat" and values.get("flat_depth") is None:
        values["flat_depth"] = round(0.1 * bore, 6)
    if shape == "keyway":
        width, depth = din_6885_key(bore)
        values.setdefault("key_width", None)
        values["key_width"] = width if values["key_width"] is None else values["key_width"]
        values["key_depth"] = depth if values.get("key_depth") is None else values["key_depth"]
    return values
