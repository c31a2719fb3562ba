"""Resolution of a part's parameters: command line (or batch overrides) over the design
profile's part section over its mechanism section over the spec's defaults.

The one place where the CLI's options, a batch entry and a design profile meet.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ValidationError

from wheelstep_cli.config.problem_search import every_problem, gathered, tied_keys
from wheelstep_cli.config.schema import InvalidInput, build, design_errors
from wheelstep_cli.config.specs import GearPairSpec, ShoeSpec, strut_contradiction
from wheelstep_cli.errors import DesignError, offered_remedies

STRUT = ("c", "r_min")
#: What sets the crank law of a gear pair, which a law CSV replaces.
CRANK_LAW = ("a", "b", "c", "r_min", "turns")
#: Where generated teeth roll and are mounted, which a --module sets instead (mm).
DISTANCES = ("center_distance", "install_distance")


def _generated(values: dict[str, Any], spec: type[BaseModel]) -> bool:
    """Whether ``values`` of a gear-pair spec give generated teeth (the default)."""
    if "teeth" not in spec.model_fields:
        return False
    teeth = values.get("teeth", spec.model_fields["teeth"].default)
    return getattr(teeth, "value", teeth) == "generated"


def spec_values(spec: type[BaseModel], section: str, profile, top: dict[str, Any],
                on_command_line: bool = True) -> dict[str, Any]:
    """The values of a ``spec`` from the layers, higher layers winning (None: not given).
    ``on_command_line``: ``top`` holds options (else a batch entry's overrides, its design
    a profile), as refusals name them.

    A strut given in a layer (as ``c`` or ``r_min``) replaces the strut of the layers below,
    in either form. A spec without ``r_min`` (the gear pair) gets c = R_min - a + 4b.
    """
    layers = [top] if profile is None else [profile.values("mechanism"), profile.values(section), top]
    fields = spec.model_fields
    merged: dict[str, Any] = {}
    resized = False         # a layer above the strut's gives a or b
    for layer in layers:
        given = {k: v for k, v in layer.items() if v is not None}
        if any(k in given for k in STRUT):
            for key in STRUT:
                merged.pop(key, None)
            resized = False
            if "c" in given and "r_min" in given:
                # one layer's two forms must agree (a contradiction is not settled by a rule of either)
                lengths = {"a": fields["a"].default, "b": fields["b"].default, **merged, **given}
                if why := strut_contradiction(lengths["a"], lengths["b"], given["c"], given["r_min"]):
                    raise DesignError("r_min", given["r_min"], why)
        elif "a" in given or "b" in given:
            resized = True
        if "module" in given and _generated({**merged, **given}, spec):
            # generated teeth roll where the module fits (SPEC §9) and are mounted there:
            # a lower layer's distances (a preset's) give way, as a strut does
            for key in DISTANCES:
                merged.pop(key, None)
        merged.update(given)
    if resized and "c" in merged:
        # a strut given both ways below a layer that resizes the cranks: c is kept (as when given alone)
        merged.pop("r_min", None)
    if "law_csv" in fields and merged.get("law_csv") is not None:
        if top.get("law_csv") is not None:
            _no_crank_law(top, "--law-csv" if on_command_line else "the entry's law_csv")
        else:
            _no_crank_law(top, f"the {'profile' if on_command_line else 'design'}'s {section}.law_csv")
    if "r_min" in merged and "r_min" not in fields:
        r_min = merged.pop("r_min")
        if "c" not in merged:
            merged["c"] = strut_length(merged.get("a", fields["a"].default), merged.get("b", fields["b"].default),
                                       r_min)
    return {k: v for k, v in merged.items() if k in fields}


def _no_crank_law(top: dict[str, Any], law_csv: str) -> None:
    """Refuse what sets the crank law given (on the command line, or as a batch entry's
    overrides) with a law CSV, which replaces that law: it would do nothing. A profile's
    mechanism stays (it is shared with the other parts). ``law_csv``: where the CSV was given,
    as the refusal names it."""
    for key in CRANK_LAW:
        if top.get(key) is not None:
            raise DesignError(key, top[key], f"sets the crank law, which {law_csv} replaces (the "
                                             "pair follows the law read from the CSV)")


def strut_length(a: float, b: float, r_min: float) -> float:
    """c from the smallest sole curvature radius (the mechanism's sizing rule), mm."""
    from wheelstep_cli.mechanism.crank import CrankMechanism

    return CrankMechanism.from_r_min(a, b, r_min).c


def spec_problems(spec: type[BaseModel], values: dict[str, Any]):
    """(spec, []) or (None, every problem) of building ``spec`` from ``values``."""
    try:
        return spec.model_validate(values), []
    except ValidationError as err:
        return None, design_errors(spec, err)


def updated(spec: BaseModel, **changes: Any) -> BaseModel:
    """The spec with some values changed, checked again (DesignError naming the first problem)."""
    return build(type(spec), {**spec.model_dump(), **changes})


def _profile(name: str | None):
    from wheelstep_cli.config.profiles import load_design_profile

    return load_design_profile(name) if name else None


def gear_pair_spec(profile, **cli) -> GearPairSpec:
    """Resolve a GearPairSpec: command line over profile over built-in defaults.

    Raises InvalidInput (every problem of the profile, with ``file:line``) or DesignError
    (a value that breaks a rule, named by its parameter).
    """
    return _resolved(GearPairSpec, "gears", _loaded(profile, GearPairSpec, "gears", cli, "mechanism"), cli,
                     "mechanism")


#: What the paper method's tables (``pitch``, ``teeth``) read of a profile's gear pair; the rest
#: (the generator's settings, a law CSV, bore, hub, face) shapes only the part, so a profile
#: tuned for generated teeth still gives its tables.
PAPER_TABLE_KEYS = ("z", "turns", "center_distance", "install_distance", "module", "backlash")


class _TableValues:
    """A design profile seen by the paper tables: its mechanism, and of its gear pair only
    :data:`PAPER_TABLE_KEYS`."""

    def __init__(self, profile):
        self.profile = profile

    def values(self, section: str) -> dict[str, Any]:
        found = self.profile.values(section)
        return found if section == "mechanism" else {k: v for k, v in found.items() if k in PAPER_TABLE_KEYS}


def _crank_law_only(loaded, profile) -> None:
    """Refuse a design profile whose gear pair follows a law CSV: the paper's sectors and teeth
    are the crank law's, and a table of them would not be its pitch curves at all."""
    value = loaded.values("gears").get("law_csv")
    if value:
        err = DesignError("law_csv", value, "replaces the crank law: the paper tables (pitch, teeth) are "
                                            "the crank law's sectors (SPEC §4, §5); `gears` writes and "
                                            "reports the teeth generated for this law")
        located = in_profile(err, loaded, "gears")
        raise located if located is not None else DesignError(
            "profile", profile, f"gives gears.law_csv = {value}: {err.limit}")


def _left_out(loaded) -> str | None:
    """What the paper tables leave out of the design profile ``loaded`` that a reader could
    expect in them: the blend its generated teeth's law is smoothed over (the paper method
    follows the crank law itself); None when there is nothing to say."""
    blend = None if loaded is None else loaded.values("gears").get("blend")
    if not blend:
        return None
    return (f"the profile's gears.blend = {blend:g} deg smooths the law that generated teeth follow "
            "(gears, kinematics); the paper tables are the crank law's own sectors")


def paper_table_spec(profile, **cli) -> tuple[GearPairSpec, str | None]:
    """The spec of the paper method's tables (SPEC §4, §5): command line over the profile's
    mechanism and :data:`PAPER_TABLE_KEYS`, paper teeth at their design distance L_p (the
    one given, else the installed distance less the paper's opening). The tables do not
    mount the pair, so it is taken as mounted at L_p and without a bore. With it, a note of
    what of the profile the tables leave out (None: nothing)."""
    from wheelstep_cli.config.specs import paper_design_distance

    loaded = _profile(profile)
    if loaded is not None:
        _crank_law_only(loaded, profile)

    def tables(seen, top: dict[str, Any]) -> GearPairSpec:
        values = spec_values(GearPairSpec, "gears", None if seen is None else _TableValues(seen),
                             {**top, "teeth": "paper", "bore": 0.0})
        # the profile's values were checked when it was read, the command line's are numbers
        center = paper_design_distance(values.get("center_distance"), values.get("install_distance"))
        spec = _named_for(top, build, GearPairSpec, {**values, "center_distance": center,
                                                     "install_distance": center}, profile=(seen, "gears"))
        _named_for(top, spec.mechanism, profile=(seen, "gears"))
        return spec

    try:
        spec = tables(loaded, cli)
    except DesignError as first:
        raise every_problem(tables, loaded, cli, first) from None
    return spec, _left_out(loaded)


def shoe_spec(profile, **cli) -> ShoeSpec:
    """Resolve a ShoeSpec: command line over profile (``shoe:``, ``mechanism:``) over defaults."""
    return _resolved(ShoeSpec, "shoe", _loaded(profile, ShoeSpec, "shoe", cli, "design"), cli, "design")


def _loaded(name: str | None, spec_type: type[BaseModel], section: str, cli: dict[str, Any], check: str):
    """The design profile ``name`` read (None: none given). A profile that cannot be read is
    refused with the other problems of the run: for a value out of its own bounds, the rules
    the profile's other values and the options break (resolved with the profile read without
    the keys at fault, those not tied to them); for a file that cannot be read at all, the
    options' own rules, those no value of the profile could mend (each of options alone)."""
    try:
        return _profile(name)
    except DesignError as unread:
        partial = getattr(unread, "partial", None)
        try:
            _resolved(spec_type, section, partial, cli, check)
        except DesignError as err:
            given = {k for k, v in cli.items() if v is not None}
            out = {issue.what.rpartition(".")[2] for issue in getattr(unread, "issues", ())}
            own = [e for e in (err, *getattr(err, "also", ()))
                   if (not tied_keys(e) & out if partial is not None else tied_keys(e) <= given)]
            if own:     # the file's lines together, in its order; the options' after them
                raise gathered([unread, *own]) from None
        raise


def _checked(spec_type: type[BaseModel], values: dict[str, Any], check: str):
    """The spec built from ``values`` and its ``check`` method run (the mechanism sized, so an
    impossible one is caught now)."""
    spec = build(spec_type, values)
    getattr(spec, check)()
    return spec


def _resolved(spec_type: type[BaseModel], section: str, loaded, cli: dict[str, Any], check: str):
    """The spec of the command line ``cli`` over the design profile ``loaded`` (None: none)
    over the defaults, checked (:func:`_checked`); the rules the command line and the user's
    profile break are said all at once (:func:`~wheelstep_cli.config.problem_search.every_problem`)."""
    def resolved(seen, top: dict[str, Any]):
        return _named_for(top, lambda: _checked(spec_type, spec_values(spec_type, section, seen, top), check),
                          profile=(seen, section))

    try:
        return resolved(loaded, cli)
    except DesignError as first:
        raise every_problem(resolved, loaded, cli, first) from None


def _named_for(cli: dict[str, Any], step, *args, profile: tuple | None = None):
    """``step(*args)``; a rule it breaks is named by a parameter the user gave, where the rule
    can be stated for one (the mechanism is sized here, so an impossible one is caught now):
    on the command line, else in the design profile (``profile`` = (the loaded profile or
    None, the part's section)), at the value's ``file:line``."""
    try:
        return step(*args)
    except InvalidInput:
        raise
    except DesignError as err:
        given = [k for k, v in cli.items() if v is not None]
        named = err.for_given(given)
        if named.param.replace("-", "_") not in given and profile is not None and profile[0] is not None:
            located = in_profile(named, *profile)
            if located is not None:
                named = located
        # what the rule is stated for, which the error said for one of them no longer lists
        named.tied = {name.replace("-", "_") for name in (err.param, *err.alternatives)}
        raise named from None


def _profile_keys(loaded, section: str) -> list[str]:
    """The keys a profile gives its part, the part's section first, then its mechanism (but
    what sets the crank law when the part follows a law CSV instead)."""
    part = loaded.values(section)
    mechanism = [k for k in loaded.values("mechanism") if not (part.get("law_csv") and k in CRANK_LAW)]
    return [*part, *mechanism]


def in_profile(err: DesignError, loaded, section: str) -> InvalidInput | None:
    """``err`` said at the line of the design profile ``loaded`` that gives its parameter, or
    one its rule is also stated for, in the part's ``section`` or the mechanism (None: the
    profile gives none of them, or it is a shipped preset, whose values the command line
    overrides: the error names the flag)."""
    if loaded.shipped:
        return None
    from wheelstep_cli.config.names import as_flags, as_keys, in_file_words
    from wheelstep_cli.config.schema import Issue, show

    # the rule's own parameter when the profile gives it, else the first it is stated for that
    # the profile gives: its own statements (a dedendum's limit) come before the inputs tied on
    own, keys = err.param.replace("-", "_"), _profile_keys(loaded, section)
    named = [own, *(name.replace("-", "_") for name in err.alternatives)]
    key = next((k for k in named if k in keys), None)
    if key is None:
        return None
    err = err.for_given([key])
    remedies = offered_remedies(err)    # those of the statement the line makes
    limit = err.limit
    for remedy in remedies:
        # a remedy as the profile's keys (z: 74, backlash: 0.239), not as flags
        limit = limit.replace(f"use {as_flags(remedy)}", f"use {as_keys(remedy)}")
    for part in (section, "mechanism"):
        given = loaded.values(part)
        # only where the profile's value is the one the rule met (a command line's --r-min
        # replaces the profile's c, and a table's distance is derived from the profile's)
        if key in given and given[key] == err.value:
            located = InvalidInput([Issue(loaded.where(part, key), f"{part}.{key}",
                                          f"= {show(err.value)}: {in_file_words(limit, batch=False)}")])
            located.remedy, located.remedies = (remedies[0] if remedies else {}), remedies
            return located
    return None

