"""The meshing check over one period of a transmission law (SPEC §10).

Angles in radians, lengths in mm.
"""

from __future__ import annotations

import functools
import threading
from dataclasses import replace
from typing import Callable

import numpy as np

from wheelstep_cli.errors import require, rounded_up
from wheelstep_cli.gears.meshing.figures import BAND_HARMONICS, Track, count_teeth, pitch_arc
from wheelstep_cli.gears.meshing.outlines import MeshWindow
from wheelstep_cli.gears.meshing.peaks import PeakPoses, error_um, refine_peaks
from wheelstep_cli.gears.meshing.report import MeshingReport
from wheelstep_cli.gears.meshing.search import Pair, PoseContacts, batch_contacts, prepare
from wheelstep_cli.gears.meshing.settings import MeshingSettings, default_samples
from wheelstep_cli.gears.threads import thread_map
from wheelstep_cli.gears.transmission import TransmissionLaw


def mesh_window(pinion: np.ndarray, wheel: np.ndarray, distance: float,
                settings: MeshingSettings = MeshingSettings()) -> MeshWindow:
    """The mesh window of two outlines (N, 2) mm at centre distance ``distance`` mm.

    Contacts are searched for at the vertices inside the box; edges are taken from the
    box widened by the margin. Its half-height is ``settings.window`` (mm) or, when
    that is None, ``settings.window_fraction`` times the smaller outer radius, the least
    it may be (DesignError naming ``window`` below it).
    """
    rp = float(np.hypot(pinion[:, 0], pinion[:, 1]).max())
    rw = float(np.hypot(wheel[:, 0], wheel[:, 1]).max())
    default = settings.window_fraction * min(rp, rw)
    half_height = default if settings.window is None else settings.window
    # contacts lie up to about that far from the line of centres (round the pitch-curve
    # corners too): a narrower window loses them and reports contact lost or a wrong band.
    # 1 % and 0.1 mm below are let through, so a window given at the design's default still
    # serves the band check's outlines grown by a printer's deviation (0.25 x at most 0.3 mm)
    least = 0.99 * default - 0.1
    require(half_height >= least, "window", half_height,
            f"must be >= {rounded_up(least)} mm (about {settings.window_fraction:g} x the smaller "
            "outer radius: a narrower window misses contacts)")
    # contacts lie between the wheel's tips (x = D - rw) and the pinion's (x = rp); the
    # margin keeps the outline round an overlapping vertex in view for its depth
    return MeshWindow(distance - rw - 1e-6, rp + 1e-6, float(half_height),
                      settings.window_margin * float(half_height))


def check_meshing(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                  settings: MeshingSettings = MeshingSettings(), start: float = 0.0,
                  progress: Callable[[int, int], None] | None = None,
                  teeth: int | None = None,
                  start_offset: Callable[[np.ndarray], np.ndarray] | None = None) -> MeshingReport:
    """Run the meshing check (SPEC §10) over one period of ``law`` (outlines that do not repeat
    every period, a print's, pass :class:`~wheelstep_cli.gears.cycle.WholeCycle` of it).

    ``pinion``, ``wheel``: closed outlines (N, 2) in mm in their own frames (any
    orientation). ``law``: read through ``carrier_angle`` (the wheel angle the pair
    should have), ``theta_period`` and ``hub_speed_factor``. ``distance``: installed
    centre distance (mm). ``settings.samples`` poses over the period (None:
    :func:`default_pose_count`), from ``start`` (rad). ``progress(done, total)`` is called
    after every batch of poses. ``teeth``: the pinion's tooth count (None: counted on its
    outline), which sets the tooth pitch, the band of the figures of merit and the default
    pose count. ``start_offset(theta)``: where each pose's contact search starts, in rad of
    wheel angle from the law's (None: at the law's angle; it must lie in the play, as the
    middle of a pair's play does); the contacts, and so the transmission error measured
    from the law, do not depend on it.
    """
    pinion = np.asarray(pinion, dtype=float)
    wheel = np.asarray(wheel, dtype=float)
    period = float(law.theta_period)
    if teeth is None:
        teeth = max(1, pair_teeth(pinion, None, law)[0])
    samples = default_pose_count(law, teeth) if settings.samples is None else settings.samples
    theta = start + period * np.arange(samples) / samples
    phi_law = np.asarray(law.carrier_angle(theta), dtype=float)
    phi_start = phi_law if start_offset is None else phi_law + np.asarray(start_offset(theta), dtype=float)
    box = mesh_window(pinion, wheel, distance, settings)
    make_pair = functools.partial(prepare, pinion, wheel, distance, box, settings)
    batch = max(1, min(settings.batch, settings.batch_points // (len(pinion) + len(wheel))))
    slices = [slice(lo, min(lo + batch, samples)) for lo in range(0, samples, batch)]
    contacts = _search(make_pair, theta, phi_start, slices, settings, progress)
    report = _report(law, theta, (phi_law, phi_start), contacts, float(distance), start, teeth)
    if settings.peak_rounds <= 0:
        return report
    return replace(report, peaks=_peaks(report, law, settings, _contacts_at(make_pair(), law, settings,
                                                                             start_offset)))


def _contacts_at(pair: Pair, law: TransmissionLaw, settings: MeshingSettings,
                 start_offset: Callable[[np.ndarray], np.ndarray] | None):
    """A function of pinion angles (rad) giving (the law's wheel angle, drive-side and
    coast-side contact angles) there, rad; NaN where the teeth overlap or none was found."""
    def contacts_at(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        phi_law = np.asarray(law.carrier_angle(theta), dtype=float)
        phi_start = phi_law if start_offset is None else phi_law + np.asarray(start_offset(theta), float)
        found = [batch_contacts(pair, theta[lo:lo + settings.batch], phi_start[lo:lo + settings.batch],
                                settings) for lo in range(0, len(theta), settings.batch)]
        back, fwd = (np.concatenate([getattr(f, name) for f in found]) for name in ("back", "fwd"))
        clear = ~np.concatenate([f.interference for f in found])
        drive = np.where(clear & np.isfinite(back), phi_start - back, np.nan)
        coast = np.where(clear & np.isfinite(fwd), phi_start + fwd, np.nan)
        return phi_law, drive, coast
    return contacts_at


def _peaks(report: MeshingReport, law: TransmissionLaw, settings: MeshingSettings,
           contacts_at) -> PeakPoses | None:
    """The poses measured round the TE's extremes that could raise F'i or f'i
    (gears.meshing.peaks), None when there are none."""
    period, distance = float(report.period), report.distance
    sides = {"drive": "phi_drive", "coast": "phi_coast"}
    te = {flank: getattr(report, side) - report.phi_law for flank, side in sides.items()}
    means = {flank: float(np.mean(values)) for flank, values in te.items()}
    errors = {"drive": report.drive.error_um, "coast": report.coast.error_um}
    rows = []

    def measure(theta: np.ndarray) -> dict[str, np.ndarray]:
        phi_law, drive, coast = contacts_at(theta)
        radius = distance / (1.0 + _law_rate(law, theta))
        rows.append((theta, phi_law, drive, coast, radius))
        return {flank: error_um(angle - phi_law, radius, means[flank])
                for flank, angle in (("drive", drive), ("coast", coast))}

    refine_peaks(report.theta, errors, report.track, settings.peak_rounds, measure)
    if not rows:
        return None
    theta, phi_law, drive, coast, radius = (np.concatenate(column) for column in zip(*rows))
    # the arc along the wheel pitch curve, taken back into the period the poses began
    start = float(report.theta[0])
    at = start + np.mod(theta - start, period)
    arc = np.interp(at, np.append(report.theta, start + period),
                    np.append(report.track.arc, report.track.arc_total))
    return PeakPoses(theta, phi_law, drive, coast, radius, arc)


def default_pose_count(law: TransmissionLaw, teeth: int) -> int:
    """The poses over one period of ``law`` that give a pinion of ``teeth`` teeth the default
    count (:func:`~wheelstep_cli.gears.meshing.settings.default_samples`) in its shortest
    tooth pitch. The teeth are equal arcs of the pitch curve, so a tooth spans less pinion
    angle where the curve runs faster (ds/dtheta largest): the period's average tooth pitch
    count is scaled by max / mean of ds/dtheta (about 1.64 for the crank law)."""
    period = float(law.theta_period)
    turn = np.linspace(0.0, 2.0 * np.pi, 4096, endpoint=False)
    radius = _pinion_pitch_radius(law, turn, 1.0)
    slope = np.gradient(np.concatenate([radius[-1:], radius, radius[:1]]), turn[1] - turn[0])[1:-1]
    speed = np.hypot(radius, slope)
    # a law that does not turn the wheel has no pitch curve: its teeth are counted evenly
    factor = float(speed.max() / speed.mean()) if speed.mean() > 0.0 else 1.0
    return default_samples(teeth * period / (2.0 * np.pi) * factor)


def _pinion_pitch_radius(law: TransmissionLaw, angle: np.ndarray, distance: float) -> np.ndarray:
    """The pinion's pitch radius (mm) at body angles ``angle`` (rad) at centre distance
    ``distance`` mm: the pitch point for theta lies at body angle theta."""
    rate = _law_rate(law, angle)
    return distance * rate / (1.0 + rate)


def pair_teeth(pinion: np.ndarray, wheel: np.ndarray | None,
               law: TransmissionLaw) -> tuple[int, int | None, float]:
    """(pinion teeth, wheel teeth, wheel teeth a pinion of those teeth needs) counted on two
    outlines (N, 2) mm in their own frames (``wheel`` None: its count None), each along the
    pitch curve of ``law`` scaled to the outline's radius by area, so that any distance the
    pair is mounted at counts alike. Over a period the pinion turns theta_P and the wheel
    the law's rise, so the wheel has z_p theta_P / |rise| teeth."""
    period = float(law.theta_period)
    ends = np.asarray(law.carrier_angle(np.array([0.0, period])), dtype=float)
    rise = max(abs(float(ends[1] - ends[0])), 1e-9)
    # pitch radius at unit centre distance: the pinion's at body angle theta, rate / (1 + rate)
    z_p = _teeth_along(pinion, lambda a: _pinion_pitch_radius(law, a, 1.0))
    if wheel is None:
        return z_p, None, z_p * period / rise
    # the wheel's pitch point for phi lies at body angle -phi, at D - r_p = D / (1 + rate):
    # sampled over the periods one wheel turn takes
    periods = int(np.ceil(2.0 * np.pi / rise)) + 1
    theta = np.linspace(0.0, periods * period, 4096 * periods, endpoint=False)
    body = np.mod(-np.asarray(law.carrier_angle(theta), dtype=float), 2.0 * np.pi)
    order = np.argsort(body, kind="stable")
    body, unit = body[order], (1.0 / (1.0 + _law_rate(law, theta)))[order]
    z_w = _teeth_along(wheel, lambda a: np.interp(a, body, unit, period=2.0 * np.pi))
    return z_p, z_w, z_p * period / rise


def _teeth_along(outline: np.ndarray, shape: Callable[[np.ndarray], np.ndarray]) -> int:
    """Teeth of an outline (N, 2) mm along the pitch curve of radius ``shape(angle)`` (body
    angle, rad), scaled so that it encloses the outline's area: teeth above and below it
    cancel, so the curve runs through the teeth at any mounted distance."""
    turn = np.linspace(0.0, 2.0 * np.pi, 4096, endpoint=False)
    rms = float(np.sqrt(np.mean(shape(turn) ** 2)))
    # a law that does not turn the wheel has no pitch curve to scale (radius 0 throughout)
    scale = radius_by_area(outline) / rms if rms > 0.0 else 1.0
    return count_teeth(outline, lambda a: scale * shape(a))


def radius_by_area(outline: np.ndarray) -> float:
    """sqrt(area / pi) of a closed outline (N, 2) mm: its teeth above and below the pitch
    curve cancel, so this is near the mean pitch radius."""
    x, y = outline[:, 0], outline[:, 1]
    return float(np.sqrt(abs(np.sum(x * np.roll(y, -1)) - np.sum(y * np.roll(x, -1))) / (2.0 * np.pi)))


def _law_rate(law: TransmissionLaw, theta: np.ndarray, step: float = 1e-6) -> np.ndarray:
    """dphi/dtheta of the law at pinion angles ``theta`` (rad), by a central difference of
    ``carrier_angle`` over +-``step`` rad (the check reads the law only through it)."""
    theta = np.asarray(theta, dtype=float)
    ahead = np.asarray(law.carrier_angle(theta + step), dtype=float)
    return (ahead - np.asarray(law.carrier_angle(theta - step), dtype=float)) / (2.0 * step)


def _search(make_pair: Callable[[], Pair], theta: np.ndarray, phi_law: np.ndarray,
            slices: list[slice], settings: MeshingSettings,
            progress: Callable[[int, int], None] | None) -> PoseContacts:
    """Contacts of every pose (``theta``, ``phi_law`` rad), the batches ``slices`` shared
    by threads; ``make_pair()`` prepares the outlines for one thread."""
    samples = len(theta)
    found = PoseContacts(np.empty(samples), np.empty(samples), np.zeros(samples, dtype=bool),
                         np.zeros(samples), np.zeros(samples))
    # batches are independent and numpy / shapely release the GIL in their loops: threads
    # share the work between cores; each batch fills its own slice, so the result is the same.
    # Each thread uses its own prepared outlines (a prepared polygon is not thread-safe); the
    # pilot's are handed on to the first thread that needs them.
    spare = [make_pair()]
    narrowed = replace(settings, reach=_pilot_reach(spare[0], theta, phi_law, settings))
    lock, own = threading.Lock(), threading.local()

    def run(sl):
        if not hasattr(own, "pair"):
            with lock:
                own.pair = spare.pop() if spare else None
            if own.pair is None:
                own.pair = make_pair()
        return batch_contacts(own.pair, theta[sl], phi_law[sl], narrowed)

    for sl, part in zip(slices, thread_map(run, slices, settings.threads)):
        for name in ("back", "fwd", "interference", "area", "depth"):
            getattr(found, name)[sl] = getattr(part, name)
        if progress is not None:
            progress(sl.stop, samples)
    return found


def _pilot_reach(pair: Pair, theta: np.ndarray, phi_law: np.ndarray, settings: MeshingSettings) -> float:
    """The first pass's reach (rad) for the poses ``theta``, ``phi_law`` (rad): ``settings.pilot``
    of them, spread evenly, are searched with ``settings.reach``; the reach is then
    ``settings.pilot_margin`` times their largest gap, within ``settings.reach`` / 16 ..
    ``settings.reach``.

    A first pass that looks farther than the contacts lie only finds more pairs to reject,
    and one that looks less far hands its poses to the second pass: both give the same
    contacts (search only), so the reach is sized to the pair's own gaps. Not below a
    sixteenth: the pass's angle bins are twice the reach wide, and teeth with next to no
    play (gaps of microradians) would have it sort into millions of them.
    """
    if settings.pilot <= 0 or not np.isfinite(settings.reach):
        return settings.reach
    index = np.unique(np.linspace(0, len(theta), settings.pilot, endpoint=False).astype(np.intp))
    found = batch_contacts(pair, theta[index], phi_law[index], settings)
    gaps = np.concatenate([found.back, found.fwd])
    gaps = gaps[np.isfinite(gaps) & (gaps > 0.0)]
    if len(gaps) == 0:
        return settings.reach
    return float(min(settings.reach, max(settings.reach / 16.0, settings.pilot_margin * gaps.max())))


def _periodic_derivative(theta: np.ndarray, values: np.ndarray, rise: float, period: float):
    """Central-difference d(values)/d(theta) over a period with values(theta + P) = values + rise."""
    ext_t = np.concatenate([[theta[-1] - period], theta, [theta[0] + period]])
    ext_v = np.concatenate([[values[-1] - rise], values, [values[0] + rise]])
    return np.gradient(ext_v, ext_t)[1:-1]


def _report(law: TransmissionLaw, theta: np.ndarray, phis: tuple[np.ndarray, np.ndarray],
            contacts: PoseContacts, distance: float, start: float, teeth: int) -> MeshingReport:
    """The report of the poses ``theta`` (rad) from their contacts, found from the wheel
    angles ``phis`` = (the law's, where each search started; rad), the pinion having
    ``teeth`` teeth."""
    phi_law, phi_start = phis
    period = float(law.theta_period)
    rise = float(law.carrier_angle(np.array([start + period]))[0]
                 - law.carrier_angle(np.array([start]))[0])
    delta_back = np.where(np.isfinite(contacts.back), contacts.back, np.nan)
    delta_fwd = np.where(np.isfinite(contacts.fwd), contacts.fwd, np.nan)
    phi_drive = phi_start - delta_back
    phi_coast = phi_start + delta_fwd
    f_drive = np.asarray(law.hub_speed_factor(phi_drive), dtype=float)
    f_law = np.asarray(law.hub_speed_factor(phi_law), dtype=float)
    hub_speed = f_drive * _periodic_derivative(theta, phi_drive, rise, period)
    law_rate = _law_rate(law, theta)
    # the law's own speed from its own rate: a difference over the pose step would read the
    # pitch curves' corners as ripple that shrinks only with the step
    hub_speed_law = f_law * law_rate
    # instantaneous centre on the line of centres: r_w / r_p = dtheta/dphi, r_w + r_p = D
    pitch_radius = distance / (1.0 + law_rate)
    arc, arc_total = pitch_arc(phi_law, pitch_radius, rise)
    per_period = teeth * period / (2.0 * np.pi)
    track = Track(period, phi_law, law_rate, pitch_radius, arc, arc_total, arc_total / per_period,
                  int(np.floor(BAND_HARMONICS * per_period + 1e-9)), law.hub_speed_factor)
    return MeshingReport(theta, phi_law, phi_drive, phi_coast, contacts.interference,
                         contacts.area, contacts.depth, hub_speed, hub_speed_law, pitch_radius,
                         distance, period, teeth, track)
