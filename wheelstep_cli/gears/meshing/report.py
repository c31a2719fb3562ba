"""Results of the meshing check (SPEC §10): per-pose arrays and their summary.

Angles in radians, lengths in mm; degrees, arcminutes and % only in ``to_dict``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MeshingReport:
    """Per-pose results (arrays over the pinion angles ``theta``) and their summary.

    ``phi_law``, ``phi_drive``, ``phi_coast``: wheel angles (rad); NaN where no contact
    was found within the mesh window in that direction. ``interference``: per-pose
    overlap at the law's angle. ``overlap_area``: mm^2 per pose. ``penetration``: depth
    (mm) of the deepest vertex inside the other outline (0 when clear).
    ``hub_speed``: f(phi_drive) dphi_drive/dtheta (relative units), ``pitch_radius``:
    the wheel's instantaneous pitch radius (mm) at the installed distance.
    """

    theta: np.ndarray
    phi_law: np.ndarray
    phi_drive: np.ndarray
    phi_coast: np.ndarray
    interference: np.ndarray
    overlap_area: np.ndarray
    penetration: np.ndarray
    hub_speed: np.ndarray
    hub_speed_law: np.ndarray
    pitch_radius: np.ndarray
    distance: float
    period: float

    @property
    def transmission_error(self) -> np.ndarray:
        """phi_drive - phi_law (rad at the wheel)."""
        return self.phi_drive - self.phi_law

    @property
    def backlash(self) -> np.ndarray:
        """Angular backlash phi_coast - phi_drive (rad at the wheel)."""
        return self.phi_coast - self.phi_drive

    @property
    def backlash_mm(self) -> np.ndarray:
        """Backlash along the wheel's pitch curve (mm): pitch radius times angular backlash."""
        return self.pitch_radius * self.backlash

    @property
    def interferes(self) -> bool:
        """True when the outlines overlap at the law's angle at some pose."""
        return bool(np.any(self.interference))

    @property
    def contact_lost(self) -> bool:
        """True when at some pose no drive-side contact was found (teeth out of mesh)."""
        return bool(np.any(np.isnan(self.phi_drive)))

    @property
    def te_peak_to_peak(self) -> float:
        """Peak-to-peak transmission error (rad at the wheel)."""
        return _peak_to_peak(self.transmission_error)

    @property
    def te_max_step(self) -> float:
        """Largest change of TE between neighbouring poses (rad), the period wrapped.

        Shrinks with more samples while the drive-side motion is continuous; stays
        when the wheel jumps (contact hands over to a tooth that was not touching).
        Then the hub speed has spikes that grow with the sample count, and the ripple
        only means "at this sampling".
        """
        te = self.transmission_error
        return float(np.nanmax(np.abs(np.diff(np.append(te, te[:1])))))

    @property
    def hub_speed_ripple(self) -> float:
        """Peak-to-peak over mean of the hub speed from the drive-side contact (fraction)."""
        return _peak_to_peak(self.hub_speed) / float(np.nanmean(self.hub_speed))

    @property
    def clear(self) -> np.ndarray:
        """Poses whose hub speed comes from clear contact: neither they nor a neighbour interfere."""
        bad = self.interference | np.isnan(self.phi_drive)
        return ~(bad | np.roll(bad, 1) | np.roll(bad, -1))

    @property
    def hub_speed_ripple_clear(self) -> float:
        """Hub speed ripple (fraction) over the clear poses only; NaN if there are none.

        Where outlines overlap, the drive contact is a penetration estimate, not a
        motion; this figure shows what the teeth do where they do mesh.
        """
        clear = self.clear
        if not clear.any():
            return float("nan")
        v = self.hub_speed[clear]
        return _peak_to_peak(v) / float(np.nanmean(v))

    def to_dict(self) -> dict:
        """Summary in degrees, arcminutes, mm and % for JSON and tables."""
        arcmin = 60.0 * 180.0 / np.pi
        te = self.transmission_error
        return {
            "distance_mm": self.distance,
            "samples": int(len(self.theta)),
            "period_deg": float(np.degrees(self.period)),
            "interference": self.interferes,
            "interfering_poses": int(np.count_nonzero(self.interference)),
            "max_overlap_area_mm2": float(self.overlap_area.max()),
            "max_penetration_mm": float(self.penetration.max()),
            "contact_lost": self.contact_lost,
            "backlash_min_arcmin": _nan_none(np.nanmin(self.backlash) * arcmin),
            "backlash_max_arcmin": _nan_none(np.nanmax(self.backlash) * arcmin),
            "backlash_min_mm": _nan_none(np.nanmin(self.backlash_mm)),
            "backlash_max_mm": _nan_none(np.nanmax(self.backlash_mm)),
            "te_min_arcmin": _nan_none(np.nanmin(te) * arcmin),
            "te_max_arcmin": _nan_none(np.nanmax(te) * arcmin),
            "te_peak_to_peak_arcmin": _nan_none(self.te_peak_to_peak * arcmin),
            "te_max_step_arcmin": _nan_none(self.te_max_step * arcmin),
            "hub_speed_ripple_pct": _nan_none(100.0 * self.hub_speed_ripple),
            "hub_speed_ripple_clear_pct": _nan_none(100.0 * self.hub_speed_ripple_clear),
            "clear_poses": int(np.count_nonzero(self.clear)),
            "law_hub_speed_ripple_pct": float(
                100.0 * _peak_to_peak(self.hub_speed_law) / np.mean(self.hub_speed_law)),
        }


def _peak_to_peak(values: np.ndarray) -> float:
    """Greatest minus least value, NaNs ignored (NaN when all are)."""
    if np.all(np.isnan(values)):
        return float("nan")
    return float(np.nanmax(values) - np.nanmin(values))


def _nan_none(value: float) -> float | None:
    """The value as a float, None when not finite (for JSON)."""
    return None if not np.isfinite(value) else float(value)
