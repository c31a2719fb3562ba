"""Resolution of a part's parameters: command line over design profile over built-in defaults.

The one place where the CLI's options and a design profile's sections meet.
"""

from __future__ import annotations

from wheelstep_cli.errors import DesignError


def gear_pair_spec(profile, **cli):
    """Resolve a GearPairSpec: command line over profile over built-in defaults."""
    from wheelstep_cli.config.profiles import load_profile, merge_options, profile_section
    from wheelstep_cli.parts.gear_pair import SPEC_KEYS, GearPairSpec

    layers = []
    if profile:
        path, data = load_profile(profile)
        layers.append(profile_section(path, data, "gears", SPEC_KEYS))
        mechanism = profile_section(path, data, "mechanism", ("a", "b", "c", "r_min"))
        if "c" not in mechanism and "r_min" in mechanism:
            a, b = cli.get("a") or mechanism.get("a", 60.0), cli.get("b") or mechanism.get("b", 100.0)
            mechanism["c"] = mechanism["r_min"] - a + 4 * b
        mechanism.pop("r_min", None)
        layers.append(mechanism)
    spec = GearPairSpec(**merge_options(cli, *layers))
    try:
        spec.mechanism()
    except DesignError as err:
        raise err.for_given(k for k, v in cli.items() if v is not None) from None
    return spec


def shoe_spec(profile, **cli):
    """Resolve a ShoeSpec: command line over profile (``shoe:``, ``mechanism:``) over defaults."""
    from wheelstep_cli.config.profiles import load_profile, merge_options, profile_section
    from wheelstep_cli.parts.shoe import SPEC_KEYS, ShoeSpec

    layers = []
    if profile:
        path, data = load_profile(profile)
        part_keys = tuple(k for k in SPEC_KEYS if k not in ("a", "b", "c", "r_min"))
        layers.append(profile_section(path, data, "shoe", part_keys))
        mechanism = profile_section(path, data, "mechanism", ("a", "b", "c", "r_min"))
        if cli.get("c") is not None or cli.get("r_min") is not None:
            # the strut given on the command line replaces the profile's, in either form
            mechanism.pop("c", None)
            mechanism.pop("r_min", None)
        layers.append(mechanism)
    return ShoeSpec(**merge_options(cli, *layers))
