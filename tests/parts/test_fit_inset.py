"""A fit's inset (parts.gear_pair.inset_gear_pair): the written pair is the design's outlines
offset along their normals, as its meshes say, and still one printable body per gear."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from wheelstep_cli.config.specs import GearPairSpec
from wheelstep_cli.geometry.solids import section_outline
from wheelstep_cli.parts.gear_pair import build_gear_pair, inset_gear_pair


@pytest.fixture(scope="module")
def design():
    return build_gear_pair(GearPairSpec(z=24, thickness=4.0))


@pytest.mark.parametrize("inset", [0.08, -0.03])
def test_the_written_sections_are_the_design_outlines_offset_along_their_normals(design, inset):
    fitted = inset_gear_pair(design, inset)
    assert fitted.inset == pytest.approx(inset) and fitted.spec == design.spec
    mid = 0.5 * float(design.spec.thickness)
    for part, outline in ((fitted.pinion, design.pinion_outline), (fitted.wheel, design.wheel_outline)):
        section = shapely.Polygon(section_outline(part.vertices, part.faces, part.name, mid))
        drawn = shapely.Polygon(outline)
        # every point of the written section lies |inset| from the design outline, to 1 um
        # (the section's thinning is 0.5 um): inside it for an inset, outside for a growth
        distances = [drawn.exterior.distance(shapely.Point(p)) for p in section.exterior.coords[::7]]
        assert np.allclose(distances, abs(inset), atol=1e-3)
        assert (section.area < drawn.area) == (inset > 0)
        # the plate rebuilt round the new outline: its own volume check, not the design's
        assert fitted.checks[part.name].expected_volume != design.checks[part.name].expected_volume
