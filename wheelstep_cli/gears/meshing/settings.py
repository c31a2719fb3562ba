"""Settings of the meshing check (SPEC §10): what is measured and how the search runs.

Fields marked *search only* change the speed and memory of the check, never its
results (tests compare the fast search with the plain one bit for bit). The others
change what is measured. Change a value with :func:`dataclasses.replace`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from wheelstep_cli.gears.threads import THREADS

#: Poses per pinion tooth pitch the check samples by default (SPEC §10: at least 16).
POSES_PER_TOOTH = 16

#: The fewest poses over a period the check samples by default: more than 16 per tooth pitch
#: for most designs, which keeps their largest pose-to-pose TE step (a figure that shrinks
#: with the sampling) fine at a cost of about 2 s on two cores.
LEAST_SAMPLES = 1536


def default_samples(teeth_per_period: float) -> int:
    """The default pose count (whole batches of 64) over a period in which ``teeth_per_period``
    pinion tooth pitches pass: :data:`POSES_PER_TOOTH` each, at least :data:`LEAST_SAMPLES`.
    A non-circular pinion's shortest tooth pitch counts as more of them
    (:func:`~wheelstep_cli.gears.meshing.check.default_pose_count`)."""
    # a millionth off: a count read off a law by finite differences is not exact
    need = math.ceil(POSES_PER_TOOTH * teeth_per_period * (1.0 - 1e-6))
    return max(LEAST_SAMPLES, -(-need // 64) * 64)


@dataclass(frozen=True)
class MeshingSettings:
    """How the meshing check samples, windows and searches the poses of a pair."""

    samples: int | None = None
    """Poses over one period of the law (count); None: 16 in the pinion's shortest tooth
    pitch, at least 1536 (:func:`~wheelstep_cli.gears.meshing.check.default_pose_count`)."""

    window: float | None = None
    """Half-height (mm) of the mesh window round the line of centres; None: ``window_fraction``
    times the smaller gear's outer radius."""

    window_fraction: float = 0.25
    """Default half-height of the mesh window as a fraction of the smaller outer radius (1)."""

    window_margin: float = 0.25
    """Margin (fraction of the window's half-height) by which edges are taken from round
    the window, so the outline round an overlapping vertex stays in view for its depth."""

    long_edge: float = 0.1
    """Edges longer than this fraction of the window's half-height are tested in every pose
    instead of being found by angle (1). Search only: speed, not results."""

    batch: int = 64
    """Poses handled together in one vectorised batch (count; fewer for very large outlines).
    Search only: speed and memory, not results."""

    batch_points: int = 1_000_000
    """Most outline points (poses x points of both outlines) in one batch (count); bounds a
    batch's memory. Search only: memory, not results."""

    max_pairs: int = 1 << 19
    """Most vertex/edge candidate pairs held at once (count, about 100 bytes each in
    temporaries). Search only: memory, not results."""

    reach: float = 0.01
    """First pass (rad of wheel rotation): only contacts this close are looked for; poses
    with none that close are searched again without the limit. Search only: speed, not
    results (inf: one plain pass)."""

    pilot: int = 16
    """Poses (count, spread evenly over the period) searched first with ``reach``; the
    first pass of every pose then looks only ``pilot_margin`` times as far as the largest
    gap they found (at most ``reach``). 0: no pilot. Search only: speed, not results."""

    pilot_margin: float = 1.5
    """How far past the pilot's largest gap the first pass looks (ratio); a pose whose
    contact lies farther is searched again. Search only: speed, not results."""

    band_bins: int = 2048
    """Body-angle bins (count) of the radial bands that skip vertices and edges far from the
    other outline in the first pass. Search only: speed, not results."""

    overlap_area: bool = True
    """Measure each interfering pose's overlapping area (mm^2; False: not measured, the
    report gives none). The band's cases report depth and poses, not the area."""

    contacts_where_jammed: bool = True
    """Search the contacts of the poses whose outlines overlap at the start pose too (False:
    none there, their rotations to contact are NaN). Where rigid teeth cannot go the
    rotations are only penetration estimates: the band's cases report jam, poses and depth
    there, and give backlash and TE only where the teeth clear."""

    peak_rounds: int = 4
    """Bisection rounds (count) round each TE extreme that could raise F'i or f'i, between the
    equal-step poses (gears.meshing.peaks): the handover kinks lie between poses, and read
    off the poses alone the figures fall short of the continuous ones. 4 rounds pin a kink
    to a sixteenth of the step. 0: the equal-step poses only."""

    threads: int = THREADS
    """Threads (count) sharing the batches; each fills its own slice of the result.
    Search only: speed, not results."""
