"""Generated (conjugate) teeth for a non-circular pair (SPEC §9).

The pinion is cut by a straight-sided rack (pressure angle alpha, tip fillet)
whose pitch line rolls without slip on the pinion's pitch curve; at a pitch-curve
corner the rack pivots about the corner point through part of the turn from each
side (PIVOT), leaving a ridge in the corner space that hands the drive over sooner.
The pinion's tip corners are rounded (a sharp corner drives as a point), its pointed
corner teeth topped, and that outline, as written, cuts the wheel moving along the
exact law ("rotate and carve"): the wheel's outline is the blank minus the union of
the pinion's poses and of the paths its outline points run between poses, in the
wheel frame, so the pair is conjugate by construction, including the concave notch
at each shoe handover.

Backlash: the pinion's teeth are thinned by j_n/2 (the rack tooth is thickened),
and the wheel is carved by the pinion dilated by j_n/2 along its normals, so the
total normal backlash at the design centre distance is j_n and both gears' teeth
are thinned by j_n/2. Opening the centre distance adds about 2 dL sin(alpha).

Angles in radians, lengths in mm.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from wheelstep_cli.errors import DesignError, require
from wheelstep_cli.gears.generation.envelope import (PolarGrid, miter_offset, offset_polyline, outline_from_radii,
                                         polyline_envelope)
from wheelstep_cli.gears.pitch_curves import PitchCurves, pitch_curves
from wheelstep_cli.gears.transmission import TransmissionLaw
from wheelstep_cli.gears.threads import thread_map

#: Smallest tip land (mm) before a tooth counts as pointed (same floor as the paper method).
MIN_TIP_LAND = 0.1
#: Normal clearance (mm) added to the angular backlash so discretisation scallops never touch
#: (with the carving paths and rounded tips, ripple at 1536 poses: 0.002 interferes by microns,
#: 0.004 -> 2.35 %, 0.005 -> 1.59, 0.006 -> 1.52, 0.007 -> 1.58, 0.008 -> 1.63, 0.01 -> 1.92 %).
SCALLOP_CLEARANCE = 0.006
#: Rack-tooth tilt towards the radius, as a fraction of the pitch curve's normal-to-radius angle
#: (chosen by measurement: 0 -> 11.5 % hub speed ripple, 0.3 -> 11.4, 0.6 -> 4.9, 1.0 -> 8.9; with
#: the carving paths and rounded tips, clearance 0.005: 0.5 -> 8.39, 0.6 -> 1.59, 0.7 -> 3.05 %).
DEFAULT_TILT = 0.6
#: Where the angular play goes: 0 splits it (drive TE = -play), +-1 puts it all on the coast side.
#: Mostly on the coast side: the drive contact then lags the law by little, so the hub speed factor
#: is not read at a lagged angle (a 0.8 % step at each corner with the play split); 0.8 keeps 2'
#: of the play on the drive side as margin (pivot 0.2: LEAD 0 -> 3.0 %, 0.8 -> 2.36, 0.9 -> 2.40,
#: 1.0 -> 2.50 %, no interference in any; with the carving paths and rounded tips: 0.8 -> 1.52,
#: 0.9 -> 1.43 %).
LEAD = 0.8
#: Radius (x module) the pinion's tip corners are rounded to (tip relief; 0: sharp). A sharp
#: tip corner touches the wheel as a point, and near the handover corners such contacts rode
#: over the flanks with sawtooth speed errors; a rounded tip carves, and then drives on, a
#: smooth flank (with the carving paths: 0 -> 2.51 %, 0.05 -> 1.90, 0.08 -> 2.08, 0.1 -> 1.92,
#: 0.12 -> 1.94, 0.15 -> 2.56, 0.2 -> 3.10 % ripple at 1536 poses, clearance 0.01).
TIP_ROUND = 0.1
#: Pinion outline taken into each carving pose: this many pitches either side of the pitch point.
WINDOW_PITCHES = 1.8
#: Most tooth height (x module) that may be topped off a pointed tooth before the design is refused.
MAX_TOPPING = 0.35
CORNER_MODES = ("space", "tooth")
#: Douglas-Peucker tolerance (mm) of the pinion outline that carves the wheel and is written.
PINION_TOLERANCE = 0.0005
#: Douglas-Peucker tolerance (mm) of the wheel's ray-map outline as written.
WHEEL_TOLERANCE = 0.0005
#: Fraction of the corner turn the rack pivots through from each side (>= 0.5: the whole turn).
#: A partial pivot leaves a ridge in the corner space, so the wheel tooth there takes over
#: the drive before the previous tooth tip lets go (measured: 1.0 -> 4.66 %, 0.4 -> 4.66,
#: 0.3 -> 4.32, 0.2 -> 3.98, 0.15 -> 3.93, 0.1 -> 4.09, 0 -> 4.45 % hub speed ripple with 160 rays
#: and the play split; with 480 rays and LEAD 0.8: 0.15 -> 2.91, 0.2 -> 2.36 %; with the carving
#: paths and rounded tips, clearance 0.005: 0.1 -> 7.95, 0.15 -> 1.59, 0.2 -> 1.59, 0.3 -> 4.87 %).
PIVOT = 0.2
#: Pinion poses per tooth pitch that carve the wheel. Between poses the carving also follows
#: each outline point's path (see :func:`carve_by_pinion`), so 24 carve as well as 48 did.
CARVE_POSES_PER_TOOTH = 24
#: Wheel ray-map density: the wheel's ray map holds 2 x this many rays per wheel tooth (the
#: same rule as ``rays_per_tooth``). Near the notch the wheel flanks run almost along the rays,
#: and the chords between rays stand proud of the carved flank by microns: a pinion tip then
#: rides over them (480 rays: 4 um humps in TE; 960, 1440, 1920: gone, the same ripple).
WHEEL_RAYS_PER_TOOTH = 960
#: Carving poses whose outline points are followed as one path (see :func:`carve_by_pinion`).
PATH_RUN = 64


@dataclass(frozen=True)
class RackCutter:
    """Basic rack: pressure angle (rad); addendum, dedendum, tip fillet radius as multiples of m.

    ``addendum`` is the gears' tooth height above the pitch curve, ``dedendum`` the
    depth below it (the cutter's tooth height), ``fillet`` the cutter's tip radius.
    ``backlash`` is the total normal backlash j_n (mm) of the pair.
    """

    pressure_angle: float = np.radians(20.0)
    addendum: float = 1.0
    dedendum: float = 1.25
    fillet: float = 0.25
    backlash: float = 0.5

    def __post_init__(self) -> None:
        require(np.radians(5.0) <= self.pressure_angle <= np.radians(35.0), "pressure-angle",
                float(np.degrees(self.pressure_angle)), "must be 5..35 deg")
        require(0.3 <= self.addendum <= 2.0, "addendum", self.addendum, "must be 0.3..2 x module")
        require(self.addendum < self.dedendum <= 2.5, "dedendum", self.dedendum,
                f"must be > addendum ({self.addendum:g}) and <= 2.5 x module (tip clearance)")
        require(0.0 <= self.fillet <= 0.45, "fillet", self.fillet, "must be 0..0.45 x module")
        require(np.isfinite(self.backlash) and self.backlash >= 0, "backlash", self.backlash,
                "must be >= 0 mm")


@dataclass(frozen=True)
class GeneratedPair:
    """Generated outlines and what was found about them.

    ``pinion_outline`` / ``wheel_outline``: closed CCW (N, 2) arrays in mm (own frames,
    pitch point for carrier angle phi at pinion body angle +theta(phi), wheel -phi).
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
    play: float = 0.0      # rad of wheel angle each side (angular backlash mode)


def rack_profile(cutter: RackCutter, module: float, pitch: float, teeth: int,
                 flank_points: int = 60) -> np.ndarray:
    """Cutter polyline (K, 2) in rack coordinates (x along the pitch line, y outward, mm).

    ``teeth`` cutter teeth centred at x = (j - (teeth-1)/2) p; each cuts one space
    of the gear, reaching y = -dedendum m with tip fillets; between teeth the
    polyline runs at a height the gear blank never reaches.
    """
    a = cutter.pressure_angle
    tan_a, cos_a, sin_a = np.tan(a), np.cos(a), np.sin(a)
    h_f = cutter.dedendum * module
    rho = cutter.fillet * module
    # cutter tooth half thickness at the pitch line: p/4 plus the pinion's thinning j_n/4 (normal)
    half = pitch / 4.0 + cutter.backlash / (4.0 * cos_a)
    top = min(cutter.addendum * module + 0.15 * module, (pitch / 2.0 - half) / tan_a - 1e-3)
    if top <= cutter.addendum * module:
        land = 2.0 * (pitch / 2.0 - half - cutter.addendum * module * tan_a)
        raise DesignError("addendum", cutter.addendum,
                          f"the teeth come to a point (the rack's tooth spaces close below the tip "
                          f"line, tip land {land:.3f} mm at module {module:.3f} mm); use a smaller "
                          "addendum, a smaller pressure angle or more teeth (--z)")
    yc = -h_f + rho
    xc = half + (yc * sin_a - rho) / cos_a                 # right fillet centre
    require(xc >= 0.0, "fillet", cutter.fillet, "too large: the cutter tip has no flat land")
    # right half of one cutter tooth, from the tip centre out to the top
    tip = np.column_stack([np.linspace(0.0, xc, 4, endpoint=False), np.full(4, -h_f)])
    arc_t = np.linspace(-np.pi / 2.0, -a, 10)
    fillet = np.column_stack([xc + rho * np.cos(arc_t), yc + rho * np.sin(arc_t)])
    y = np.linspace(yc - rho * sin_a, top, flank_points)[1:]
    flank = np.column_stack([half + y * tan_a, y])
    right = np.vstack([tip, fillet, flank, [[pitch / 2.0, top]]])
    tooth = np.vstack([right[::-1] * [-1.0, 1.0], right[1:]])   # left top -> tip -> right top
    shifts = (np.arange(teeth) - (teeth - 1) / 2.0) * pitch
    rack = (tooth[None, :, :] + np.column_stack([shifts, np.zeros(teeth)])[:, None, :])
    rack = rack[:, :-1].reshape(-1, 2)
    return np.vstack([rack, tooth[-1:] + [shifts[-1], 0.0]])


def _pivot_fractions(count: int) -> np.ndarray:
    """Fractions of the corner turn the pivoting rack takes: [0, PIVOT] and [1 - PIVOT, 1]."""
    f = np.linspace(0.0, 1.0, count)
    return f[(f <= PIVOT + 1e-12) | (f >= 1.0 - PIVOT - 1e-12)]


def _curve_frames(points: np.ndarray, arc: np.ndarray, s: np.ndarray, outward_sign: float):
    """Point, unit tangent and outward unit normal at arc positions s on a sampled curve."""
    x = np.interp(s, arc, points[:, 0])
    y = np.interp(s, arc, points[:, 1])
    seg = np.diff(points, axis=0)
    seg /= np.hypot(seg[:, 0], seg[:, 1])[:, None]
    idx = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(seg) - 1)
    tangent = seg[idx]
    normal = outward_sign * np.column_stack([tangent[:, 1], -tangent[:, 0]])
    return np.column_stack([x, y]), tangent, normal


def _outward_sign(points: np.ndarray) -> float:
    """+1 when the right-hand normal of the polyline points away from the origin."""
    seg = np.diff(points, axis=0)
    right = np.column_stack([seg[:, 1], -seg[:, 0]])
    return 1.0 if np.sum(right * points[:-1]) > 0 else -1.0


def radial_tilt(curve: np.ndarray, arc: np.ndarray):
    """Angle mu(s) (rad) between the pitch-curve normal and the radius vector, as a function of arc.

    Tilting a rack tooth by -mu turns its axis from the pitch-curve normal to the
    radius: both flanks then meet the direction of motion at the pressure angle.
    """
    seg = np.diff(curve, axis=0)
    mid = 0.5 * (curve[1:] + curve[:-1])
    radial = mid / np.hypot(mid[:, 0], mid[:, 1])[:, None]
    cross = radial[:, 0] * seg[:, 1] - radial[:, 1] * seg[:, 0]
    mu = np.arctan2(np.sum(radial * seg, axis=1), cross)
    s_mid = 0.5 * (arc[1:] + arc[:-1])
    total = arc[-1]
    return lambda s: np.interp(np.mod(s, total), s_mid, mu)


def _place_rack(origin, tangent, normal, rack, tooth_x, rel_shift, tilt_of_arc, arc_at_contact):
    """Rack points in the gear frame for poses (P,) : each rack tooth tilted about its pitch point.

    ``tooth_x``: per rack point, its tooth's centre x in the template; ``rel_shift``:
    per pose, the template's x offset; ``tilt_of_arc``: tilt (rad) of a tooth centred
    at an arc position (None: no tilt); ``arc_at_contact``: per pose, the contact arc.
    """
    rx = rack[None, :, 0] + rel_shift[:, None]
    ry = np.broadcast_to(rack[None, :, 1], rx.shape)
    if tilt_of_arc is not None:
        centre = tooth_x[None, :] + rel_shift[:, None]
        tau = tilt_of_arc(arc_at_contact[:, None] + centre)
        dx = rx - centre
        c, s = np.cos(tau), np.sin(tau)
        rx, ry = centre + c * dx - s * ry, s * dx + c * ry
    return origin[:, None, :] + rx[..., None] * tangent[:, None, :] + ry[..., None] * normal[:, None, :]


def _rack_poses(curve: np.ndarray, arc: np.ndarray, rack: np.ndarray, tooth_x: np.ndarray,
                rack_center: float, pitch: float, poses: int, corner_poses: int,
                period_angle: float, tilt: float) -> list[np.ndarray]:
    """Rack points (mm, gear frame) in every cutting pose over one period of ``curve``.

    The first array holds the ``poses`` rolling poses; where the period ends in a
    corner (the tangent jumps) a second holds the pivot poses about the corner point.
    ``tooth_x`` is each rack point's tooth centre along the rack (mm).
    """
    sign = _outward_sign(curve)
    mu = radial_tilt(curve, arc)
    tilt_fn = (lambda a: -tilt * mu(a)) if tilt else None
    s = (np.arange(poses) + 0.5) * arc[-1] / poses
    origin, tangent, normal = _curve_frames(curve, arc, s, sign)
    shift = np.mod(rack_center - s + pitch / 2.0, pitch) - pitch / 2.0
    worlds = [_place_rack(origin, tangent, normal, rack, tooth_x, shift, tilt_fn, s)]
    # the tangent arriving at the start corner: the period's end tangent, rotated back one period
    c, sn = np.cos(-period_angle), np.sin(-period_angle)
    t_end = curve[-1] - curve[-2]
    t_in = np.array([c * t_end[0] - sn * t_end[1], sn * t_end[0] + c * t_end[1]])
    t_out = curve[1] - curve[0]
    turn = np.arctan2(t_in[0] * t_out[1] - t_in[1] * t_out[0], np.dot(t_in, t_out))
    if corner_poses > 0 and abs(turn) > 1e-6:
        angles = np.arctan2(t_in[1], t_in[0]) + turn * _pivot_fractions(corner_poses)
        count = len(angles)
        tangent = np.column_stack([np.cos(angles), np.sin(angles)])
        normal = sign * np.column_stack([tangent[:, 1], -tangent[:, 0]])
        shift = np.full(count, np.mod(rack_center + pitch / 2.0, pitch) - pitch / 2.0)
        origin = np.broadcast_to(curve[0], (count, 2))
        worlds.append(_place_rack(origin, tangent, normal, rack, tooth_x, shift, tilt_fn, np.zeros(count)))
    return worlds


def _topped(outline: np.ndarray, grid: PolarGrid, topped: np.ndarray, before: np.ndarray,
            copies: int) -> np.ndarray:
    """The exact outline cut down to the topped radii (rays a topping lowered; others untouched)."""
    lowered = topped < before - 1e-12
    if not lowered.any():
        return outline
    import shapely

    cap = np.where(lowered, topped, 10.0 * float(before.max()))
    limit = shapely.Polygon(outline_from_radii(grid, cap, copies))
    return _ccw_outline(shapely.Polygon(outline).intersection(limit).buffer(0))


def rack_tooth_polygons(cutter: RackCutter, module: float, pitch: float, teeth: int = 5,
                        flank_points: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Closed cutter teeth in rack coordinates, shape (teeth, K, 2), and their centres x (mm).

    Each tooth runs from its left top over the tip to its right top and closes far
    outside the blank, so a tooth can be tilted about its pitch point on its own.
    """
    one = rack_profile(cutter, module, pitch, 1, flank_points)
    far = one[:, 1].max() + 4.0 * module
    closed = np.vstack([one, [[one[-1, 0], far], [one[0, 0], far]]])
    centres = (np.arange(teeth) - (teeth - 1) / 2.0) * pitch
    return closed[None, :, :] + np.column_stack([centres, np.zeros(teeth)])[:, None, :], centres


def pinion_by_rack(curve: np.ndarray, arc: np.ndarray, cutter: RackCutter, module: float,
                   pitch: float, rack_center: float, poses: int, corner_poses: int,
                   period_angle: float, copies: int, tilt: float) -> np.ndarray:
    """Pinion outline (N, 2, CCW, mm) = blank minus the union of every rack-tooth pose (exact).

    Same kinematics as :func:`cut_by_rolling_rack` (rolling, pivoting at the corner,
    teeth tilted by -tilt mu), but as polygon booleans: teeth that lean over their
    neighbours' spaces keep their true shape, which a polar ray map cannot hold.
    """
    import shapely
    import shapely.affinity

    teeth, centres = rack_tooth_polygons(cutter, module, pitch)
    k = teeth.shape[1]
    flat = teeth.reshape(-1, 2)
    tooth_x = np.repeat(centres, k)
    worlds = _rack_poses(curve, arc, flat, tooth_x, rack_center, pitch, poses, corner_poses,
                         period_angle, tilt)
    polys = np.concatenate([w.reshape(-1, len(centres), k, 2).reshape(-1, k, 2) for w in worlds])
    turn_sign = np.sign(_polar_sweep(curve))
    # one period's cutter region, then its rotated copies (a union of all poses at once costs more)
    region = shapely.union_all(shapely.polygons(polys))
    cutter_region = shapely.union_all([shapely.affinity.rotate(region, a, origin=(0.0, 0.0), use_radians=True)
                                       for a in turn_sign * period_angle * np.arange(copies)])
    body = np.concatenate([curve[:-1] @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
                           for a in turn_sign * period_angle * np.arange(copies)])
    # bevel joins: a chord across each pitch-curve corner relieves the corner teeth's tips
    blank = shapely.Polygon(body).buffer(cutter.addendum * module, join_style="bevel")
    # buffer(0) drops the zero-area slivers booleans can leave where rack poses just touch
    return _ccw_outline(blank.difference(cutter_region).buffer(0))


def round_tips(outline: np.ndarray, radius: float) -> np.ndarray:
    """The outline (N, 2, mm) with its convex corners (tooth tips) rounded to ``radius`` mm.

    An opening (erode, then dilate) changes nothing else. The outline is first thinned
    by a fraction of a micron: a boolean's many collinear points slow the buffers down.
    """
    import shapely

    if radius <= 0:
        return outline
    body = shapely.simplify(shapely.Polygon(outline), 0.0002)
    return _ccw_outline(body.buffer(-radius, quad_segs=8).buffer(radius, quad_segs=8))


def _ccw_outline(polygon) -> np.ndarray:
    """Exterior (N, 2) of a shapely polygon, counter-clockwise; of the largest part if it split."""
    if polygon.geom_type != "Polygon":
        polygon = max(polygon.geoms, key=lambda g: g.area)
    outline = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(outline[:, 0] * np.roll(outline[:, 1], -1) - np.roll(outline[:, 0], -1) * outline[:, 1])
    return outline if area > 0 else outline[::-1]


def blank_radii(curve: np.ndarray, grid: PolarGrid, height: float, fan: bool = True) -> np.ndarray:
    """Farthest crossing per ray of the pitch curve offset outward by ``height`` mm.

    ``curve`` spans one period (grid.period rad of body angle); it is closed over the
    whole turn first so the corners between periods get their offset fans.
    """
    copies = int(round(2.0 * np.pi / grid.period))
    angles = grid.period * np.arange(copies) * np.sign(_polar_sweep(curve))
    c, s = np.cos(angles), np.sin(angles)
    body = curve[:-1]
    full = np.concatenate([np.column_stack([ci * body[:, 0] - si * body[:, 1],
                                            si * body[:, 0] + ci * body[:, 1]]) for ci, si in zip(c, s)])
    if _outward_sign(full) < 0:
        full = full[::-1]
    offset = offset_polyline(full, height, closed=True, fan=fan)
    offset = np.vstack([offset, offset[:1]])                 # close the loop
    return polyline_envelope(grid, offset[None], nearest=False)


def _polar_sweep(curve: np.ndarray) -> float:
    """Signed body angle (rad) a curve sweeps from its first to its last point."""
    return float(np.sum(np.diff(np.unwrap(np.arctan2(curve[:, 1], curve[:, 0])))))


def carve_by_pinion(law: TransmissionLaw, pinion_outline: np.ndarray, wheel_grid: PolarGrid,
                    distance: float, clearance: float, poses: int, window: float,
                    reach: float = np.inf, play: float = 0.0, lead: float = 0.0) -> np.ndarray:
    """Nearest crossing per wheel ray of the pinion moving along the law (one law period).

    ``pinion_outline``: closed CCW outline (mm, pinion frame, ordered by polar angle
    overall), carved with as it is (only split into pieces of at most 0.05 mm). Poses sample the driven angle uniformly (plus the law's corners); at
    each, the outline (dilated by ``clearance`` mm) within ``window`` rad of its pitch
    point is placed in the wheel frame (pinion rotated by -theta at the origin, wheel
    by pi + phi about (distance, 0)). The wheel is carved both by the outline in each
    pose and by the path of each outline point from pose to pose: the poses alone leave
    a scallop between the imprints of a sharp tooth tip, the paths alone one between
    neighbouring points of a flank. With ``play`` > 0 (rad of wheel angle) the
    carving is widened to the union over wheel turns in [-play, play]: a constant
    angular backlash, so the drive-side TE is constant along the cycle; ``lead``
    (-1..1) shifts that window (+1: all play on the coast side).
    """
    import shapely

    dense = np.asarray(shapely.segmentize(shapely.LinearRing(pinion_outline), 0.05).coords)[:-1]
    # outline is CCW: its right-hand normal points outward
    dilated = miter_offset(dense, clearance) if clearance > 0 else dense
    n_pts = len(dense)
    angle = np.unwrap(np.arctan2(dense[:, 1], dense[:, 0]))
    reach_angle = np.maximum.accumulate(angle)
    phi = law.phi_start + law.phi_period * (np.arange(poses) + 0.5) / poses
    if law.corners:
        phi = np.sort(np.append(phi, np.asarray(law.corners)))
    theta = law.pinion_angle(phi)
    local = angle[0] + np.mod(theta - angle[0], 2.0 * np.pi)
    start = np.searchsorted(reach_angle, local - window)
    end = np.searchsorted(reach_angle, local + window)
    # windows wrapping past the outline's start: look them up one turn on
    wrap = local - window < angle[0]
    start[wrap] = np.searchsorted(reach_angle, local[wrap] - window + 2.0 * np.pi) - n_pts
    width = int(np.max(end - start)) + 1

    def carve_run(i0: int) -> np.ndarray:
        # poses in runs of PATH_RUN (each run shares its last pose with the next): the outline
        # in each pose, and every outline point any pose of the run holds followed through it
        run = slice(i0, min(i0 + PATH_RUN, len(phi) - 1) + 1)
        idx = np.mod(start[run, None] + np.arange(width)[None, :], n_pts)
        radii = polyline_envelope(wheel_grid, _in_wheel_frame(dilated[idx], theta[run], phi[run], distance),
                                  reach=reach)
        points = np.arange(int(start[run].min()), int(end[run].max()) + 1)
        path = _in_wheel_frame(dilated[np.mod(points, n_pts)][None], theta[run], phi[run], distance)
        return polyline_envelope(wheel_grid, np.ascontiguousarray(path.transpose(1, 0, 2)), out=radii,
                                 reach=reach)

    radii = functools.reduce(np.minimum, thread_map(carve_run, range(0, len(phi) - 1, PATH_RUN)))
    if play > 0:
        radii = _widen(radii, play / wheel_grid.width, lead)
    return radii


def _in_wheel_frame(points: np.ndarray, theta: np.ndarray, phi: np.ndarray, distance: float) -> np.ndarray:
    """Pinion points (P or 1, K, 2; mm, pinion frame) in the wheel frame at poses (theta, phi) (P,)."""
    c, s = np.cos(-theta), np.sin(-theta)
    wx = c[:, None] * points[..., 0] - s[:, None] * points[..., 1] - distance
    wy = s[:, None] * points[..., 0] + c[:, None] * points[..., 1]
    ang = -(np.pi + phi)
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([c[:, None] * wx - s[:, None] * wy, s[:, None] * wx + c[:, None] * wy], axis=-1)


def _widen(radii: np.ndarray, span: float, lead: float) -> np.ndarray:
    """Periodic sliding minimum over +-span rays (fractional ends interpolated), shifted by lead*span.

    The union of the carving over all wheel turns in [-play, play] is, ray by ray, the
    smallest radius within +-play.
    """
    k = int(np.floor(span))
    if k > 0:
        padded = np.concatenate([radii[-k:], radii, radii[:k]])
        widened = np.lib.stride_tricks.sliding_window_view(padded, 2 * k + 1).min(axis=1)
    else:
        widened = radii
    n = len(radii)
    j = np.arange(n)
    for edge in (-span, span):
        lo = np.floor(j + edge).astype(np.int64)
        t = (j + edge) - lo
        widened = np.minimum(widened, (1 - t) * radii[lo % n] + t * radii[(lo + 1) % n])
    if lead:
        lo = np.floor(j + lead * span).astype(np.int64)
        t = (j + lead * span) - lo
        widened = (1 - t) * widened[lo % n] + t * widened[(lo + 1) % n]
    return widened


def top_pointed_teeth(grid: PolarGrid, radii: np.ndarray, pitch_radii: np.ndarray,
                      blank: np.ndarray, floor: float) -> tuple[np.ndarray, int, float, float]:
    """Top every tooth whose tip land is below ``floor`` mm down to where it is ``floor`` wide.

    Teeth are the runs of rays whose outline lies above the pitch curve. Returns the
    new radii, how many teeth were topped, the largest height removed (mm) and the
    smallest tip land left (mm).
    """
    above = radii > pitch_radii
    if above.all() or not above.any():
        return radii, 0, 0.0, 0.0
    first = int(np.argmin(above))
    order = np.roll(np.arange(len(radii)), -first)
    a = above[order].astype(np.int8)
    edges = np.diff(np.concatenate(([0], a, [0])))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    out = radii.copy()
    topped, worst, thinnest = 0, 0.0, np.inf
    for lo, hi in zip(starts, ends):                       # one iteration per tooth
        rays = order[lo:hi]
        if hi - lo < 3:
            continue                                        # a sliver above the pitch curve, no tooth
        uncut = radii[rays] >= blank[rays] - 1e-9
        land_now = grid.width * float(np.sum(blank[rays][uncut]))
        if land_now >= floor:
            thinnest = min(thinnest, land_now)
            continue
        r = np.sort(radii[rays])[::-1]
        land = np.arange(1, len(r) + 1) * grid.width * r    # land width if cut at r[k]
        k = int(np.argmax(land >= floor)) if np.any(land >= floor) else len(r) - 1
        out[rays] = np.minimum(out[rays], r[k])
        topped += 1
        worst = max(worst, float(r[0] - r[k]))
        thinnest = min(thinnest, float(land[k]))
    return out, topped, worst, thinnest


def curvature_radius(points: np.ndarray) -> np.ndarray:
    """Signed radius of curvature (mm) along a sampled curve; > 0 where convex (seen from outside)."""
    d1 = np.gradient(points, axis=0)
    d2 = np.gradient(d1, axis=0)
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    speed = np.hypot(d1[:, 0], d1[:, 1])
    orient = 1.0 if np.sum(points[:-1, 0] * points[1:, 1] - points[1:, 0] * points[:-1, 1]) > 0 else -1.0
    with np.errstate(divide="ignore"):
        return orient * speed**3 / cross


def undercut_limit(cutter: RackCutter, module: float) -> float:
    """Smallest convex pitch-curve radius of curvature (mm) a rack cuts without undercut."""
    a = cutter.pressure_angle
    # the cutter's addendum h_a0 is the gears' dedendum
    return module * (cutter.dedendum - cutter.fillet * (1.0 - np.sin(a))) / np.sin(a) ** 2


def _undercut_remedy(cutter: RackCutter, module: float, rho: float, teeth_per_period: int,
                     pinion_periods: int) -> str:
    """Remedy text: the tooth count and pressure angle at which the rack stops undercutting."""
    a = cutter.pressure_angle
    per_m = (cutter.dedendum - cutter.fillet * (1.0 - np.sin(a))) / np.sin(a) ** 2
    module_max = rho / per_m
    z_min = pinion_periods * int(np.ceil(teeth_per_period * module / module_max))
    lo, hi = a, np.radians(35.0)
    f = lambda x: (cutter.dedendum - cutter.fillet * (1 - np.sin(x))) / np.sin(x) ** 2 * module - rho
    if f(hi) > 0:
        angle_text = "no pressure angle up to 35 deg helps"
    else:
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
        angle_text = f"pressure angle >= {np.degrees(hi):.1f} deg"
    return (f"use module <= {module_max:.3f} mm (pinion z >= {z_min}) or {angle_text}")


def generate_pair(law: TransmissionLaw, pinion_teeth: int, cutter: RackCutter, center_distance: float,
                  corner: str = "space",
                  poses_per_tooth: int = 48, rays_per_tooth: int = 480,
                  strict: bool = True, tilt: float = DEFAULT_TILT,
                  backlash_mode: str = "angular", carve_poses_per_tooth: int | None = None,
                  wheel_rays_per_tooth: int | None = None) -> GeneratedPair:
    """Generate both gears for ``law`` with ``pinion_teeth`` teeth on the pinion, the pitch
    curves rolling at ``center_distance`` mm.

    Raises DesignError (with the remedy) for undercut or pointed teeth and for tooth
    counts that do not divide the law's periods.
    """
    require(corner in CORNER_MODES, "corner", corner, "must be 'space' or 'tooth'")
    periods = law.pinion_periods
    require(pinion_teeth >= 6 and pinion_teeth % periods == 0, "z", pinion_teeth,
            f"must be a multiple of {periods} (law periods per pinion turn) and >= 6")
    per_period = pinion_teeth // periods
    wheel_teeth = per_period * law.wheel_periods
    curves = pitch_curves(law, center_distance)
    pitch = curves.period_arc / per_period
    module = pitch / np.pi
    h_a = cutter.addendum * module

    # undercut: the rack undercuts where the convex pitch curve bends tighter than the limit
    limit = undercut_limit(cutter, module)
    rho = curvature_radius(curves.pinion)
    # corners are cut by the pivoting rack, and so are blended corners: leave them out
    keep = np.ones(len(rho), dtype=bool)
    keep[:2] = keep[-2:] = False
    for smoothed in law.blended_corners:
        d = np.mod(curves.phi - smoothed + law.phi_period / 2.0, law.phi_period) - law.phi_period / 2.0
        keep &= np.abs(d) > 1.5 * law.blend_half_width
    rho = rho[keep]
    convex = rho[rho > 0]
    rho_min = float(convex.min()) if len(convex) else float("inf")
    if rho_min < limit and strict:
        raise DesignError("z", pinion_teeth,
                          f"the rack undercuts the pinion: pitch-curve radius of curvature "
                          f"{rho_min:.2f} mm < {limit:.2f} mm at module {module:.3f} mm; "
                          + _undercut_remedy(cutter, module, rho_min, per_period, periods))

    theta0 = float(law.pinion_angle(curves.phi[0]))
    pinion_grid = PolarGrid(theta0, law.theta_period, per_period * rays_per_tooth)
    offset = pitch / 2.0 if corner == "space" else 0.0   # arc of the first pinion tooth centre
    # no offset fan at the pinion's corners: a chord there relieves the corner teeth's tips
    pinion_blank = blank_radii(curves.pinion, pinion_grid, h_a, fan=False)
    pinion_exact = pinion_by_rack(curves.pinion, curves.arc, cutter, module, pitch, offset + pitch / 2.0,
                                  per_period * poses_per_tooth, 4 * poses_per_tooth, law.theta_period,
                                  periods, tilt)
    # its ray map (farthest crossing: the tips, also of teeth leaning over a neighbour's space)
    cut = polyline_envelope(pinion_grid, np.vstack([pinion_exact, pinion_exact[:1]])[None], nearest=False)
    cut_radii = np.minimum(pinion_blank, cut)

    # teeth too thin at the tip (the few next to a pitch-curve corner) are topped to the
    # land floor when that costs at most MAX_TOPPING x m of height; otherwise refuse. The
    # pinion is topped before it carves the wheel, so the wheel is conjugate to the pinion
    # as written (a tip topped after carving leaves the wheel without contact there).
    require(np.all(np.isfinite(cut_radii)), "z", pinion_teeth,
            "the generated outline has gaps (pitch curve too tight for the cutter)")
    topping, lands = {}, {}
    pinion_radii, topping["pinion"], lands["pinion"] = _top_or_refuse(
        "pinion", pinion_grid, curves.pinion, cut_radii, pinion_blank, cutter, module, strict)
    # the outline as written (tips rounded; slivers and spikes a boolean can leave removed)
    # carves the wheel
    rounded = round_tips(pinion_exact, TIP_ROUND * module)
    pinion_outline = simplify_outline(_topped(rounded, pinion_grid, pinion_radii, cut_radii, periods),
                                      PINION_TOLERANCE)

    wheel_rays = per_period * 2 * (wheel_rays_per_tooth or WHEEL_RAYS_PER_TOOTH)
    wheel_grid = PolarGrid(-float(curves.phi[-1]), law.phi_period, wheel_rays)
    wheel_blank = blank_radii(curves.wheel, wheel_grid, h_a)
    # backlash: a constant angular play of the wheel (TE constant along the cycle) plus a thin
    # normal clearance that keeps discretisation scallops from touching
    if backlash_mode == "angular":
        clearance = min(cutter.backlash / 2.0, SCALLOP_CLEARANCE)
        mean_rh = float(np.mean(np.hypot(*curves.wheel.T)))
        play = (cutter.backlash / 2.0 - clearance) / (mean_rh * np.cos(cutter.pressure_angle))
    else:
        clearance, play = cutter.backlash / 2.0, 0.0
    window = WINDOW_PITCHES * pitch / float(np.min(np.hypot(*curves.pinion.T)))
    # the lead only pays where the law has handover corners (the hub speed factor kinks there);
    # a smooth law keeps the play split evenly, as ordinary spur gears are thinned
    lead = LEAD if (law.corners or law.blended_corners) else 0.0
    carved = carve_by_pinion(law, pinion_outline, wheel_grid, center_distance, clearance,
                             per_period * (carve_poses_per_tooth or CARVE_POSES_PER_TOOTH), window,
                             float(wheel_blank.max()), play, lead)
    wheel_radii = np.minimum(wheel_blank, carved)
    require(np.all(np.isfinite(wheel_radii)), "z", pinion_teeth,
            "the generated outline has gaps (pitch curve too tight for the cutter)")

    wheel_radii, topping["wheel"], lands["wheel"] = _top_or_refuse(
        "wheel", wheel_grid, curves.wheel, wheel_radii, wheel_blank, cutter, module, strict)
    return GeneratedPair(
        law=law, curves=curves, cutter=cutter, pinion_teeth=pinion_teeth, wheel_teeth=wheel_teeth,
        module=module, pitch=pitch, corner=corner,
        pinion_outline=pinion_outline,
        wheel_outline=outline_from_radii(wheel_grid, wheel_radii, law.wheel_periods),
        pinion_radii=pinion_radii, wheel_radii=wheel_radii,
        pinion_grid=pinion_grid, wheel_grid=wheel_grid,
        undercut_limit=limit, min_curvature_radius=rho_min,
        pinion_tip_land=lands["pinion"], wheel_tip_land=lands["wheel"], topping=topping, play=play)


def _top_or_refuse(name: str, grid: PolarGrid, curve: np.ndarray, radii: np.ndarray,
                   blank: np.ndarray, cutter: RackCutter, module: float, strict: bool):
    """Top the gear's pointed teeth (see :func:`top_pointed_teeth`), or refuse when that costs
    more than MAX_TOPPING x module: (new radii, (teeth topped, largest drop mm), thinnest land mm)."""
    pitch_r = polyline_envelope(grid, curve[None], nearest=False)
    new, count, drop, land = top_pointed_teeth(grid, radii, pitch_r, blank, MIN_TIP_LAND)
    if drop > MAX_TOPPING * module and strict:
        raise DesignError("addendum", cutter.addendum,
                          f"the {name} teeth come to a point (a {MIN_TIP_LAND} mm tip land needs "
                          f"{drop:.2f} mm off the tip, > {MAX_TOPPING} x module {module:.3f} mm); "
                          "use a smaller addendum, a smaller pressure angle or more teeth (--z)")
    return new, (count, drop), land


def simplify_outline(outline: np.ndarray, tolerance: float = 0.001) -> np.ndarray:
    """Drop outline points within ``tolerance`` mm of the polyline (Douglas-Peucker) and spikes.

    A spike is a vertex where the outline doubles back on itself (a zero-width sliver a
    boolean can leave); a few vectorised passes remove nested ones.
    """
    import shapely

    ring = shapely.simplify(shapely.LinearRing(outline), tolerance, preserve_topology=True)
    pts = np.asarray(ring.coords)[:-1]
    for _ in range(8):
        d_in = pts - np.roll(pts, 1, axis=0)
        d_out = np.roll(pts, -1, axis=0) - pts
        norm = np.hypot(d_in[:, 0], d_in[:, 1]) * np.hypot(d_out[:, 0], d_out[:, 1])
        cos = np.sum(d_in * d_out, axis=1) / np.maximum(norm, 1e-300)
        spike = (cos < -0.95) | (norm < 1e-18)
        if not spike.any():
            break
        spike &= ~np.roll(spike, 1)          # never drop two neighbours in one pass
        pts = pts[~spike]
    return pts
