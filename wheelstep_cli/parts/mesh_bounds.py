"""What to do when a written gear pair would mesh outside its bounds (issue 13, SPEC §10):
refuse it before anything is written, with a remedy whose build meshes within them.

The bounds and the remedies the figures point to are in :mod:`~wheelstep_cli.parts.bound_figures`
(imported here for the callers that name them from this module). Lengths in mm, figures in um, %.
"""

from __future__ import annotations

from typing import Callable

from wheelstep_cli.config.names import as_flags
from wheelstep_cli.config.specs import GENERATOR_SETTINGS, MAX_TEETH
from wheelstep_cli.errors import DesignError
from wheelstep_cli.parts.fewest_teeth import fewest_teeth
from wheelstep_cli.parts.printed_teeth import sized_remedy
from wheelstep_cli.parts.smaller import drawn_smaller
# the figures' side re-exported: callers name the bounds and their remedies from here
from wheelstep_cli.parts.bound_figures import (MeshBounds, backlash_remedy, bound_violations,  # noqa: F401
                                               ripple_teeth_remedy, teeth_remedy, worst_ripple)


#: Remedies tried (each a build and a meshing check) along each way of remedying a design
#: before a refusal offers one: the figures' remedy, then (:func:`_other_ways`) fewer teeth
#: for a ripple alone and the changed settings at their defaults; 3 ways at most. Five tries
#: let a way alternate less play and more teeth twice (less play, then, where it hardly lowered
#: the ripple, more teeth, less play for them, more teeth) after a try a hair over a bound.
REMEDY_TRIES = 5


def remedy_check(printer, wrap: Callable | None = None, bed=None) -> Callable:
    """``verify(design)`` -> (pair, meshing record) for a bounds refusal's remedy
    (:func:`require_within_bounds`): the gear pair of ``design`` built for
    ``printer`` as batch and ``gears`` build it, its teeth wide enough for the printer's
    nozzle and, when the pair is laid out on the ``bed`` of a printer, both gears on that
    bed (DesignError, with its own remedy if any, when not), checked as written;
    ``wrap(check, pair)`` runs the check (a progress bar) when given."""
    from wheelstep_cli.parts.gear_pair import require_pair_on_bed
    from wheelstep_cli.parts.kinds import build_for_printer
    from wheelstep_cli.parts.mesh_check import check_gear_pair, meshing_record
    from wheelstep_cli.parts.printed_teeth import require_printable_teeth

    def verify(design):
        trial = build_for_printer("gear-pair", design, printer)
        if bed is not None:     # a remedy the plate cannot hold is no remedy
            require_pair_on_bed(trial, bed)
        require_printable_teeth(trial)
        return trial, meshing_record(check_gear_pair(trial) if wrap is None else wrap(check_gear_pair, trial))
    return verify


def require_within_bounds(pair, record: dict, bounds: MeshBounds = MeshBounds(),
                          verify: Callable | None = None) -> None:
    """Refuse (DesignError naming the option to change) a generated pair whose meshing record
    breaks a figure bound, with the options that should bring it within: more teeth (--z)
    for F'i and f'i, less backlash (--backlash) for the ripple a flank's play costs.
    ``verify(design)`` (pair, meshing record) builds and checks a design as the caller
    writes it: when given, a remedy is offered only once a build with it is within the
    bounds (up to REMEDY_TRIES remedies, each from the last try's figures), or the line says
    what was tried; without it (a sweep's rows) the remedy the figures point to is said as a
    try, not built. Interference is refused elsewhere."""
    from wheelstep_cli.parts.gear_laws import design_backlash

    broken = _broken(record, bounds)
    if not broken or pair.generated is None:
        return
    design = pair.as_asked
    remedy, tried, candidates = {}, [], []
    if abs(pair.opening) > OPENING_TOLERANCE:
        # off the distance they roll at the pitch curves do not roll: mount them there (built
        # and followed up like any remedy: mounted right, the teeth may still need changing)
        broken.append(opening_phrase(pair))
        remedy["install_distance"] = pair.design_distance
        if verify is not None:
            remedy, tried, candidates = verified_remedy(design, remedy, verify, bounds)
    else:
        remedy = _remedy_of(pair, design, record, bounds, built=verify is not None)
        if verify is not None and remedy:
            # the play alone first only where a build follows it up (a sweep's row keeps the count)
            remedy, tried, candidates = verified_remedy(design, _play_first(design, remedy), verify, bounds,
                                                        measured=record)
        if verify is not None and not remedy:
            remedy, tried, candidates = _other_ways(pair, design, record, verify, bounds, (tried, candidates))
        remedy = dict(sorted(remedy.items(), key=lambda option: option[0] != "z"))   # the count first
    param = next(iter(remedy), "z")
    value = design_backlash(design) if param == "backlash" else getattr(design, param)
    if remedy and verify is None and "install_distance" not in remedy:
        # a sweep's row: no build per refused point, so the remedy is what the figures point to
        advice = f"try {as_flags(remedy)} (from the figures; not built)"
    elif remedy:
        # a remedy found after refused tries says why it is not the first one
        advice = f"use {as_flags(remedy)}" + (f" (tried first: {'; '.join(tried)})" if tried else "")
    else:
        found = no_remedy(tried) if tried else f"no tooth count up to {MAX_TEETH} brings it within them"
        advice = change_advice(design, found) + _fit_hint(pair, broken)
    error = DesignError(param, value,
                        f"the pair would mesh outside the bounds ({'; '.join(broken)}); nothing "
                        f"written; {advice}")
    # every input that shapes the teeth or the law shares the blame: the line names the one
    # the user gave (the remedy stays the remedy)
    shaping = {**{name: getattr(design, name) for name in GENERATOR_SETTINGS}, **design.sizing(),
               "law_csv": design.law_csv}
    error = error.tied_to({"backlash": design_backlash(design), **shaping})
    error.remedy = remedy   # name -> value, for a batch file to state as its keys
    error.tried = candidates  # the remedies built and found wanting, likewise
    error.tried_words, error.broken = tried, broken   # what they gave; the bounds broken
    raise error


def fit_may_cure(pair, broken: list[str]) -> bool:
    """Whether a fit to the printer's band may cure the bounds ``broken`` (a refusal's phrases):
    a ripple drawn with the tooth clearance of a printer that states a band (the clearance's
    play costs speed; a fit replaces the clearance)."""
    printer = pair.printing.printer if pair.printing is not None else None
    if printer is None or float(printer.tooth_clearance) <= 0.0 or printer.band is None:
        return False
    return any("ripple" in text for text in broken)


def _fit_hint(pair, broken: list[str]) -> str:
    """For a ripple drawn with a printer's tooth clearance (the play it prints costs speed), where
    a fit to the printer's band, which replaces that clearance, draws less play (not built here:
    a fit is checked over the band, several meshing checks; ``gears`` tries it)."""
    if not fit_may_cure(pair, broken):
        return ""
    clearance = float(pair.printing.printer.tooth_clearance)
    return (f"; the play of the printer's {clearance:g} mm tooth clearance costs ripple: a fit to its band "
            "draws less (`wheelstep gears --fit auto`, or `fit: auto` in the printer profile's band "
            "section), and says the tooth count it then needs")


def undercut_checked(build: Callable, design, verify: Callable | None):
    """``build()``; an undercut refusal (a DesignError with ``undercut`` options) is raised as
    :func:`verified_undercut` says it: with the remedies ``verify`` built within the bounds
    (without ``verify``, a remedy's own try, as it is)."""
    try:
        return build()
    except DesignError as err:
        if not getattr(err, "undercut", None) or verify is None:     # None: a remedy's own try
            raise
        raise verified_undercut(err, design, verify) from None


def refused_try(options: dict, err: DesignError) -> str:
    """What a remedy's try (``options``) refused with ``err`` gave, as a refusal lists it: the
    rule's own option said too when the try does not set it (a thin tooth is the count's, a
    socket the smaller shoe cannot hold is the socket depth's)."""
    rule = "" if err.param in options else f"--{err.param.replace('_', '-')} = {err.shown_value}: "
    return f"{as_flags(options)} is refused: {rule}{err.cause}"


def no_remedy(tried: list[str]) -> str:
    """A refusal's words for no remedy found, with what each try gave (none tried: none said)."""
    return f"no remedy found ({'; '.join(tried)})" if tried else "no remedy found"


def verified_undercut(err: DesignError, design, verify: Callable,
                      bounds: MeshBounds = MeshBounds()) -> DesignError:
    """The undercut refusal ``err`` of ``design`` (its ``undercut``: the options at which the
    rack stops undercutting) with those remedies offered only once a build with them is within
    the bounds, each followed as a bounds refusal's remedy is (the tooth count that clears the
    undercut can still mesh outside the bounds: z 20 -> use --z 21)."""
    offered, tried, failed = [], [], []
    for option in err.undercut:
        remedy, why, candidates = verified_remedy(design, option, verify, bounds)
        failed.extend(candidates)
        if remedy:
            offered.append(remedy)
        else:
            tried.extend(why)
    offered = _undominated(offered)
    cause = err.limit.split("; use pinion z")[0]
    unchecked = err.limit[len(cause):]
    advice = "; " + (" or ".join(f"use {as_flags(remedy)}" for remedy in offered) if offered
                     else change_advice(design, no_remedy(tried)))
    # the inputs sharing the blame state the rule with the checked remedies too
    alternatives = {name: (value, text.replace(unchecked, advice)) for name, (value, text) in err.alternatives.items()}
    checked = DesignError(err.param, err.value, cause + advice, alternatives)
    checked.remedy = offered[0] if offered else {}
    checked.remedies = offered
    checked.tried = failed    # the remedies built and found wanting, for a batch file's keys
    return checked


def _undominated(offered: list[dict]) -> list[dict]:
    """``offered`` without a remedy that changes all another one does and more, with no fewer
    teeth (a pressure angle needing z 52 besides, when z 38 alone does it)."""
    def dominated(remedy: dict, other: dict) -> bool:
        changes = lambda options: set(options) - {"backlash"}    # the play follows the count
        return ("z" in remedy and "z" in other and changes(other) < changes(remedy)
                and other["z"] <= remedy["z"])

    return [remedy for remedy in offered if not any(dominated(remedy, other) for other in offered)]


def change_advice(design, found: str) -> str:
    """A refusal's advice when no remedy was found (``found`` says so): what must change, the
    law (a CSV law replaces the crank mechanism, whose options are then refused) or the size."""
    law = "the law (--law-csv)" if design.law_csv is not None else "the mechanism (--a, --b, --c)"
    return f"{found}: change {law} or {_size_option(design)}"


def _size_option(design) -> str:
    """What sizes the pair: the module when the user gave one (the centre distance is then
    solved for it and cannot be given with it), else the centre distance."""
    return "the centre distance" if design.module is None else "--module"


def _broken(record: dict, bounds: MeshBounds) -> list[str]:
    """The bounds ``record`` breaks, interference left out (refused elsewhere)."""
    return [text for text in bound_violations(record, bounds) if "interfere" not in text]


def _remedy_of(pair, design, record: dict, bounds: MeshBounds, built: bool = True,
               teeth: bool = False) -> dict:
    """The options (name -> value) the figures of ``record`` point to for ``design``; ``built``:
    the remedy is built and checked before it is offered (else, a sweep's row, said as a try);
    ``teeth``: a ripple is remedied by more teeth, not less play (less play was tried)."""
    broken, remedy = _broken(record, bounds), {}
    periods = pair.generated.law.pinion_periods
    if any("F'i" in text or "f'i" in text for text in broken):
        # the deviations fall about as 1/z^2 (measured): the nearest count that should do, not
        # one many times the design's, where a build still outside is followed from its own
        # figures; a try said unbuilt keeps the surer 1/z count
        remedy["z"] = teeth_remedy(record, design.z, periods, bounds, squared=built)
        if remedy["z"] > MAX_TEETH and not _changed_settings(design):
            remedy["z"] = periods * (MAX_TEETH // periods)     # nothing to set back: that count to try
    if any("ripple" in text for text in broken):
        remedy.update(_ripple_remedy(pair, design, record, remedy, bounds, teeth))
    return _within_the_tooth_limit(design, remedy)


def _play_first(design, remedy: dict) -> dict:
    """``remedy``, or when it adds teeth to a design whose backlash the user set above the
    design's own (whose play costs the figures too), that backlash alone first: the tries
    that follow add teeth only if it does not do."""
    from wheelstep_cli.parts.gear_laws import own_backlash

    if "z" not in remedy or design.backlash is None:
        return remedy
    own = round(own_backlash(design), 3)
    return {"backlash": own} if design.backlash > own else remedy


def verified_remedy(design, remedy: dict, verify: Callable, bounds: MeshBounds, known: list[dict] = (),
                    measured: dict | None = None) -> tuple[dict, list[str], list[dict]]:
    """(the first remedy whose build is within the bounds, or {}; what each failed try gave;
    the failed remedies, ``known`` ones first: remedies an earlier search found wanting, not
    built again). Each try follows from the last one's figures (or from its refusal's own
    remedy); a try that leads back to the design as it is, or to a remedy already tried, or
    beyond the tooth limit ends the search. A ripple that a try of less play alone hardly
    lowered (from the try before, or from ``measured``, the design's own meshing record) is
    followed with more teeth. REMEDY_TRIES tries, besides the mounting
    at the rolling distance and the one a module the user gave outgrew the printer with (the
    same remedy then keeps the size asked for)."""
    tried, candidate, failed, sized, shrink = [], dict(remedy), list(known), False, 1.0
    # mounting the pair where its pitch curves roll is no try of the teeth: those follow it
    mounting = "install_distance" in remedy
    before: tuple[dict, dict | None] = ({}, measured)     # the last try and its record
    while len(tried) - sized - mounting < REMEDY_TRIES:
        if sized:       # undercut options and followed remedies too
            candidate = sized_remedy(design, candidate, shrink)
        if (all(getattr(design, name) == value for name, value in candidate.items())
                or candidate in failed or candidate.get("z", 0) > MAX_TEETH):
            break
        trial = design.model_copy(update=candidate)
        try:
            pair, record = verify(trial)
        except DesignError as err:
            tried.append(refused_try(candidate, err))
            failed.append(candidate)
            if getattr(err, "beyond_printer", None) and design.module is not None:
                if not sized and sized_remedy(design, candidate) != candidate:
                    sized = True    # the module given outgrows the printer: the size asked for is kept
                    continue
                if getattr(err, "bed_scale", 1.0) < 1.0:
                    # kept at its size (or sized already) it is still off the bed: drawn smaller
                    sized, shrink = True, shrink * err.bed_scale
                    continue
            # a refusal with a remedy of its own (teeth too thin: fewer teeth) is followed too;
            # with no backlash given, the play chosen for the count it leaves goes with that
            # count (the default follows the new one); a backlash given stays replaced
            own = getattr(err, "remedy", None) or drawn_smaller(trial, err)
            if design.backlash is None and own.get("z", candidate.get("z")) != candidate.get("z"):
                candidate = {name: value for name, value in candidate.items() if name != "backlash"}
            candidate = {**candidate, **own}
            continue
        broken = bound_violations(record, bounds)
        if not broken:
            generated = getattr(pair, "generated", None)
            periods = generated.law.pinion_periods if generated is not None else 2
            return fewest_teeth(design, candidate, failed, periods, verify, bounds), tried, failed
        failed.append(candidate)
        tried.append(f"{as_flags(candidate)} still gives {broken[0]}"
                     + (f" and {len(broken) - 1} more" if len(broken) > 1 else ""))
        teeth = _play_not_the_cause(candidate, record, before, bounds)
        following = _remedy_of(pair, trial, record, bounds, teeth=teeth) if pair.generated is not None else {}
        before, candidate = (candidate, record), {**candidate, **following}
    return {}, tried, failed


def _play_not_the_cause(candidate: dict, record: dict, before: tuple[dict, dict | None],
                        bounds: MeshBounds) -> bool:
    """Whether the try ``candidate`` (meshing ``record``) changed only the backlash from the
    try ``before`` (its remedy and record) and took less than a quarter of the worst flank's
    ripple excess over the bound off: the ripple left is the tooth form's, not the play's."""
    remedy, earlier = before
    if earlier is None or {name for name in candidate if candidate[name] != remedy.get(name)} != {"backlash"}:
        return False
    was, now = worst_ripple(earlier), worst_ripple(record)
    if was is None or now is None or was <= bounds.ripple_pct:
        return False
    return was - now < 0.25 * (was - bounds.ripple_pct)


def _within_the_tooth_limit(design, remedy: dict) -> dict:
    """``remedy``, or, when its tooth count is more than a design may have, the generator
    settings the design changed set back to their defaults (those teeth are the cause);
    empty when it changed none (no remedy of teeth or settings)."""
    if remedy.get("z", 0) <= MAX_TEETH:
        return remedy
    # the defaults' teeth with the design's own backlash: the backlash part of the remedy was
    # sized for the other tooth count
    return _changed_settings(design)


def _other_ways(pair, design, record: dict, verify: Callable, bounds: MeshBounds,
                so_far: tuple[list[str], list[dict]]) -> tuple[dict, list[str], list[dict]]:
    """(remedy or {}, every try, every failed remedy) once the remedies the figures point to
    (``so_far``: their tries and candidates) were built and found wanting, each followed as
    :func:`verified_remedy` follows a remedy: for a ripple alone, fewer teeth (a pitch too
    small for the flanks' micron deviations, :func:`ripple_teeth_remedy`); then the generator
    settings ``design`` changes at their defaults, count and backlash kept (a small pressure
    angle or short addendum can break the bounds at every tooth count)."""
    tried, candidates = so_far
    broken = _broken(record, bounds)
    ways = [_changed_settings(design)]
    if any("ripple" in text for text in broken) and not any("F'i" in text or "f'i" in text
                                                             for text in broken):
        z = ripple_teeth_remedy(record, design.z, pair.generated.law.pinion_periods, bounds)
        ways.insert(0, sized_remedy(design, {"z": z}) if z < design.z else {})
    for way in ways:
        if way and way not in candidates:
            remedy, more, candidates = verified_remedy(design, way, verify, bounds, candidates)
            tried = tried + more
            if remedy:
                return remedy, tried, candidates
    return {}, tried, candidates


def _changed_settings(design) -> dict:
    """The generator settings ``design`` changes, at their defaults (name -> value)."""
    from wheelstep_cli.config.specs import GearPairSpec

    fields = GearPairSpec.model_fields
    return {name: fields[name].default for name in GENERATOR_SETTINGS
            if getattr(design, name) != fields[name].default}


#: Largest difference (mm) of the installed and rolling distances taken as none (a float's
#: round trip through %g metadata).
OPENING_TOLERANCE = 1e-9


def opening_phrase(pair) -> str:
    """What mounting ``pair`` off its rolling distance does, for a refusal (mm)."""
    side = "farther" if pair.opening > 0 else "closer"
    return (f"mounted at {pair.mounted_distance:g} mm, {abs(pair.opening):g} mm {side} than the "
            f"pitch curves roll ({pair.design_distance:g} mm), where they do not follow the law")


def _ripple_remedy(pair, design, record: dict, remedy: dict, bounds: MeshBounds,
                   teeth: bool = False) -> dict:
    """Options (name -> value) that should bring the ripple within the bound. Other teeth
    ripple otherwise: with a new --z the backlash is the default for that design (what its
    play may cost, gears.generation.play), else it is scaled from the measured play, unless
    ``teeth`` (less play was tried and the ripple stayed: two periods more teeth, the backlash
    the design sets kept where the new count's default is larger)."""
    from wheelstep_cli.parts.gear_laws import design_backlash

    law = pair.generated.law
    # a backlash the design sets is printed with the printer's tooth clearance added on top;
    # the default backlash follows the tooth count, the clearance taken out of it
    clearance = float(pair.printing.printer.tooth_clearance) if pair.printing is not None else 0.0
    if "z" not in remedy and not teeth:
        backlash = backlash_remedy(law, record, pair.spec.backlash_mm, bounds) - clearance
        # teeth need some play: the printer's clearance gives it, else the design's own; a
        # backlash no smaller than the design's is no remedy (the ripple is not the play's)
        if (0.0 if clearance > 0 else 0.02) <= round(backlash, 3) < design_backlash(design):
            return {"backlash": round(backlash, 3)}
    z = remedy.get("z", design.z + 2 * law.pinion_periods)
    teeth = {} if "z" in remedy else {"z": z}
    if design.backlash is None:
        return teeth
    default = design_backlash(design.model_copy(update={"z": z, "backlash": None}))
    backlash = round(min(design.backlash_mm, default), 3)    # the one given, kept: no option to set
    return {**teeth, "backlash": backlash} if backlash != round(design.backlash_mm, 3) else teeth
