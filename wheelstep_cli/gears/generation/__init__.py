"""Generated (conjugate) teeth for a non-circular pair (SPEC §9).

The pinion is cut by a straight-sided rack (pressure angle alpha, tip fillet)
whose pitch line rolls without slip on the pinion's pitch curve; at a pitch-curve
corner the rack pivots about the corner point through part of the turn from each
side (GenerationSettings.pivot), leaving a ridge in the corner space that hands the
drive over sooner.
The pinion's tip corners are rounded (a sharp corner drives as a point), its pointed
corner teeth topped, and that outline, as written, cuts the wheel moving along the
exact law ("rotate and carve"): the wheel's outline is the blank minus the union of
the pinion's poses and of the paths its outline points run between poses, in the
wheel frame, so the pair is conjugate by construction, including the concave notch
at each shoe handover.

Backlash: the pinion's teeth are thinned by j_n/2 (the rack tooth is thickened),
and the wheel's by a constant angular play worth j_n/2 at its mean pitch radius (or,
with backlash_mode "normal", by carving with the pinion dilated by j_n/2 along its
normals), so the total normal backlash at the design centre distance is about j_n. Opening the centre distance adds about 2 dL sin(alpha).

Modules: ``settings`` (GenerationSettings), ``rack`` (the cutter and its poses),
``pinion`` (cut by the rack), ``wheel`` (carved by the pinion), ``limits`` (undercut,
pointed teeth), ``outline`` (blanks, simplification), ``envelope`` (polar ray maps),
``pair`` (generate_pair). Angles in radians, lengths in mm.
"""

from wheelstep_cli.gears.generation.envelope import PolarGrid, polyline_envelope
from wheelstep_cli.gears.generation.limits import curvature_radius, top_pointed_teeth, undercut_limit
from wheelstep_cli.gears.generation.outline import blank_radii, simplify_outline
from wheelstep_cli.gears.generation.pair import GeneratedPair, generate_pair, generate_pinion
from wheelstep_cli.gears.generation.pinion import pinion_by_rack, round_tips
from wheelstep_cli.gears.generation.rack import RackCutter, RackRolling, rack_profile, rack_tooth_polygons, radial_tilt
from wheelstep_cli.gears.generation.settings import BACKLASH_MODES, CORNER_MODES, GenerationSettings
from wheelstep_cli.gears.generation.wheel import Carving, carve_by_pinion

__all__ = [
    "BACKLASH_MODES", "CORNER_MODES", "Carving", "GeneratedPair", "GenerationSettings", "PolarGrid",
    "RackCutter", "RackRolling", "blank_radii", "carve_by_pinion", "curvature_radius", "generate_pair",
    "generate_pinion",
    "pinion_by_rack", "polyline_envelope", "rack_profile", "rack_tooth_polygons", "radial_tilt",
    "round_tips", "simplify_outline", "top_pointed_teeth", "undercut_limit",
]
