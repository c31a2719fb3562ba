"""A generated gear pair too large for the printer's bed, remedied by the same pair drawn
smaller. The law depends on the mechanism's proportions only and the pitch curves scale
with the distance they roll at (SPEC §3); with the tooth count kept, the module follows the
pitch, so the whole footprint scales with that distance. Lengths in mm."""

from __future__ import annotations

from typing import Callable

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.mesh_bounds import no_remedy
from wheelstep_cli.parts.smaller import scaled_options, size_percent


def scaled_to_bed(build: Callable, design, verify: Callable | None, unbuilt: bool = False):
    """``build()``, or when a gear of ``design`` (generated teeth) is too large for the bed
    (its refusal carries ``bed_scale``), that refusal with the pair drawn smaller as its
    remedy once ``verify(design)`` -> (pair, meshing record) (mesh_bounds.remedy_check, or a
    command's whole check, which refuses what it does not write) finds that pair on the bed,
    meshing and within the bounds, or with the remedy the smaller pair's own refusal offers,
    built the same way (its teeth at that size: the search keeps the size); else what the
    tries gave. ``unbuilt`` (a sweep's row): the smaller pair said as a try, not built;
    without ``verify`` (a remedy's own try) the refusal as it is."""
    from wheelstep_cli.config.specs import Teeth

    try:
        return build()
    except DesignError as err:
        scale = getattr(err, "bed_scale", None)
        if (scale is None or design.teeth != Teeth.generated or getattr(err, "remedy", None)
                or (verify is None and not unbuilt)):
            raise
        options, factor = scaled_options(design, scale)
        if unbuilt:
            raise err.with_advice(f"try {as_flags(options)} (the pair drawn at {size_percent(factor)} of its size; "
                                  "not built)", options) from None
        sizing = next(iter(options))    # the input the scaling sets, and its size as the design has it
        size = options[sizing] / factor
        found, tried, factor = _smaller_pair(design, options, factor, verify)
        if found is None:
            raise err.with_advice(f"{no_remedy(tried)}: a printer with a larger bed (--printer)", {}) from None
        # the size offered (a later try may have drawn it smaller still); a module sizes the
        # pair with the count
        factor = found.get(sizing, size * factor) / size
        if sizing == "module":
            factor *= found.get("z", design.z) / design.z
        raise err.with_advice(f"use {as_flags(found)} (the pair drawn at {size_percent(factor)} of its size"
                              f"{_changed_besides(found, options, sizing)}, which the bed holds)", found) from None


def _smaller_pair(design, options: dict, factor: float, verify: Callable
                  ) -> tuple[dict | None, list[str], float]:
    """(the options that draw ``design`` smaller, with the remedy its refusal offers, or None;
    what the tries gave; the size factor). A smaller pair still off the bed (the printer's
    fixed compensations do not scale) is drawn smaller once more by its own refusal's scale."""
    from wheelstep_cli.config.schema import build
    from wheelstep_cli.parts.mesh_bounds import MeshBounds, bound_violations, require_within_bounds, verified_remedy

    for attempt in range(2):
        try:
            smaller = build(type(design), {**design.model_dump(), **options})
            pair, record = verify(smaller)
            break
        except DesignError as refusal:
            tried = [f"{as_flags(options)} is refused: {refusal.cause}"]
            if getattr(refusal, "bed_scale", None) and attempt == 0:
                options, factor = scaled_options(design, factor * refusal.bed_scale)
                continue
            own = getattr(refusal, "remedy", None) or {}
            # a refusal's own remedy (fewer teeth, less play) is built before it is offered
            found, more, _ = verified_remedy(smaller, own, verify, MeshBounds()) if own else ({}, [], [])
            return ({**options, **found} if found else None), [*tried, *more], factor
    broken = bound_violations(record)
    if not broken:
        return options, [], factor
    if record["interference"]:
        return None, [f"{as_flags(options)} is refused: {broken[0]}"], factor
    try:
        require_within_bounds(pair, record, verify=verify)     # its remedy is built by its search
    except DesignError as refusal:
        tried = [f"{as_flags(options)} is refused: {refusal.cause}", *getattr(refusal, "tried_words", [])]
        own = getattr(refusal, "remedy", None) or {}
        return ({**options, **own} if own else None), tried, factor
    return options, [], factor


def _changed_besides(found: dict, scaled: dict, sizing: str) -> str:
    """What a remedy changes besides drawing the pair smaller (``scaled``: the scaling's own
    options, ``sizing`` the one that sizes the pair), as words after the size ("" if nothing):
    the count, the play a try at that size needed."""
    words = {"z": lambda v: f"{v} teeth", "backlash": lambda v: f"a backlash of {v:g} mm"}
    more = [words.get(name, lambda v, n=name: f"{n.replace('_', ' ')} {v:g}")(value)
            for name, value in found.items() if name != sizing and scaled.get(name) != value]
    return f" with {' and '.join(more)}" if more else ""
