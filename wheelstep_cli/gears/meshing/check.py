"""The meshing check over one period of a transmission law (SPEC §10).

Angles in radians, lengths in mm.
"""

from __future__ import annotations

import functools
import threading
from typing import Callable

import numpy as np

from wheelstep_cli.gears.meshing.outlines import MeshWindow
from wheelstep_cli.gears.meshing.report import MeshingReport
from wheelstep_cli.gears.meshing.search import Pair, PoseContacts, batch_contacts, prepare
from wheelstep_cli.gears.meshing.settings import MeshingSettings
from wheelstep_cli.gears.threads import thread_map
from wheelstep_cli.gears.transmission import TransmissionLaw


def mesh_window(pinion: np.ndarray, wheel: np.ndarray, distance: float,
                settings: MeshingSettings = MeshingSettings()) -> MeshWindow:
    """The mesh window of two outlines (N, 2) mm at centre distance ``distance`` mm.

    Contacts are searched for at the vertices inside the box; edges are taken from the
    box widened by the margin. Its half-height is ``settings.window`` (mm) or, when
    that is None, ``settings.window_fraction`` times the smaller outer radius.
    """
    rp = float(np.hypot(pinion[:, 0], pinion[:, 1]).max())
    rw = float(np.hypot(wheel[:, 0], wheel[:, 1]).max())
    half_height = settings.window
    if half_height is None:
        half_height = settings.window_fraction * min(rp, rw)
    # contacts lie between the wheel's tips (x = D - rw) and the pinion's (x = rp); the
    # margin keeps the outline round an overlapping vertex in view for its depth
    return MeshWindow(distance - rw - 1e-6, rp + 1e-6, float(half_height),
                      settings.window_margin * float(half_height))


def check_meshing(pinion: np.ndarray, wheel: np.ndarray, law: TransmissionLaw, distance: float,
                  settings: MeshingSettings = MeshingSettings(), start: float = 0.0,
                  progress: Callable[[int, int], None] | None = None) -> MeshingReport:
    """Run the meshing check (SPEC §10) over one period of ``law``.

    ``pinion``, ``wheel``: closed outlines (N, 2) in mm in their own frames (any
    orientation). ``law``: read through ``carrier_angle`` (the wheel angle the pair
    should have), ``theta_period`` and ``hub_speed_factor``. ``distance``: installed
    centre distance (mm). ``settings.samples`` poses over the period, from ``start``
    (rad). ``progress(done, total)`` is called after every batch of poses.
    """
    pinion = np.asarray(pinion, dtype=float)
    wheel = np.asarray(wheel, dtype=float)
    period = float(law.theta_period)
    samples = settings.samples
    theta = start + period * np.arange(samples) / samples
    phi_law = np.asarray(law.carrier_angle(theta), dtype=float)
    box = mesh_window(pinion, wheel, distance, settings)
    make_pair = functools.partial(prepare, pinion, wheel, distance, box, settings)
    batch = max(1, min(settings.batch, settings.batch_points // (len(pinion) + len(wheel))))
    slices = [slice(lo, min(lo + batch, samples)) for lo in range(0, samples, batch)]
    contacts = _search(make_pair, theta, phi_law, slices, settings, progress)
    return _report(law, theta, phi_law, contacts, float(distance), start)


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
    # Each thread prepares its own outlines (a prepared polygon is not thread-safe).
    own = threading.local()

    def run(sl):
        if not hasattr(own, "pair"):
            own.pair = make_pair()
        return batch_contacts(own.pair, theta[sl], phi_law[sl], settings)

    for sl, part in zip(slices, thread_map(run, slices, settings.threads)):
        for name in ("back", "fwd", "interference", "area", "depth"):
            getattr(found, name)[sl] = getattr(part, name)
        if progress is not None:
            progress(sl.stop, samples)
    return found


def _periodic_derivative(theta: np.ndarray, values: np.ndarray, rise: float, period: float):
    """Central-difference d(values)/d(theta) over a period with values(theta + P) = values + rise."""
    ext_t = np.concatenate([[theta[-1] - period], theta, [theta[0] + period]])
    ext_v = np.concatenate([[values[-1] - rise], values, [values[0] + rise]])
    return np.gradient(ext_v, ext_t)[1:-1]


def _report(law: TransmissionLaw, theta: np.ndarray, phi_law: np.ndarray, contacts: PoseContacts,
            distance: float, start: float) -> MeshingReport:
    """The report of the poses ``theta`` (rad) from their contacts."""
    period = float(law.theta_period)
    rise = float(law.carrier_angle(np.array([start + period]))[0]
                 - law.carrier_angle(np.array([start]))[0])
    delta_back = np.where(np.isfinite(contacts.back), contacts.back, np.nan)
    delta_fwd = np.where(np.isfinite(contacts.fwd), contacts.fwd, np.nan)
    phi_drive = phi_law - delta_back
    phi_coast = phi_law + delta_fwd
    f_drive = np.asarray(law.hub_speed_factor(phi_drive), dtype=float)
    f_law = np.asarray(law.hub_speed_factor(phi_law), dtype=float)
    hub_speed = f_drive * _periodic_derivative(theta, phi_drive, rise, period)
    law_rate = _periodic_derivative(theta, phi_law, rise, period)
    hub_speed_law = f_law * law_rate
    # instantaneous centre on the line of centres: r_w / r_p = dtheta/dphi, r_w + r_p = D
    pitch_radius = distance / (1.0 + law_rate)
    return MeshingReport(theta, phi_law, phi_drive, phi_coast, contacts.interference,
                         contacts.area, contacts.depth, hub_speed, hub_speed_law, pitch_radius,
                         distance, period)
