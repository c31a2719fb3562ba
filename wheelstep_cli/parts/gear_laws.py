"""The law generated teeth follow, the distance they roll at and their default backlash.

Shared by the gear pair's pipeline (``gear_pair``), the printer compensation (``kinds``)
and the bounds' remedies (``mesh_bounds``). Lengths in mm, angles in radians inside.
"""

from __future__ import annotations

import numpy as np

from wheelstep_cli.config.specs import GearPairSpec


def generation_law(spec: GearPairSpec):
    """The law the generated teeth follow (crank law or --law-csv) and its blended form."""
    from wheelstep_cli.gears.laws import blended_law

    law = design_law(spec)
    return law, blended_law(law, np.radians(spec.blend))


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


def generated_backlash(spec: GearPairSpec, law, distance: float, settings) -> float:
    """Default normal backlash (mm) of generated teeth rolling at ``distance`` mm on ``law``:
    the play a flank carries steps the hub speed at the law's handover corners
    (gears.generation.play), so it is the most that costs ``settings.backlash_ripple``."""
    from wheelstep_cli.gears.generation.play import default_backlash
    from wheelstep_cli.gears.pitch_curves import pitch_curves

    curves = pitch_curves(law, distance)
    module = curves.period_arc / max(1, spec.z // law.pinion_periods) / np.pi
    return default_backlash(law, curves.wheel, np.radians(spec.pressure_angle), settings.backlash_ripple,
                            module)


def rolling_distance(spec: GearPairSpec, law) -> float:
    """The distance (mm) generated teeth roll and are mounted at: the one a given module
    fits (SPEC §9: the pitch curves' perimeter is proportional to it), else the installed
    distance."""
    from wheelstep_cli.errors import require
    from wheelstep_cli.gears.pitch_curves import center_distance_for_module

    if spec.module is None:
        return float(spec.install_distance)
    require(spec.module > 0, "module", spec.module, "must be > 0 mm")
    per_period = max(1, spec.z // law.pinion_periods)
    return float(center_distance_for_module(law, per_period, spec.module))
