"""Both generated gears of a pair, and what was found about them (SPEC §9).

The pinion is cut by the rack rolling on its pitch curve (see ``rack``, ``pinion``),
checked for undercut and pointed teeth (``limits``), and its outline as written
carves the wheel moving along the exact law (``wheel``). Angles in radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.gears.generation.envelope import PolarGrid, outline_from_radii, polyline_envelope
from wheelstep_cli.gears.generation.limits import (GearBody, ToppingLimits, min_convex_radius,
                                                   top_or_refuse, undercut_limit, undercut_options,
                                                   undercut_remedy)
from wheelstep_cli.gears.generation.outline import blank_radii, simplify_outline
from wheelstep_cli.gears.generation.pinion import pinion_by_rack, round_tips, topped_outline
from wheelstep_cli.gears.generation.rack import RackCutter, RackRolling
from wheelstep_cli.gears.generation.settings import CORNER_MODES, GenerationSettings
from wheelstep_cli.gears.generation.wheel import (Carving, backlash_split, carve_by_pinion,
                                                  head_on_relief, level_space_ridges, notch_weight)
from wheelstep_cli.gears.pitch_curves import PitchCurves, pitch_curves
from wheelstep_cli.gears.transmission import TransmissionLaw
from wheelstep_cli.geometry.planar import segmentize_ring


@dataclass(frozen=True)
class GeneratedPair:
    """Generated outlines and what was found about them.

    ``pinion_outline`` / ``wheel_outline``: closed CCW (N, 2) arrays in mm (own frames,
    pitch point for carrier angle phi at pinion body angle +theta(phi), wheel -phi).
    ``center_distance``: the distance (mm) the pair was generated to roll at.
    """

    law: TransmissionLaw
    curves: PitchCurves
    cutter: RackCutter
    pinion_teeth: int
    wheel_teeth: int
    module: float
    pitch: float
    corner: str
    pinion_outline: np.ndarray
    wheel_outline: np.ndarray
    pinion_radii: np.ndarray
    wheel_radii: np.ndarray
    pinion_grid: PolarGrid
    wheel_grid: PolarGrid
    undercut_limit: float
    min_curvature_radius: float
    pinion_tip_land: float
    wheel_tip_land: float
    topping: dict
    center_distance: float
    play: float = 0.0      # rad of wheel angle each side (angular backlash mode)
    #: The settings as applied: those given at the pair's module (GenerationSettings.at_module).
    settings: GenerationSettings = field(default_factory=GenerationSettings)


@dataclass(frozen=True)
class _Job:
    """What every stage of one generation shares (mm, rad)."""

    law: TransmissionLaw
    curves: PitchCurves
    cutter: RackCutter
    pinion_teeth: int
    per_period: int          # pinion teeth per law period
    pitch: float             # mm along the pitch curves
    settings: GenerationSettings
    strict: bool

    @property
    def module(self) -> float:
        return self.pitch / np.pi

    @property
    def limits(self) -> ToppingLimits:
        return ToppingLimits(self.settings.min_tip_land, self.settings.max_topping, self.module, self.strict)


@dataclass(frozen=True)
class _GearCut:
    """One gear as cut: outline (N, 2) mm, radii per ray, rays, (teeth topped, drop mm), land mm."""

    outline: np.ndarray
    radii: np.ndarray
    grid: PolarGrid
    topping: tuple[int, float]
    land: float
    play: float = 0.0


def generate_pair(law: TransmissionLaw, pinion_teeth: int, cutter: RackCutter, *, corner: str = "space",
                  settings: GenerationSettings = GenerationSettings(), strict: bool = True,
                  center_distance: float) -> GeneratedPair:
    """Generate both gears for ``law`` with ``pinion_teeth`` teeth on the pinion, the pitch
    curves rolling at ``center_distance`` mm.

    ``corner``: a pinion tooth ``"space"`` or ``"tooth"`` centred on each pitch-curve
    corner; ``settings``: how finely and with which corrections; ``strict``: refuse
    undercut and pointed teeth (False: generate anyway). Raises DesignError (with the remedy)
    for undercut or pointed teeth and for tooth counts that do not divide the law's periods.
    """
    job = _job(law, pinion_teeth, cutter, corner, settings, strict, center_distance)
    curves, per_period = job.curves, job.per_period
    limit, rho_min = _check_undercut(job)
    # teeth too thin at the tip (the few next to a pitch-curve corner) are topped to the
    # land floor when that costs at most max_topping x m of height; otherwise refuse. The
    # pinion is topped before it carves the wheel, so the wheel is conjugate to the pinion
    # as written (a tip topped after carving leaves the wheel without contact there).
    pinion = _cut_pinion(job, corner)
    wheel = _cut_wheel(job, pinion.outline, center_distance)
    return GeneratedPair(
        law=law, curves=curves, cutter=cutter, pinion_teeth=pinion_teeth,
        wheel_teeth=per_period * law.wheel_periods, module=job.module, pitch=job.pitch, corner=corner,
        pinion_outline=pinion.outline, wheel_outline=wheel.outline,
        pinion_radii=pinion.radii, wheel_radii=wheel.radii,
        pinion_grid=pinion.grid, wheel_grid=wheel.grid,
        undercut_limit=limit, min_curvature_radius=rho_min,
        pinion_tip_land=pinion.land, wheel_tip_land=wheel.land,
        topping={"pinion": pinion.topping, "wheel": wheel.topping},
        center_distance=float(center_distance), play=wheel.play, settings=job.settings)


def generate_pinion(law: TransmissionLaw, pinion_teeth: int, cutter: RackCutter, *, corner: str = "space",
                    settings: GenerationSettings = GenerationSettings(),
                    center_distance: float) -> tuple[np.ndarray, float]:
    """The pinion alone as :func:`generate_pair` cuts it (outline (N, 2) mm, module mm),
    without carving the wheel: for checks of the pinion's teeth (a printer's tip land)."""
    job = _job(law, pinion_teeth, cutter, corner, settings, True, center_distance)
    _check_undercut(job)
    return _cut_pinion(job, corner).outline, job.module


def require_whole_periods(law: TransmissionLaw, pinion_teeth: int, most: int | None = None) -> None:
    """Refuse (DesignError on z) a pinion tooth count that is not a whole number of teeth in
    each period of ``law`` (at least 6 in all), naming the nearest counts that are (up to
    ``most`` teeth when given) as its ``remedies``."""
    periods = law.pinion_periods
    if pinion_teeth >= 6 and pinion_teeth % periods == 0:
        return
    # teeth per period: the two round the count's, at least 6 teeth, at most ``most``
    least, top = -(-6 // periods), (most if most is not None else pinion_teeth + periods) // periods
    fits = sorted({min(max(least, k), top) for k in (pinion_teeth // periods, -(-pinion_teeth // periods))})
    remedies = [{"z": k * periods} for k in fits]
    error = DesignError("z", pinion_teeth, f"must be a multiple of {periods} (law periods per pinion "
                        "turn) and >= 6; " + " or ".join(f"use --z {r['z']}" for r in remedies))
    error.remedy, error.remedies = remedies[0], remedies
    raise error


def _job(law: TransmissionLaw, pinion_teeth: int, cutter: RackCutter, corner: str,
         settings: GenerationSettings, strict: bool, center_distance: float) -> _Job:
    """What the stages of one generation share; refuses a corner mode or tooth count that
    cannot be generated."""
    require(corner in CORNER_MODES, "corner", corner, "must be 'space' or 'tooth'")
    require_whole_periods(law, pinion_teeth)
    per_period = pinion_teeth // law.pinion_periods
    curves = pitch_curves(law, center_distance)
    pitch = curves.period_arc / per_period
    return _Job(law, curves, cutter, pinion_teeth, per_period, pitch, settings.at_module(pitch / np.pi),
                strict)


def _check_undercut(job: _Job) -> tuple[float, float]:
    """(undercut limit, smallest convex pitch-curve radius) in mm; refuses undercut when strict.

    The rack undercuts where the convex pitch curve bends tighter than the limit.
    """
    module = job.module
    limit = undercut_limit(job.cutter, module)
    rho_min = min_convex_radius(job.law, job.curves)
    if rho_min < limit and job.strict:
        error = DesignError("z", job.pinion_teeth,
                            f"the rack undercuts the pinion: pitch-curve radius of curvature "
                            f"{rho_min:.2f} mm < {limit:.2f} mm at module {module:.3f} mm; "
                            + undercut_remedy(job.cutter, module, rho_min, job.per_period,
                                              job.law.pinion_periods))
        # the same remedies as options, for a caller that checks them before it offers them
        error.undercut = undercut_options(job.cutter, module, rho_min, job.per_period, job.law.pinion_periods)
        raise error
    return limit, rho_min


def contact_window(curves: PitchCurves, distance: float, addendum: float) -> float:
    """Body angle (rad) either side of the pitch point within which a pinion point can meet
    the wheel: where the pinion's tip curve crosses the wheel's (their local pitch radii
    plus the ``addendum`` mm, centres ``distance`` mm apart), the largest over the period.

    A pinion tip corner touches the wheel that far off the line of centres just after a
    handover; a fixed number of pitches is too narrow for small pitches (issue 13).
    """
    r_tip = np.hypot(*curves.pinion.T) + addendum
    w_tip = distance - np.hypot(*curves.pinion.T) + addendum
    cos = (r_tip ** 2 + distance ** 2 - w_tip ** 2) / (2.0 * r_tip * distance)
    return float(np.arccos(np.clip(cos, -1.0, 1.0)).max())


def _require_no_gaps(radii: np.ndarray, pinion_teeth: int) -> None:
    """Refuse a ray map (mm) some ray of which no cut crossed."""
    require(np.all(np.isfinite(radii)), "z", pinion_teeth,
            "the generated outline has gaps (pitch curve too tight for the cutter); more teeth "
            "(--z) make the cutter smaller")


def _cut_pinion(job: _Job, corner: str) -> _GearCut:
    """The pinion cut by the rack, topped, tips rounded: the outline as written (and carving)."""
    law, curves, s = job.law, job.curves, job.settings
    theta0 = float(law.pinion_angle(curves.phi[0]))
    grid = PolarGrid(theta0, law.theta_period, job.per_period * s.rays_per_tooth)
    offset = job.pitch / 2.0 if corner == "space" else 0.0   # arc of the first pinion tooth centre
    # no offset fan at the pinion's corners: a chord there relieves the corner teeth's tips
    blank = blank_radii(curves.pinion, grid, job.cutter.addendum * job.module, fan=False)
    rolling = RackRolling(curves.pinion, curves.arc, job.pitch, offset + job.pitch / 2.0,
                          job.per_period * s.poses_per_tooth, 4 * s.poses_per_tooth, law.theta_period,
                          law.pinion_periods, s.tilt, s.pivot)
    exact = pinion_by_rack(rolling, job.cutter, job.module)
    # its ray map (farthest crossing: the tips, also of teeth leaning over a neighbour's space),
    # taken on short segments: the map interpolates a segment's radius linearly in angle, and
    # the outline's flanks are long straight segments (the rack's flanks are)
    dense = segmentize_ring(exact, s.ray_map_segment)
    cut = polyline_envelope(grid, np.vstack([dense, dense[:1]])[None], nearest=False)
    cut_radii = np.minimum(blank, cut)
    _require_no_gaps(cut_radii, job.pinion_teeth)
    radii, topping, land = top_or_refuse(GearBody("pinion", grid, curves.pinion, blank), cut_radii,
                                         job.cutter, job.limits)
    # the outline as written (tips rounded; slivers and spikes a boolean can leave removed)
    # carves the wheel
    rounded = round_tips(exact, s.tip_round * job.module, s.tip_round_thin)
    outline = simplify_outline(topped_outline(rounded, grid, radii, cut_radii, law.pinion_periods),
                               s.pinion_tolerance)
    return _GearCut(outline, radii, grid, topping, land)


def relief_angle(pressure_angle: float) -> float:
    """Largest angle (rad) between a wheel surface's normal and its radius that the tip
    clearance relief lowers: half the angle a flank's normal makes with the radius at the
    pitch point (90 deg less the ``pressure_angle``, rad). A drive contact's normal passes
    through the pitch point, so it leans about that far or farther (the profile angle grows
    toward the tips; the handover contacts of the default pair lean 43-49 deg)."""
    return 0.5 * (0.5 * np.pi - pressure_angle)


def _relief_region(job: _Job, grid: PolarGrid, radii: np.ndarray, pitch: np.ndarray) -> np.ndarray:
    """Per wheel ray (0..1): how much of the tip clearance relief applies.

    Carved by the pinion's tips, the wheel's space bottoms end microns below them, sloping
    along a non-circular space, so every head-on surface below the wheel's pitch curve is
    lowered. At a handover notch also above it: the pinion's corner teeth and corner space
    are cut by the pivoting rack, not by the blank, and the wheel blank's concave offset
    stands the addendum / cos(half the turn) above the notch, as deep as the pinion's
    corner space, so tips met spaces there on the line of centres with no clearance.
    """
    law, curves = job.law, job.curves
    below = (radii < pitch).astype(float)
    if not law.corners:
        return below
    # the pitch point for carrier angle phi sits at the wheel's body angle -phi
    reach = job.settings.corner_relief_pitches * job.pitch / float(np.min(np.hypot(*curves.wheel.T)))
    return np.maximum(below, notch_weight(grid, -np.asarray(law.corners, dtype=float), reach))


def _cut_wheel(job: _Job, pinion_outline: np.ndarray, distance: float) -> _GearCut:
    """The wheel carved by ``pinion_outline`` rolling at ``distance`` mm, widened by the play, topped."""
    law, curves, s = job.law, job.curves, job.settings
    grid = PolarGrid(-float(curves.phi[-1]), law.phi_period, job.per_period * 2 * s.wheel_rays_per_tooth)
    blank = blank_radii(curves.wheel, grid, job.cutter.addendum * job.module)
    clearance, play = backlash_split(job.cutter, curves.wheel, s)
    # a pitch beyond where the tip curves cross: the crossing is found at the pitch point's
    # own radii, the tip that meets the wheel there sits up to a pitch away
    pitch_angle = job.pitch / float(np.min(np.hypot(*curves.pinion.T)))
    window = max(s.window_pitches * pitch_angle,
                 contact_window(curves, distance, job.cutter.addendum * job.module) + pitch_angle)
    # the lead only pays where the law has handover corners (the hub speed factor kinks there);
    # a smooth law keeps the play split evenly, as ordinary spur gears are thinned
    lead = s.lead if (law.corners or law.blended_corners) else 0.0
    carving = Carving(distance, clearance, job.per_period * s.carve_poses_per_tooth, window,
                      float(blank.max()), play, lead, s.path_run, s.carve_segment)
    radii = np.minimum(blank, carve_by_pinion(law, pinion_outline, grid, carving))
    if s.mount_tolerance > 0:
        # carved again rolling that much closer: mounted closer by up to it, the pair still
        # clears (the tips' paths and the corner teeth), at the cost of a little backlash
        closer = replace(carving, distance=distance - s.mount_tolerance)
        radii = np.minimum(radii, carve_by_pinion(law, pinion_outline, grid, closer))
    _require_no_gaps(radii, job.pinion_teeth)
    pitch = blank_radii(curves.wheel, grid, 1e-6)     # the wheel's pitch curve, mm per ray
    radii = head_on_relief(radii, grid, _relief_region(job, grid, radii, pitch),
                           job.cutter.clearance * job.module, relief_angle(job.cutter.pressure_angle))
    radii = level_space_ridges(radii, pitch)
    radii, topping, land = top_or_refuse(GearBody("wheel", grid, curves.wheel, blank), radii,
                                         job.cutter, job.limits)
    return _GearCut(outline_from_radii(grid, radii, law.wheel_periods), radii, grid, topping, land, play)
