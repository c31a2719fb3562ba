"""Tuning values of the tooth generator, as one frozen value passed explicitly.

Change one with ``dataclasses.replace(GenerationSettings(), tilt=0.3)``. Its lengths (mm)
are those of a pair of module :attr:`GenerationSettings.length_module` or more; a smaller
module takes them in proportion (:meth:`GenerationSettings.at_module`). How each
default was chosen (the hub speed ripple measured for its neighbours) is recorded in
benchmarks/results.md, "Generation settings: how the defaults were chosen".
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from wheelstep_cli.errors import require

#: Pitch-curve corner treatments: a pinion tooth space or a tooth centred on each corner.
CORNER_MODES = ("space", "tooth")
#: Backlash modes: a constant angular play of the wheel, or a normal thinning of both flanks.
BACKLASH_MODES = ("angular", "normal")


@dataclass(frozen=True)
class GenerationSettings:
    """How finely and with which corrections the pair is generated (mm, rad, counts)."""

    tilt: float = 0.6
    """Rack-tooth tilt towards the radius, as a fraction (dimensionless) of the pitch curve's
    normal-to-radius angle mu. Both flanks then meet the direction of motion nearer the
    pressure angle; the CLI's ``--tilt``."""

    pivot: float = 0.2
    """Fraction (0..1) of the turn at a pitch-curve corner the rack pivots through from each
    side (>= 0.5: the whole turn). A partial pivot leaves a ridge in the corner space, so the
    wheel tooth there takes over the drive before the previous tooth tip lets go."""

    lead: float = 0.0
    """Where the angular play goes (-1..1): 0 splits it evenly (drive TE = -play), +-1 puts it
    all on the coast side. A flank carrying a wheel play delta reads the hub speed factor
    delta off the law, and its hub speed steps by delta times the jump of f'/f at each
    handover corner (``play``): with both flanks bounded alike, the even split keeps the
    larger of their ripples least (default pair: drive/coast 0.47/1.96 % at 0.8, 1.23/1.21 %
    at 0; benchmarks/results.md, issue 13)."""

    backlash_ripple: float = 0.005
    """Hub speed ripple (fraction) the play may cost each flank when no backlash is given: half
    the 1 % bound, the other half left to the tooth form (0.3-0.7 % measured)."""

    tip_round: float = 0.1
    """Radius (x module) the pinion's tip corners are rounded to (tip relief; 0: sharp). A sharp
    tip corner touches the wheel as a point and rides over the flanks near the handovers; a
    rounded tip carves, and then drives on, a smooth flank."""

    scallop_clearance: float = 0.006
    """Normal clearance (mm) taken from the backlash budget and added to the angular play, so
    the scallops the discrete carving leaves never touch."""

    backlash_mode: str = "angular"
    """``"angular"``: the wheel gets a constant angular play (TE constant along the cycle) plus
    ``scallop_clearance``; ``"normal"``: the wheel is carved by the pinion dilated by j_n/2."""

    min_tip_land: float = 0.1
    """Smallest tip land (mm) before a tooth counts as pointed: the paper method's 0.1 mm floor
    (which its sector teeth keep at every module), in proportion below ``length_module``."""

    max_topping: float = 0.35
    """Most tooth height (x module) that may be topped off a pointed tooth before the design is
    refused."""

    mount_tolerance: float = 0.0
    """The wheel is carved also with the pinion rolling this much closer (mm): mounted up to
    that much closer than designed, the pair still clears (0: carved at the distance only).
    Off by default: the flanks carved closer make the pair's TE at its own distance as bad
    as being mounted that far off (benchmarks/results.md, issue 13)."""

    corner_relief_pitches: float = 1.25
    """Wheel arc (x the tooth pitch, dimensionless) either side of a handover notch whose
    head-on surfaces are lowered by the tip clearance: the corner space and the corner teeth
    either side (the last quarter tapers)."""

    window_pitches: float = 1.8
    """Pinion outline taken into each carving pose: at least this many pitches (dimensionless)
    either side of the pitch point; more where the tip curves cross farther off (plus a
    pitch), as small pitches need (issue 13: z = 60 carved within 1.8 pitches kept 39 um of
    F'i on the drive flank, 5.4 um within 3)."""

    poses_per_tooth: int = 48
    """Rack poses per tooth pitch that cut the pinion (the corner pivot takes 4 x this many)."""

    rays_per_tooth: int = 480
    """Rays per pinion tooth pitch of the pinion's ray map (its radii, topping and lands)."""

    carve_poses_per_tooth: int = 24
    """Pinion poses per tooth pitch that carve the wheel. Between poses the carving also follows
    each outline point's path, so few poses carve as well as many."""

    wheel_rays_per_tooth: int = 960
    """Wheel ray-map density: the ray map holds 2 x this many rays per wheel tooth. Near the notch
    the flanks run almost along the rays, and coarser chords between rays stand proud of the
    carved flank by microns, for a pinion tip to ride over."""

    path_run: int = 64
    """Carving poses whose outline points are followed as one path (a run of poses shares its
    last pose with the next)."""

    carve_segment: float = 0.05
    """Longest piece (mm) the pinion outline is split into for carving: between the outline's
    points, their paths carve the wheel too."""

    ray_map_segment: float = 0.05
    """Longest segment (mm) of the pinion's cut outline when its ray map is taken: the map's
    linear-in-angle interpolation of a segment then stays well within a micron of the line."""

    tip_round_thin: float = 0.0002
    """Douglas-Peucker tolerance (mm) the pinion's cut outline is thinned by before its tips
    are rounded: a boolean's many collinear points slow the buffers down."""

    pinion_tolerance: float = 0.0005
    """Douglas-Peucker tolerance (mm) of the pinion outline that carves the wheel and is written."""

    wheel_tolerance: float = 0.0005
    """Douglas-Peucker tolerance (mm) of the wheel's ray-map outline as written (by the caller)."""

    length_module: float = 2.0
    """Module (mm) down to which the lengths above (scallop clearance, tip land floor, segments,
    Douglas-Peucker tolerances: :attr:`LENGTHS`) hold as given; a smaller module takes them in
    proportion. ``mount_tolerance`` is not among them: it is a mounting distance, the frame's. The bounds on F'i
    and f'i are micrometres, which a larger module needs as finely as this one; the bound on
    the hub speed ripple is relative, which a smaller module needs as finely per tooth: below
    it, a design scaled by s is generated as its pair scaled by s."""

    #: The fields that are lengths (mm) :meth:`at_module` scales.
    LENGTHS = ("scallop_clearance", "min_tip_land", "carve_segment", "ray_map_segment", "tip_round_thin",
               "pinion_tolerance", "wheel_tolerance")

    def at_module(self, module: float) -> "GenerationSettings":
        """These settings for a pair of ``module`` mm: the lengths scaled by module /
        length_module when that is below 1 (see :attr:`length_module`), else unchanged."""
        scale = min(1.0, module / self.length_module)
        if scale >= 1.0:
            return self
        return replace(self, **{name: getattr(self, name) * scale for name in self.LENGTHS})

    def __post_init__(self) -> None:
        require(self.length_module > 0, "length_module", self.length_module, "must be > 0 mm")
        require(self.backlash_mode in BACKLASH_MODES, "backlash_mode", self.backlash_mode,
                "must be 'angular' or 'normal'")
