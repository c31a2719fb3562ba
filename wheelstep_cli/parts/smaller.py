"""A part drawn smaller so that a printer's bed holds it: the options that scale a design.
Lengths in mm."""

from __future__ import annotations

import math

from wheelstep_cli.config.specs import Teeth
from wheelstep_cli.errors import DesignError


def scaled_options(design, scale: float) -> tuple[dict, float]:
    """(options, factor): the options (name -> value) that draw ``design``'s generated pair
    at most ``scale`` times its size, and the factor they scale it by. The input that sizes
    the pair (a module given, else the rolling distance given, else the installed distance)
    is rounded down (0.001 mm of module, 0.1 mm of distance); the other lengths the user gave
    (the other distance, the backlash) follow by the same factor, so the opening and the
    play keep their share of the teeth."""
    if design.module is not None:
        sizing, step = "module", 0.001
    elif design.center_distance is not None:
        sizing, step = "center_distance", 0.1
    else:
        sizing, step = "install_distance", 0.1
    given = getattr(design, sizing)
    size = float(given if given is not None else design.paper_distances[1])
    smaller = math.floor(size * scale / step + 1e-9) * step
    factor = smaller / size
    options = {sizing: round(smaller, 3)}
    for name in ("center_distance", "install_distance", "backlash"):
        value = getattr(design, name)
        if name != sizing and value is not None:
            options[name] = round(float(value) * factor, 3)
    return options, factor


def drawn_smaller(trial, err: DesignError) -> dict:
    """The options that draw ``trial``'s generated pair small enough for the bed its try was
    refused by (a count or play that widens the gears a little past the bed's edge), or {}."""
    scale = getattr(err, "bed_scale", None)
    if scale is None or trial.teeth != Teeth.generated:
        return {}
    return scaled_options(trial, scale)[0]


def scaled_mechanism(spec, scale: float) -> tuple[dict, float]:
    """(options, factor): a, b and the strut as ``spec`` gives it (c, r_min, or both; neither:
    the default R_min) scaled by at most ``scale``, each rounded down to 0.1 mm; with both c
    and r_min given, r_min follows from the scaled a, b, c (a - 4b + c), so they agree. The
    factor is the one a has."""
    def down(value: float) -> float:
        return round(math.floor(value * scale * 10 + 1e-9) / 10, 3)

    design = spec.design()
    options = {"a": down(spec.a), "b": down(spec.b)}
    if spec.c is not None:
        options["c"] = down(spec.c)
        if spec.r_min is not None:
            options["r_min"] = round(options["a"] - 4 * options["b"] + options["c"], 3)
    else:
        options["r_min"] = down(design.r_min)
    return options, options["a"] / spec.a


def size_percent(factor: float) -> str:
    """A size factor as a refusal says it: whole per cent, or tenths when that would say 100 %."""
    return f"{100 * factor:.0f} %" if factor < 0.995 else f"{100 * factor:.1f} %"
