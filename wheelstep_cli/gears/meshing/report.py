"""Results of the meshing check (SPEC §10): per-pose arrays and their summary.

Angles in radians, lengths in mm; degrees, arcminutes and % only in ``to_dict``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from wheelstep_cli.gears.meshing.figures import FlankFigures, Track, flank_figures
from wheelstep_cli.gears.meshing.peaks import PeakPoses


@dataclass(frozen=True)
class MeshingReport:
    """Per-pose results (arrays over the pinion angles ``theta``) and their summary.

    ``phi_law``, ``phi_drive``, ``phi_coast``: wheel angles (rad); NaN where no contact
    was found within the mesh window in that direction. ``interference``: per-pose
    overlap at the law's angle. ``overlap_area``: mm^2 per pose (NaN when not measured:
    MeshingSettings.overlap_area). ``penetration``: depth (mm) of the deepest vertex inside
    the other outline (0 when clear).
    ``hub_speed``: f(phi_drive) dphi_drive/dtheta (relative units), pointwise (a
    diagnostic: it has no limit as the poses grow), ``pitch_radius``: the wheel's
    instantaneous pitch radius (mm) at the installed distance. ``teeth``: the pinion's
    tooth count; ``track``: what the figures of merit of both flanks share (SPEC §10).
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
    teeth: int
    track: Track
    mounting: dict | None = None   # how much closer it may be mounted (parts.mesh_check), mm
    peaks: PeakPoses | None = None  # poses measured between the equal steps round the TE's peaks

    @cached_property
    def drive(self) -> FlankFigures:
        """Figures of merit of the drive flank (SPEC §10): F'i, f'i, band-limited ripple."""
        return flank_figures(self.transmission_error, self.track, self._between("phi_drive"))

    @cached_property
    def coast(self) -> FlankFigures:
        """Figures of merit of the coast flank (SPEC §10), its TE phi_coast - phi_law."""
        return flank_figures(self.phi_coast - self.phi_law, self.track, self._between("phi_coast"))

    def _between(self, side: str) -> tuple | None:
        """(TE rad, pitch radius mm, arc mm) of ``side`` at the peaks' poses, None without them."""
        if self.peaks is None:
            return None
        return (getattr(self.peaks, side) - self.peaks.phi_law, self.peaks.pitch_radius, self.peaks.arc)

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
        return _most(np.abs(np.diff(np.append(te, te[:1]))))

    @property
    def hub_speed_ripple(self) -> float:
        """Pointwise peak-to-peak over mean of the hub speed from the drive-side contact
        (fraction): a diagnostic that grows with the sampling (SPEC §10)."""
        if np.all(np.isnan(self.hub_speed)):
            return float("nan")
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

    def _in_phase(self, drive: dict) -> bool:
        """Whether the pair follows its law in phase: no interference, contact kept, and the
        drive flank's total transmission error F'i under a quarter of the tooth pitch (a pair
        assembled a tooth off crashes or wanders by about a pitch from the law)."""
        total = drive.get("F_i_total_um")
        return bool(not self.interferes and not self.contact_lost and total is not None
                    and total < 250.0 * self.track.pitch)

    def to_dict(self) -> dict:
        """Summary in degrees, arcminutes, mm, um and % for JSON and tables: the figures of
        merit per flank side (``drive``, ``coast``), backlash band, interference, and the
        pointwise ripple labelled as a diagnostic."""
        arcmin = 60.0 * 180.0 / np.pi
        law_ripple = _peak_to_peak(self.hub_speed_law) / float(np.mean(self.hub_speed_law))
        drive = _flank_dict(self.drive, self.transmission_error * arcmin)
        summary = {
            "distance_mm": self.distance,
            "samples": int(len(self.theta)),
            "peak_poses": 0 if self.peaks is None else int(len(self.peaks.theta)),
            "period_deg": float(np.degrees(self.period)),
            "pinion_teeth": int(self.teeth),
            "tooth_pitch_mm": self.track.pitch,
            "band_harmonics": self.track.harmonics,
            "interference": self.interferes,
            "interfering_poses": int(np.count_nonzero(self.interference)),
            "max_overlap_area_mm2": _nan_none(float(np.max(self.overlap_area))),
            "max_penetration_mm": float(self.penetration.max()),
            "contact_lost": self.contact_lost,
            "backlash_min_arcmin": _nan_none(_least(self.backlash) * arcmin),
            "backlash_max_arcmin": _nan_none(_most(self.backlash) * arcmin),
            "backlash_min_mm": _nan_none(_least(self.backlash_mm)),
            "backlash_max_mm": _nan_none(_most(self.backlash_mm)),
            "drive": drive,
            "in_phase": self._in_phase(drive),
            "coast": _flank_dict(self.coast, (self.phi_coast - self.phi_law) * arcmin),
            "diagnostic_pointwise_ripple_pct": _nan_none(100.0 * self.hub_speed_ripple),
            "diagnostic_pointwise_ripple_clear_pct": _nan_none(
                100.0 * self.hub_speed_ripple_clear),
            "clear_poses": int(np.count_nonzero(self.clear)),
            "law_hub_speed_ripple_pct": float(100.0 * law_ripple),
        }
        if self.mounting is not None:
            summary["mounting"] = dict(self.mounting)
        return summary


def _flank_dict(figures: FlankFigures, te_arcmin: np.ndarray) -> dict:
    """One flank side's figures (um, %, arcmin) for JSON."""
    return {
        "F_i_total_um": _nan_none(figures.total_um),
        "f_i_tooth_um": _nan_none(figures.tooth_um),
        "hub_speed_ripple_pct": _nan_none(100.0 * figures.ripple),
        "te_max_step_um": _nan_none(figures.max_step_um),
        "te_min_arcmin": _nan_none(_least(te_arcmin)),
        "te_max_arcmin": _nan_none(_most(te_arcmin)),
    }


def _peak_to_peak(values: np.ndarray) -> float:
    """Greatest minus least value, NaNs ignored (NaN when all are)."""
    return _most(values) - _least(values)


def _least(values: np.ndarray) -> float:
    """The least value, NaNs ignored (NaN when all are: a check that searched no pose)."""
    return float("nan") if np.all(np.isnan(values)) else float(np.nanmin(values))


def _most(values: np.ndarray) -> float:
    """The greatest value, NaNs ignored (NaN when all are)."""
    return float("nan") if np.all(np.isnan(values)) else float(np.nanmax(values))


def _nan_none(value: float) -> float | None:
    """The value as a float, None when not finite (for JSON)."""
    return None if not np.isfinite(value) else float(value)
