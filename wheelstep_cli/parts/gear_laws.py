"""The law generated teeth follow, the distance they roll at and their default backlash.

Shared by the gear pair's pipeline (``gear_pair``), the printer compensation (``kinds``)
and the bounds' remedies (``mesh_bounds``). Lengths in mm, angles in radians inside.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from wheelstep_cli.config.specs import GearPairSpec


def generation_law(spec: GearPairSpec):
    """The law the generated teeth follow (crank law or --law-csv) and its blended form."""
    from wheelstep_cli.gears.laws import blended_law

    law = design_law(spec)
    return law, blended_law(law, np.radians(spec.blend))


def kinematics_law(design, turns: int, gears: dict, turns_given: bool):
    """(law, what it is) the gears of a design profile's ``gears`` section (its values) follow
    on ``design`` (a CrankMechanism), for the hub speed over a shoe cycle: the crank law of
    ``turns``, or the section's law CSV (which must repeat within the shoe cycle; --turns,
    ``turns_given``, is refused with it), blended by the section's blend. Law None: the plain
    crank law."""
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.gears.kinematics import require_shoe_cycle_period
    from wheelstep_cli.gears.laws import CrankLaw, blended_law

    law_csv, blend = gears.get("law_csv"), gears.get("blend", 0)
    if law_csv is not None:
        if turns_given:
            raise DesignError("turns", turns, "sets the crank law, which the profile's gears.law_csv replaces "
                                              "(the gears follow the law read from the CSV)")
        from wheelstep_cli.formats.law_csv import read_law_csv

        law = read_law_csv(law_csv)
        require_shoe_cycle_period(law, "law_csv", law_csv)
        what = f"the law of {law_csv}"
    elif blend:
        law, what = CrankLaw(design, turns), "the crank law"
    else:
        return None, "the crank law"
    if blend:
        law, what = blended_law(law, np.radians(blend)), f"{what} blended over {blend:g} deg"
    return law, what


def require_law_periods(spec: GearPairSpec, law=None) -> None:
    """Refuse (DesignError) generated teeth whose count is no whole number per period of the
    design's law CSV (``law``, when read already), said of --law-csv when z was not given,
    with the nearest counts within the tooth limit (a crank law's periods are the sectors
    rule's, checked with the spec)."""
    from wheelstep_cli.config.specs import MAX_TEETH
    from wheelstep_cli.errors import DesignError
    from wheelstep_cli.gears.generation.pair import require_whole_periods

    if spec.law_csv is None or getattr(spec.teeth, "value", spec.teeth) != "generated":
        return
    try:
        require_whole_periods(law if law is not None else design_law(spec), spec.z, MAX_TEETH)
    except DesignError as err:
        raise err.tied_to({"law_csv": spec.law_csv}) from None


def law_csv_metadata(spec: GearPairSpec) -> dict[str, str]:
    """What a plate keeps of the design's law CSV besides its path: the SHA-256 of its bytes
    (a plate is checked later, maybe elsewhere: the file found then must be the same)."""
    import hashlib

    if spec.law_csv is None:
        return {}
    return {"law_csv_sha256": hashlib.sha256(Path(spec.law_csv).read_bytes()).hexdigest()}


def require_plate_law_csv(spec: GearPairSpec, metadata: dict[str, str], plate: str) -> None:
    """Refuse (DesignError naming the plate's pinion file ``plate``) a plate design whose law
    CSV cannot be read from here, or is not the file the plate was made with (its metadata
    law_csv_sha256, when it has one)."""
    import hashlib

    from wheelstep_cli.errors import DesignError

    if spec.law_csv is None:
        return
    kept = f"its design's law CSV {spec.law_csv!r} (metadata law_csv: the path as given where the plate was made)"
    try:
        data = Path(spec.law_csv).read_bytes()
    except OSError:
        raise DesignError("pinion", plate, f"{kept} cannot be read from here: run where the plate was made, "
                                           "or put the CSV at that path") from None
    digest = metadata.get("law_csv_sha256")
    if digest is not None and hashlib.sha256(data).hexdigest() != digest:
        raise DesignError("pinion", plate, f"{kept} is not the file the plate was made with (its SHA-256 "
                                           "differs from the plate's law_csv_sha256): the law changed since")


def design_law(spec: GearPairSpec):
    """The law the pair is designed for: the design's crank law, or the --law-csv law."""
    from wheelstep_cli.formats.law_csv import read_law_csv

    return read_law_csv(spec.law_csv) if spec.law_csv is not None else spec.law()


def design_backlash(spec: GearPairSpec) -> float:
    """The normal backlash (mm) the pair is designed with: as given, else for generated teeth
    the most whose play keeps each flank's hub speed ripple within the settings' share
    (:func:`generated_backlash`), else 0.25 x module."""
    if spec.backlash is not None or spec.teeth != "generated":
        return spec.backlash_mm
    from wheelstep_cli.gears.generation import GenerationSettings

    _, law = generation_law(spec)
    return generated_backlash(spec, law, rolling_distance(spec, law), GenerationSettings())


def own_backlash(spec: GearPairSpec) -> float:
    """The normal backlash (mm) the design takes when none is given (:func:`design_backlash`)."""
    return design_backlash(spec.model_copy(update={"backlash": None}))


def generated_backlash(spec: GearPairSpec, law, distance: float, settings) -> float:
    """Default normal backlash (mm) of generated teeth rolling at ``distance`` mm on ``law``:
    the play a flank carries steps the hub speed at the law's handover corners
    (gears.generation.play), so it is the most that costs ``settings.backlash_ripple``.

    The cost is taken on the design's own law, not on its --blend form: measured beyond a
    blended law's own ripple (9 % at 10 deg) the play costs almost nothing, so the default
    would jump to 0.25 module (0.52 mm on the source design from 2 deg of blend), and teeth
    thinned by that much lose contact next to the blended corners (a 15 um TE dip at each
    handover, F'i 17 um at z 48 with 10 deg). A blend must not widen the play."""
    from wheelstep_cli.gears.generation.play import default_backlash
    from wheelstep_cli.gears.pitch_curves import pitch_curves

    if spec.blend:
        law = design_law(spec)
    curves = pitch_curves(law, distance)
    module = curves.period_arc / max(1, spec.z // law.pinion_periods) / np.pi
    return default_backlash(law, curves.wheel, np.radians(spec.pressure_angle), settings.backlash_ripple,
                            module)


def rolling_distance(spec: GearPairSpec, law) -> float:
    """The distance (mm) generated teeth roll at (their pitch curves' centre distance): the
    one a given module fits (SPEC §9: the pitch curves' perimeter is proportional to it),
    else --center-distance, else the installed distance (144 when neither is given)."""
    from wheelstep_cli.config.specs import DEFAULT_INSTALL, MAX_DISTANCE, MAX_TEETH, MIN_DISTANCE, MIN_TEETH
    from wheelstep_cli.errors import DesignError, require
    from wheelstep_cli.gears.pitch_curves import center_distance_for_module

    if spec.module is None:
        given = spec.center_distance if spec.center_distance is not None else spec.install_distance
        distance = float(given) if given is not None else DEFAULT_INSTALL
        if law is not None:
            _require_least_module(spec, law, distance)
        return distance
    require(spec.module > 0, "module", spec.module, "must be > 0 mm")
    per_period = max(1, spec.z // law.pinion_periods)
    distance = float(center_distance_for_module(law, per_period, spec.module))
    if not MIN_DISTANCE <= distance <= MAX_DISTANCE:
        # the distance is proportional to the module and to the teeth per period: the bound
        # solved for each, rounded to a value that passes
        bound, word = (MAX_DISTANCE, "<=") if distance > MAX_DISTANCE else (MIN_DISTANCE, ">=")
        ratio = bound / distance
        why = (f"(module and teeth set the centre distance, {distance:.4g} mm, outside "
               f"{MIN_DISTANCE:g}..{MAX_DISTANCE:g} mm)")
        rounding = np.floor if word == "<=" else np.ceil
        module = rounding(100.0 * spec.module * ratio) / 100.0
        periods = law.pinion_periods
        z = int(rounding(per_period * ratio)) * periods
        alternatives = ({"z": (spec.z, f"must be {word} {z} at module {spec.module:g} mm {why}")}
                        if MIN_TEETH <= z <= MAX_TEETH else {})
        raise DesignError("module", spec.module, f"must be {word} {module:g} mm for {spec.z} teeth "
                          f"{why}", alternatives)
    return distance


def _require_least_module(spec: GearPairSpec, law, distance: float) -> None:
    """Refuse (naming the distance given, or the tooth count) generated teeth rolling at
    ``distance`` mm whose module, which the distance sets, is under the least a ``--module``
    may be (MIN_MODULE): the limit given there holds for a distance too."""
    from wheelstep_cli.config.specs import MIN_MODULE, MIN_TEETH
    from wheelstep_cli.errors import DesignError, rounded_up
    from wheelstep_cli.gears.pitch_curves import center_distance_for_module

    per_period = max(1, spec.z // law.pinion_periods)
    least = float(center_distance_for_module(law, per_period, MIN_MODULE))
    if distance >= least:
        return
    module = MIN_MODULE * distance / least
    why = f"gives teeth of module {module:.3f} mm, under the least {MIN_MODULE:g} mm a --module may be"
    z = int(per_period * distance / least) * law.pinion_periods
    named = "center_distance" if spec.center_distance is not None else "install_distance"
    alternatives = {"z": (spec.z, f"with it, {named.replace('_', '-')} = {distance:g} {why}; must be <= {z}")} \
        if z >= MIN_TEETH else {}
    raise DesignError(named, distance, f"{why} at {spec.z} teeth; must be >= {rounded_up(least)} mm",
                      alternatives)


def installed_distance(spec: GearPairSpec, law=None) -> float:
    """The distance (mm) the pair is mounted and checked at: --install-distance, else where
    generated teeth roll (:func:`rolling_distance` on ``law``, the blended generation law
    when None), paper teeth their L_p + 0.5 mm."""
    if spec.teeth != "generated":
        return spec.paper_distances[1]
    if spec.install_distance is not None:
        return float(spec.install_distance)
    if spec.module is None:
        return rolling_distance(spec, None)
    return rolling_distance(spec, law if law is not None else generation_law(spec)[1])


def distance_record(spec: GearPairSpec, law=None) -> dict[str, float]:
    """The design's distances as a part's metadata stores them (mm): the installed one, and
    the rolling (paper: L_p) one unless a module fixes it; a design rebuilt from them is the
    same and a check of the written gears mounts them where they are mounted."""
    if spec.teeth != "generated":
        center, install = spec.paper_distances
        return {"center_distance": center, "install_distance": install}
    install = installed_distance(spec, law)
    if spec.module is not None:
        return {"install_distance": install}
    return {"center_distance": rolling_distance(spec, None), "install_distance": install}
