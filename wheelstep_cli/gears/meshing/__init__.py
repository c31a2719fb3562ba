"""Meshing check of two gear outlines (SPEC §10): contact, backlash, TE, hub speed ripple.

Law-agnostic (any :class:`~wheelstep_cli.gears.transmission.TransmissionLaw`), numpy,
polygon queries through :mod:`wheelstep_cli.geometry.planar`. Convention (both parts
face-up as printed, seen from +z): the pinion axis is at the origin, the wheel axis
at ``(D, 0)``. At pinion angle ``theta`` the pinion (outline in its own frame) is
rotated by ``-theta`` (clockwise) about the origin, the wheel by ``pi + phi(theta)``
(counter-clockwise) about ``(D, 0)``. So the pinion's pitch point for ``theta`` lies
at body angle ``+theta`` and the wheel's pitch point for ``phi`` at body angle ``-phi``.

The pinion drives. Under load the wheel lags: the **drive-side** contact is found
by rotating the wheel backwards (decreasing ``phi``) from the law's angle until its
outline first touches the pinion's; the **coast side** by rotating it forwards.
``TE = phi_drive - phi_law``; angular backlash ``= phi_coast - phi_drive``.

First contact between rotating polygons happens when a vertex of one meets an edge
of the other. Seen from the wheel axis, a wheel vertex at radius rho sweeps a circle
of that radius relative to the pinion and a pinion vertex sweeps a circle of its
radius relative to the wheel; intersecting those circles with the other outline's
edges gives, for every vertex/edge pair, the exact rotation to contact. Only the
vertices and edges inside the *mesh window* (a box round the line of centres,
between the two axes) take part.

Search (speed and memory only, the result is the same): pairs are found by sorting,
never in dense vertex x edge tables, and produced in bounded chunks. A first pass
looks only for contacts within ``MeshingSettings.reach`` rad (narrowed to a margin over
the gaps a pilot of a few poses found) and skips vertices and edges whose radial band
cannot meet the other outline that close; a pose not settled within the reach is
searched again over all pairs.

If the outlines overlap at the law's angle (a vertex of one lies inside the other),
the pose **interferes**; it is measured by the overlapping area (mm^2) and the
penetration depth (mm: the deepest such vertex's distance to the other outline).
Rigid teeth cannot take such a pose, so its contact angles are estimates: each
vertex inside counts as pressing on the flank it leaves by the smaller rotation
along its circle, giving a negative gap on that side (the drive side if it leaves
turning the wheel forwards). Summaries therefore also give the hub speed ripple
over the clear poses only.

Angles in radians, lengths in mm; degrees, arcminutes and % only in ``to_dict``.
"""

from wheelstep_cli.gears.meshing.check import check_meshing, mesh_window
from wheelstep_cli.gears.meshing.outlines import MeshWindow
from wheelstep_cli.gears.meshing.report import MeshingReport
from wheelstep_cli.gears.meshing.settings import MeshingSettings

__all__ = ["MeshWindow", "MeshingReport", "MeshingSettings", "check_meshing", "mesh_window"]
